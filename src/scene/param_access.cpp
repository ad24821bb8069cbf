// Reading and writing single SimSpec parameters by key: what `--set` and the viewer's sliders use.
#include <cstdlib>

#include "scene/params.h"
#include "scene/scene_error.h"
#include "scene/values.h"

namespace rtsph {
namespace {

using scene_detail::expected_text;
using scene_detail::format_number;

constexpr std::string_view kSource = "--set";

struct Resolved {
  const ParamInfo* param;
  int component;  // -1: the whole parameter; 0..2: x, y, z of a Vec3
};

Resolved resolve(std::string_view key) {
  if (const ParamInfo* p = find_param(key)) return {p, -1};
  const auto dot = key.rfind('.');
  if (dot != std::string_view::npos && key.size() == dot + 2) {
    const ParamInfo* p = find_param(key.substr(0, dot));
    const int c = key[dot + 1] - 'x';
    if (p && p->kind == ParamKind::Vec3 && c >= 0 && c < 3) return {p, c};
  }
  std::vector<std::string> keys;
  for (const auto& p : parameter_table()) keys.push_back(p.key);
  const std::string near = scene_detail::nearest_key(key, keys);
  throw SceneError(kSource, key, "", near.empty() ? "unknown parameter"
                                                  : "unknown parameter, did you mean " + near + "?");
}

bool parse_number(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == sep) parts.push_back(text.substr(start, i - start)), start = i + 1;
  return parts;
}

void check_number(const ParamMeta& m, std::string_view key, double v, const std::string& shown,
                  int dimension) {
  if (!scene_detail::number_fits(m, v))
    throw SceneError(kSource, key, shown, expected_text(m, dimension));
}

}  // namespace

double get_param(const SimSpec& spec, std::string_view key) {
  const Resolved r = resolve(key);
  const ParamInfo& p = *r.param;
  if (r.component >= 0) return p.get_vec(spec)[r.component];
  if (p.get) return p.get(spec);
  if (p.kind == ParamKind::Enum) return scene_detail::choice_index(p, p.get_text(spec), spec.dimension);
  throw SceneError(kSource, key, "", "is not a number; use get_param_text");
}

void set_param(SimSpec& spec, std::string_view key, double value) {
  const Resolved r = resolve(key);
  const ParamInfo& p = *r.param;
  if (r.component >= 0 || p.kind == ParamKind::Real || p.kind == ParamKind::Int)
    check_number(p, key, value, format_number(value), spec.dimension);
  if (p.kind == ParamKind::Bool && value != 0 && value != 1)
    throw SceneError(kSource, key, format_number(value), "expected 0 or 1");
  if (r.component >= 0) {
    Vec3d v = p.get_vec(spec);
    v[r.component] = value;
    p.set_vec(spec, v);
  } else if (p.kind == ParamKind::Enum) {
    const auto& choices = p.choices_for(spec.dimension);
    if (value != int(value) || value < 0 || value >= double(choices.size()))
      throw SceneError(kSource, key, format_number(value), expected_text(p, spec.dimension));
    if (p.set) p.set(spec, value);
    else p.set_text(spec, choices[std::size_t(value)]);
  } else if (p.set) {
    p.set(spec, value);
  } else {
    throw SceneError(kSource, key, format_number(value), expected_text(p, spec.dimension));
  }
}

std::string get_param_text(const SimSpec& spec, std::string_view key) {
  const Resolved r = resolve(key);
  const ParamInfo& p = *r.param;
  if (r.component >= 0) return format_number(p.get_vec(spec)[r.component]);
  switch (p.kind) {
    case ParamKind::Real:
    case ParamKind::Int: return format_number(p.get(spec));
    case ParamKind::Bool: return p.get(spec) != 0 ? "true" : "false";
    case ParamKind::String: return p.get_text(spec);
    case ParamKind::Enum:
      return p.get_text ? p.get_text(spec)
                        : p.choices_for(spec.dimension).at(std::size_t(p.get(spec)));
    case ParamKind::Vec3: break;
  }
  const Vec3d v = p.get_vec(spec);
  if (p.z_only_in_2d && spec.dimension == 2) return format_number(v[2]);
  std::string s;
  for (int i = 0; i < spec.dimension; ++i) {
    if (i) s += ',';
    s += format_number(v[i]);
  }
  return s;
}

void set_param_text(SimSpec& spec, std::string_view key, const std::string& value) {
  const Resolved r = resolve(key);
  const ParamInfo& p = *r.param;
  const std::string expected = expected_text(p, spec.dimension);
  double x = 0;
  if (r.component >= 0 || p.kind == ParamKind::Real || p.kind == ParamKind::Int) {
    if (!parse_number(value, x)) throw SceneError(kSource, key, value, expected);
    return set_param(spec, key, x);
  }
  switch (p.kind) {
    case ParamKind::Bool:
      if (value != "true" && value != "false") throw SceneError(kSource, key, value, expected);
      return p.set(spec, value == "true" ? 1 : 0);
    case ParamKind::String:
      if (value.empty()) throw SceneError(kSource, key, value, expected);
      return p.set_text(spec, value);
    case ParamKind::Enum: {
      const int i = scene_detail::choice_index(p, value, spec.dimension);
      if (i < 0) throw SceneError(kSource, key, value, expected);
      return set_param(spec, key, i);
    }
    default: break;
  }
  if (p.z_only_in_2d && spec.dimension == 2) {
    if (!parse_number(value, x)) throw SceneError(kSource, key, value, expected);
    return set_param(spec, std::string(key) + ".z", x);
  }
  std::string inner = value;
  if (inner.size() >= 2 && inner.front() == '[' && inner.back() == ']')
    inner = inner.substr(1, inner.size() - 2);
  const auto parts = split(inner, ',');
  if (int(parts.size()) != spec.dimension) throw SceneError(kSource, key, value, expected);
  Vec3d v = p.get_vec(spec);
  for (int i = 0; i < spec.dimension; ++i) {
    std::string t = parts[std::size_t(i)];
    t.erase(0, t.find_first_not_of(' '));
    t.erase(t.find_last_not_of(' ') + 1);
    if (!parse_number(t, v[i])) throw SceneError(kSource, key, value, expected);
    check_number(p, key, v[i], value, spec.dimension);
  }
  p.set_vec(spec, v);
}

}  // namespace rtsph
