#pragma once
// What the parameter tables (params.cpp, params_items.cpp) share: the field builder, which takes
// a field's kind and accessors from the member it stores, and the bounds on coordinates, speeds
// and times. Private to src/scene.
#include <algorithm>
#include <type_traits>

#include "scene/params.h"

namespace rtsph::params_detail {

template <class>
struct member_of;
template <class O, class T>
struct member_of<T O::*> {
  using owner = O;
  using type = T;
};

// Builds a field from its description and a pointer to the member that stores it; the kind and
// accessors follow from the member's type, so the table cannot disagree with SimSpec.
template <auto M>
FieldInfo<typename member_of<decltype(M)>::owner> field(ParamMeta meta) {
  using O = typename member_of<decltype(M)>::owner;
  using T = typename member_of<decltype(M)>::type;
  FieldInfo<O> f;
  static_cast<ParamMeta&>(f) = std::move(meta);
  if constexpr (std::is_same_v<T, Vec3d>) {
    f.kind = ParamKind::Vec3;
    f.get_vec = [](const O& o) { return o.*M; };
    f.set_vec = [](O& o, const Vec3d& v) { o.*M = v; };
  } else if constexpr (std::is_same_v<T, std::string>) {
    f.kind = f.choices.empty() ? ParamKind::String : ParamKind::Enum;
    f.get_text = [](const O& o) { return o.*M; };
    f.set_text = [](O& o, const std::string& v) { o.*M = v; };
  } else if constexpr (std::is_enum_v<T>) {
    f.kind = ParamKind::Enum;
    f.get = [](const O& o) { return double(int(o.*M)); };
    f.set = [](O& o, double v) { o.*M = T(int(v)); };
  } else if constexpr (std::is_same_v<T, bool>) {
    f.kind = ParamKind::Bool;
    f.get = [](const O& o) { return o.*M ? 1.0 : 0.0; };
    f.set = [](O& o, double v) { o.*M = v != 0; };
  } else if constexpr (std::is_integral_v<T>) {
    f.kind = ParamKind::Int;
    f.get = [](const O& o) { return double(o.*M); };
    f.set = [](O& o, double v) { o.*M = T(v); };
  } else {
    static_assert(std::is_same_v<T, double>, "unsupported parameter type");
    f.kind = ParamKind::Real;
    f.get = [](const O& o) { return o.*M; };
    f.set = [](O& o, double v) { o.*M = v; };
  }
  if (f.kind == ParamKind::Enum) {
    const auto it = std::find(f.choices.begin(), f.choices.end(), f.default_text);
    f.default_value = double(it - f.choices.begin());
  }
  return f;
}

inline constexpr double kLength = 1e4;  // m, bound on coordinates: keeps lattices and grids finite
inline constexpr double kSpeed = 1e3;   // m/s
inline constexpr double kTime = 1e6;    // s


}  // namespace rtsph::params_detail
