#include "scene/json_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <string>
#include <unordered_set>
#include <vector>

#include "scene/params.h"
#include "scene/scene_error.h"
#include "scene/values.h"

namespace rtsph::scene_detail {
namespace {

using ArrayReader = std::function<void(const std::string& key, const Json& value,
                                       const std::string& path)>;

class Reader {
 public:
  Reader(const std::string& source, int dimension) : source_(source), dimension_(dimension) {}

  [[noreturn]] void fail(const std::string& path, const Json& value, const std::string& expected) const {
    throw SceneError(source_, path, show(value), expected);
  }

  // Walks one JSON object against a field table. `group` is the dotted path inside the owner
  // ("solver.time_step."), `prefix` the path of the owner in the file ("obstacles[2].").
  template <class Owner>
  void read_object(const Json& obj, const std::vector<FieldInfo<Owner>>& table, Owner& out,
                   const std::string& prefix, const std::string& group,
                   const std::vector<std::string>& arrays, const ArrayReader& on_array) const {
    const std::string here = prefix + group;
    if (!obj.is_object())
      fail(here.empty() ? "(top level)" : here.substr(0, here.size() - 1), obj,
           "expected an object");
    for (const auto& [k, v] : obj.items()) {
      const std::string rel = group + k;
      const std::string path = prefix + rel;
      if (const auto* f = find(table, rel)) {
        once(path, v);
        read_value(*f, v, out, path);
      } else if (std::find(arrays.begin(), arrays.end(), rel) != arrays.end()) {
        once(path, v);
        on_array(rel, v, path);
      } else if (is_group(table, arrays, rel)) {
        read_object(v, table, out, prefix, rel + ".", arrays, on_array);
      } else {
        unknown_key(table, arrays, prefix, group, rel, v);
      }
    }
    for (const auto& f : table)
      if (f.required && f.key.starts_with(group) && !has_path(obj, f.key.substr(group.size())))
        throw SceneError(source_, prefix + f.key, "(missing)",
                         "required; " + expected_text(f, dimension_));
  }

  template <class Owner>
  void read_value(const FieldInfo<Owner>& f, const Json& v, Owner& out, const std::string& path) const {
    const std::string expected = expected_text(f, dimension_);
    switch (f.kind) {
      case ParamKind::Real:
      case ParamKind::Int:
        if (!v.is_number() || !number_fits(f, v.get<double>())) fail(path, v, expected);
        return f.set(out, v.get<double>());
      case ParamKind::Bool:
        if (!v.is_boolean()) fail(path, v, expected);
        return f.set(out, v.get<bool>() ? 1 : 0);
      case ParamKind::String:
        if (!v.is_string() || v.get_ref<const std::string&>().empty()) fail(path, v, expected);
        return f.set_text(out, v.get<std::string>());
      case ParamKind::Enum: {
        const int i = v.is_string() ? choice_index(f, v.get_ref<const std::string&>(), dimension_) : -1;
        if (i < 0) fail(path, v, expected);
        if (f.set) return f.set(out, i);
        return f.set_text(out, f.choices_for(dimension_)[std::size_t(i)]);
      }
      case ParamKind::Vec3: break;
    }
    Vec3d r = f.default_vec;  // 2D keeps the default z, so 2D specs compare equal after a round trip
    if (f.z_only_in_2d && dimension_ == 2) {
      if (!v.is_number() || !number_fits(f, v.get<double>())) fail(path, v, expected);
      r[2] = v.get<double>();
      return f.set_vec(out, r);
    }
    if (!v.is_array() || int(v.size()) != dimension_) fail(path, v, expected);
    for (int i = 0; i < dimension_; ++i) {
      const Json& c = v[std::size_t(i)];
      if (!c.is_number() || !number_fits(f, c.get<double>())) fail(path, v, expected);
      r[i] = c.get<double>();
    }
    f.set_vec(out, r);
  }

 private:
  template <class Owner>
  static const FieldInfo<Owner>* find(const std::vector<FieldInfo<Owner>>& table, const std::string& key) {
    for (const auto& f : table)
      if (f.key == key) return &f;
    return nullptr;
  }

  template <class Owner>
  static bool is_group(const std::vector<FieldInfo<Owner>>& table,
                       const std::vector<std::string>& arrays, const std::string& rel) {
    const std::string p = rel + ".";
    for (const auto& f : table)
      if (f.key.starts_with(p)) return true;
    for (const auto& a : arrays)
      if (a.starts_with(p)) return true;
    return false;
  }

