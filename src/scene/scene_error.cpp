#include "scene/scene_error.h"

#include <fmt/format.h>

namespace rtsph {
namespace {

// Control characters would break the one-line contract (and could be used to forge extra
// lines in logs), so they are written as escapes.
std::string one_line(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) {
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
    else out += char(c);
  }
  return out;
}

}  // namespace

SceneError::SceneError(std::string_view source, std::string_view path, std::string_view value,
                       std::string_view expected)
    : std::runtime_error(one_line(fmt::format("{}: {}: {}: {}", source, path, value, expected))) {}

SceneError::SceneError(std::string_view source, std::string_view message)
    : std::runtime_error(one_line(fmt::format("{}: {}", source, message))) {}

}  // namespace rtsph
