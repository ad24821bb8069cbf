#include "io/frame_index.h"

#include <charconv>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "io/atomic_file.h"

namespace rtsph::io {
namespace {

constexpr const char* kHeader = "frame,time_s,file";

template <class T>
bool parse_number(std::string_view s, T& out) {
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

std::string frame_file_name(int frame, const std::string& extension) {
  return fmt::format("frame_{:06d}.{}", frame, extension);
}

std::vector<IndexEntry> read_index(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError(fmt::format("cannot read '{}'", file.string()));
  std::vector<IndexEntry> entries;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1) {
      if (line != kHeader) throw IoError(fmt::format("{}:1: expected header '{}'", file.string(), kHeader));
      continue;
    }
    if (line.empty()) continue;
    auto c1 = line.find(','), c2 = line.find(',', c1 == std::string::npos ? c1 : c1 + 1);
    IndexEntry e;
    if (c1 == std::string::npos || c2 == std::string::npos ||
        !parse_number(std::string_view(line).substr(0, c1), e.frame) ||
        !parse_number(std::string_view(line).substr(c1 + 1, c2 - c1 - 1), e.time_s) || c2 + 1 == line.size()) {
      throw IoError(fmt::format("{}:{}: expected 'frame,time_s,file'", file.string(), line_no));
    }
    e.file = line.substr(c2 + 1);
    entries.push_back(std::move(e));
  }
  if (line_no == 0) throw IoError(fmt::format("{}: empty file", file.string()));
  return entries;
}

FrameIndex::FrameIndex(std::filesystem::path dir, bool resume) : dir_(std::move(dir)) {
  auto file = dir_ / "index.csv";
  if (resume && std::filesystem::exists(file)) entries_ = read_index(file);
}

void FrameIndex::add(int frame, double time_s, std::string file) {
  std::erase_if(entries_, [&](const IndexEntry& e) { return e.frame >= frame; });
  entries_.push_back({frame, time_s, std::move(file)});
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n", kHeader);
  // {} is the shortest text that reads back as the same double.
  for (const auto& e : entries_) fmt::format_to(std::back_inserter(out), "{},{},{}\n", e.frame, e.time_s, e.file);
  write_file_atomic(dir_ / "index.csv", std::string_view(out.data(), out.size()));
}

}  // namespace rtsph::io
