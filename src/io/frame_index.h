#pragma once
// DIR/index.csv: the frames of a run that are complete on disk, in the order written. Readers
// (scripts, the viewer's replay) trust it instead of globbing, so a half-written frame from a
// killed run is never listed.
#include <filesystem>
#include <string>
#include <vector>

namespace rtsph::io {

struct IndexEntry {
  int frame = 0;
  double time_s = 0;
  std::string file;  // relative to the index's directory
};

/// "frame_000042.vtp" for (42, "vtp").
std::string frame_file_name(int frame, const std::string& extension);

/// Parses an index.csv; throws IoError naming the file and line on malformed content.
std::vector<IndexEntry> read_index(const std::filesystem::path& file);

class FrameIndex {
 public:
  /// With `resume`, starts from DIR/index.csv if it exists; otherwise starts empty.
  FrameIndex(std::filesystem::path dir, bool resume);
  /// Records a frame whose file is complete and rewrites index.csv atomically. Entries at or
  /// after `frame` are dropped first, so a rewound or resumed run never lists stale frames.
  void add(int frame, double time_s, std::string file);
  const std::vector<IndexEntry>& entries() const { return entries_; }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::vector<IndexEntry> entries_;
};

}  // namespace rtsph::io
