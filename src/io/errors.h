#pragma once
// Exceptions of the io layer. Messages are one line and name the file, so the CLI can print
// them as they are.
#include <stdexcept>

namespace rtsph::io {

/// A file could not be created, written, renamed or read.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A checkpoint exists but cannot be used: corrupt, truncated or from another scene.
class CheckpointError : public IoError {
 public:
  using IoError::IoError;
};

}  // namespace rtsph::io
