#pragma once
// The one exception type of scene loading. what() is always a single line,
//   <file>: <json path>: <value>: <what was expected>
// so the CLI can print it as is and scripts can grep it.
#include <stdexcept>
#include <string>
#include <string_view>

namespace rtsph {

class SceneError : public std::runtime_error {
 public:
  SceneError(std::string_view source, std::string_view path, std::string_view value,
             std::string_view expected);
  /// For errors that have no JSON path (missing file, malformed JSON); still made one line.
  SceneError(std::string_view source, std::string_view message);
};

}  // namespace rtsph
