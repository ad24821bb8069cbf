#include "scene/override_path.h"

#include <fmt/format.h>

#include <charconv>
#include <optional>

#include "scene/params.h"
#include "scene/scene_error.h"
#include "scene/values.h"

namespace rtsph::scene_detail {
namespace {

struct Token {
  std::string name;                 // empty for an index
  std::size_t index = 0;
};

// "obstacles[0].motion.keyframes[1].time" -> tokens, and the generic key with the indices
// removed ("obstacles[].motion.keyframes[].time") used to find the parameter.
std::optional<std::vector<Token>> tokenize(const std::string& key, std::string& generic) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < key.size()) {
    const std::size_t end = key.find_first_of(".[", i);
    const std::string name = key.substr(i, end - i);
    if (name.empty()) return std::nullopt;
    tokens.push_back({name});
    generic += name;
    i = end;
    while (i < key.size() && key[i] == '[') {
      const std::size_t close = key.find(']', i);
      if (close == std::string::npos) return std::nullopt;
      std::size_t index = 0;
      const auto [ptr, ec] = std::from_chars(key.data() + i + 1, key.data() + close, index);
      if (ec != std::errc() || ptr != key.data() + close) return std::nullopt;
      tokens.push_back({"", index});
      generic += "[]";
      i = close + 1;
    }
    if (i < key.size()) {
      if (key[i] != '.') return std::nullopt;
      generic += '.';
      ++i;
      if (i == key.size()) return std::nullopt;
    }
  }
  if (tokens.empty()) return std::nullopt;
  return tokens;
}

template <class Owner>
void add_keys(std::vector<std::pair<std::string, const ParamMeta*>>& out, const std::string& prefix,
              const std::vector<FieldInfo<Owner>>& table) {
  for (const auto& f : table) out.emplace_back(prefix + f.key, &f);
}

const std::vector<std::pair<std::string, const ParamMeta*>>& all_keys() {
  static const auto keys = [] {
    std::vector<std::pair<std::string, const ParamMeta*>> k;
    add_keys(k, "", parameter_table());
    add_keys(k, "fluid_blocks[].", fluid_block_fields());
    add_keys(k, "obstacles[].", obstacle_fields());
    add_keys(k, "obstacles[]." + keyframes_array().key + "[].", keyframe_fields());
    add_keys(k, "emitters[].", emitter_fields());
    return k;
  }();
  return keys;
}

std::optional<Json> try_parse(const std::string& text) {
  try {
    return Json::parse(text, [](int depth, nlohmann::json::parse_event_t, Json&) {
      if (depth > 4) throw std::length_error("nesting");
      return true;
    });
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Anything that does not parse as the expected JSON becomes a string, so the reader reports
// it with the parameter's usual "expected ..." message.
Json value_json(const ParamMeta& m, const std::string& value) {
  if (m.kind == ParamKind::String || m.kind == ParamKind::Enum) {
    if (value.size() >= 2 && value.front() == '"')
      if (auto j = try_parse(value)) return *j;
    return value;
  }
  if (auto j = try_parse(value); j && (m.kind != ParamKind::Vec3 || j->is_array() || j->is_number()))
    return *j;  // a lone number is a 2D rotation rate, or a wrong length the reader reports
  if (m.kind == ParamKind::Vec3)
    if (auto j = try_parse("[" + value + "]")) return *j;
  return value;
}

}  // namespace

void set_override(Json& doc, const std::string& key, const std::string& value,
                  const std::string& source) {
  std::string generic;
  const auto tokens = tokenize(key, generic);
  const ParamMeta* meta = nullptr;
  for (const auto& [k, m] : all_keys())
    if (tokens && k == generic) meta = m;
  if (!meta) {
    std::vector<std::string> keys;
    for (const auto& [k, m] : all_keys()) keys.push_back(k);
    const std::string near = nearest_key(tokens ? generic : key, keys);
    throw SceneError(source, key, value,
                     near.empty() ? "unknown key" : "unknown key; did you mean " + near + "?");
  }
  Json* node = &doc;
  std::string walked;
  for (const Token& t : *tokens) {
    if (t.name.empty()) {
      if (!node->is_array() || t.index >= node->size())
        throw SceneError(source, key, value,
                         fmt::format("no element {} in {}: it has {}", t.index, walked,
                                     node->is_array() ? node->size() : 0));
      node = &(*node)[t.index];
      walked += fmt::format("[{}]", t.index);
    } else {
      if (!node->is_object()) *node = Json::object();
      node = &(*node)[t.name];
      walked += (walked.empty() ? "" : ".") + t.name;
    }
  }
  *node = value_json(*meta, value);
}

}  // namespace rtsph::scene_detail