  static bool has_path(const Json& obj, const std::string& dotted) {
    const Json* node = &obj;
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = dotted.find('.', start);
      const std::string part = dotted.substr(start, dot - start);
      if (!node->is_object() || !node->contains(part)) return false;
      node = &(*node)[part];
      if (dot == std::string::npos) return true;
      start = dot + 1;
    }
  }

  template <class Owner>
  [[noreturn]] void unknown_key(const std::vector<FieldInfo<Owner>>& table,
                                const std::vector<std::string>& arrays, const std::string& prefix,
                                const std::string& group, const std::string& rel,
                                const Json& v) const {
    std::vector<std::string> keys, here;
    for (const auto& f : table) keys.push_back(f.key);
    keys.insert(keys.end(), arrays.begin(), arrays.end());
    for (const auto& k : keys) {
      if (!k.starts_with(group)) continue;
      const std::string next = k.substr(group.size(), k.find('.', group.size()) - group.size());
      if (std::find(here.begin(), here.end(), next) == here.end()) here.push_back(next);
    }
    const std::string near = nearest_key(rel, keys);
    std::string list;
    for (const auto& h : here) list += (list.empty() ? "" : ", ") + h;
    fail(prefix + rel, v,
         near.empty() ? "unknown key; expected one of: " + list
                      : "unknown key; did you mean " + prefix + near + "?");
  }

  // A parameter given both nested and dotted ("solver": {"eos": …} and "solver.eos") would keep
  // whichever came last, silently, as a duplicate key would (json_text.cpp refuses those).
  void once(const std::string& path, const Json& v) const {
    if (!read_.insert(path).second) fail(path, v, "given twice (nested and as a dotted key): give it once");
  }

  const std::string& source_;
  int dimension_;
  mutable std::unordered_set<std::string> read_;  // the paths read so far
};

std::string element_path(const std::string& path, std::size_t i) {
  return fmt::format("{}[{}].", path, i);
}

template <class Owner, class ReadOne>
void read_array(const Reader& r, const Json& v, const std::string& path, std::vector<Owner>& out,
                ReadOne&& read_one) {
  if (!v.is_array()) r.fail(path, v, "expected an array of objects");
  out.clear();
  for (std::size_t i = 0; i < v.size(); ++i) {
    out.emplace_back();
    read_one(v[i], element_path(path, i), out.back());
  }
}

void read_obstacle(const Reader& r, const Json& v, const std::string& prefix, ObstacleSpec& o) {
  const std::string keyframes = keyframes_array().key;
  r.read_object(v, obstacle_fields(), o, prefix, "", {keyframes},
                [&](const std::string&, const Json& a, const std::string& path) {
                  read_array(r, a, path, o.path, [&](const Json& e, const std::string& p, Keyframe& k) {
                    r.read_object(e, keyframe_fields(), k, p, "", {}, nullptr);
                  });
                });
}

}  // namespace

SimSpec spec_from_json(const Json& doc, const std::string& source) {
  SimSpec spec;
  // The dimension decides every vector's length, so it is read before anything else.
  if (doc.is_object() && doc.contains("dimension")) {
    Json only = Json::object();
    only["dimension"] = doc["dimension"];
    Reader(source, 3).read_object(only, parameter_table(), spec, "", "", {}, nullptr);
  }
  const Reader r(source, spec.dimension);
  std::vector<std::string> arrays;
  for (const auto& a : spec_arrays()) arrays.push_back(a.key);
  r.read_object(doc, parameter_table(), spec, "", "", arrays,
                [&](const std::string& key, const Json& v, const std::string& path) {
                  if (key == "fluid_blocks")
                    read_array(r, v, path, spec.fluid_blocks,
                               [&](const Json& e, const std::string& p, FluidBlock& b) {
                                 r.read_object(e, fluid_block_fields(), b, p, "", {}, nullptr);
                               });
                  else if (key == "obstacles")
                    read_array(r, v, path, spec.obstacles,
                               [&](const Json& e, const std::string& p, ObstacleSpec& o) {
                                 read_obstacle(r, e, p, o);
                               });
                  else
                    read_array(r, v, path, spec.emitters,
                               [&](const Json& e, const std::string& p, EmitterSpec& em) {
                                 r.read_object(e, emitter_fields(), em, p, "", {}, nullptr);
                               });
                });
  return spec;
}

std::string show(const Json& value) {
  constexpr std::size_t kMax = 60;
  std::string s = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (s.size() > kMax) {
    std::size_t cut = kMax - 3;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
    s = s.substr(0, cut) + "...";
  }
  return s;
}

}  // namespace rtsph::scene_detail
