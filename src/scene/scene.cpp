#include "scene/scene.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "scene/checks.h"
#include "scene/json_reader.h"
#include "scene/override_path.h"

namespace rtsph {
namespace {

using scene_detail::Json;

// Scene files are a few kilobytes; anything this large is a mistake (or an attack on memory).
constexpr std::uintmax_t kMaxFileBytes = 16u << 20;

SimSpec validated(const Json& doc, const std::string& source) {
  SimSpec spec = scene_detail::spec_from_json(doc, source);
  scene_detail::check_geometry(spec, source);
  scene_detail::check_memory(spec, source, scene_detail::physical_memory_bytes());
  return spec;
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, "is a directory; expected a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, fmt::format("cannot read file: {}", std::strerror(errno)));
  std::string text(kMaxFileBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  if (in.bad()) throw SceneError(path, fmt::format("cannot read file: {}", std::strerror(errno)));
  text.resize(std::size_t(in.gcount()));
  if (text.size() > kMaxFileBytes)
    throw SceneError(path, fmt::format("larger than {} MiB; expected a scene file", kMaxFileBytes >> 20));
  return text;
}

std::string builtin_names() {
  std::string names;
  for (const auto& [name, _] : builtin_scenes()) names += (names.empty() ? "" : ", ") + name;
  return names;
}

}  // namespace

SimSpec parse_scene(const std::string& text, const std::string& source) {
  return validated(scene_detail::parse_json_text(text, source), source);
}

SimSpec load_scene(const std::string& name_or_path) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(name_or_path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw SceneError(name_or_path, fmt::format("cannot read file: {}", ec.message()));
  if (exists) return parse_scene(read_file(name_or_path), name_or_path);
  if (std::string text = builtin_scene_text(name_or_path); !text.empty())
    return parse_scene(text, name_or_path);
  throw SceneError(name_or_path,
                   fmt::format("no such file or built-in scene (built-ins: {})", builtin_names()));
}

void apply_override(SimSpec& spec, const std::string& assignment, const std::string& source) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError(source, assignment, eq == 0 ? "(no key)" : "(no value)",
                     "expected key=value, e.g. fluid.spacing=0.01");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  Json doc = scene_detail::spec_to_json(spec);
  scene_detail::set_override(doc, key, value, source);
  spec = validated(doc, source);
}

std::string scene_to_json(const SimSpec& spec) {
  return scene_detail::spec_to_json(spec).dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace rtsph
