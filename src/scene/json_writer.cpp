// SimSpec -> canonical JSON. Every key is written, in table order, with numbers in shortest
// round-trip form, so reading the text back gives the identical spec (checkpoints hash it).
#include "scene/json_reader.h"
#include "scene/params.h"

namespace rtsph::scene_detail {
namespace {

Json& at_path(Json& obj, const std::string& dotted) {
  Json* node = &obj;
  std::size_t start = 0;
  for (std::size_t dot; (dot = dotted.find('.', start)) != std::string::npos; start = dot + 1)
    node = &(*node)[dotted.substr(start, dot - start)];
  return (*node)[dotted.substr(start)];
}

template <class Owner>
Json write_fields(const std::vector<FieldInfo<Owner>>& table, const Owner& o, int dimension) {
  Json j = Json::object();
  for (const auto& f : table) {
    Json& slot = at_path(j, f.key);
    switch (f.kind) {
      case ParamKind::Real: slot = f.get(o); break;
      case ParamKind::Int: slot = static_cast<std::int64_t>(f.get(o)); break;
      case ParamKind::Bool: slot = f.get(o) != 0; break;
      case ParamKind::String: slot = f.get_text(o); break;
      case ParamKind::Enum:
        slot = f.get ? f.choices_for(dimension).at(std::size_t(f.get(o))) : f.get_text(o);
        break;
      case ParamKind::Vec3: {
        const Vec3d v = f.get_vec(o);
        if (f.z_only_in_2d && dimension == 2) {
          slot = v[2];
          break;
        }
        slot = Json::array();
        for (int i = 0; i < dimension; ++i) slot.push_back(v[i]);
        break;
      }
    }
  }
  return j;
}

template <class Owner, class Write>
Json write_array(const std::vector<Owner>& items, Write&& write) {
  Json a = Json::array();
  for (const auto& item : items) a.push_back(write(item));
  return a;
}

}  // namespace

Json spec_to_json(const SimSpec& spec) {
  const int d = spec.dimension;
  Json j = write_fields(parameter_table(), spec, d);
  j["fluid_blocks"] = write_array(spec.fluid_blocks, [&](const FluidBlock& b) {
    return write_fields(fluid_block_fields(), b, d);
  });
  j["obstacles"] = write_array(spec.obstacles, [&](const ObstacleSpec& o) {
    Json oj = write_fields(obstacle_fields(), o, d);
    at_path(oj, keyframes_array().key) = write_array(o.path, [&](const Keyframe& k) {
      return write_fields(keyframe_fields(), k, d);
    });
    return oj;
  });
  j["emitters"] = write_array(spec.emitters, [&](const EmitterSpec& e) {
    return write_fields(emitter_fields(), e, d);
  });
  return j;
}

}  // namespace rtsph::scene_detail
