#pragma once
// Small fixed-size vector templated on the dimension, so one code path serves 2D and 3D.
#include <array>
#include <cmath>
#include <cstddef>

namespace rtsph {

using Real = float;  // particle storage and hot loops; reductions use double

template <int D, class T = Real>
struct Vec {
  static_assert(D == 2 || D == 3, "rtsph supports 2D and 3D");
  std::array<T, D> c{};

  constexpr T& operator[](int i) { return c[i]; }
  constexpr const T& operator[](int i) const { return c[i]; }

  static constexpr Vec splat(T s) {
    Vec r;
    for (int i = 0; i < D; ++i) r.c[i] = s;
    return r;
  }
  template <class U>
  static constexpr Vec from(const Vec<D, U>& o) {
    Vec r;
    for (int i = 0; i < D; ++i) r.c[i] = static_cast<T>(o.c[i]);
    return r;
  }

  constexpr Vec& operator+=(const Vec& o) { for (int i = 0; i < D; ++i) c[i] += o.c[i]; return *this; }
  constexpr Vec& operator-=(const Vec& o) { for (int i = 0; i < D; ++i) c[i] -= o.c[i]; return *this; }
  constexpr Vec& operator*=(T s) { for (int i = 0; i < D; ++i) c[i] *= s; return *this; }
  friend constexpr Vec operator+(Vec a, const Vec& b) { return a += b; }
  friend constexpr Vec operator-(Vec a, const Vec& b) { return a -= b; }
  friend constexpr Vec operator*(Vec a, T s) { return a *= s; }
  friend constexpr Vec operator*(T s, Vec a) { return a *= s; }
  friend constexpr Vec operator/(Vec a, T s) { for (int i = 0; i < D; ++i) a.c[i] /= s; return a; }
  friend constexpr Vec operator-(Vec a) { for (int i = 0; i < D; ++i) a.c[i] = -a.c[i]; return a; }
  friend constexpr bool operator==(const Vec&, const Vec&) = default;
};

template <int D, class T>
constexpr T dot(const Vec<D, T>& a, const Vec<D, T>& b) {
  T s = 0;
  for (int i = 0; i < D; ++i) s += a[i] * b[i];
  return s;
}
template <int D, class T>
T norm(const Vec<D, T>& a) { return std::sqrt(dot(a, a)); }
template <int D, class T>
constexpr Vec<D, T> cwise_min(Vec<D, T> a, const Vec<D, T>& b) {
  for (int i = 0; i < D; ++i) a[i] = b[i] < a[i] ? b[i] : a[i];
  return a;
}
template <int D, class T>
constexpr Vec<D, T> cwise_max(Vec<D, T> a, const Vec<D, T>& b) {
  for (int i = 0; i < D; ++i) a[i] = b[i] > a[i] ? b[i] : a[i];
  return a;
}

/// Three-component vector for dimension-independent descriptions (scenes, UI); 2D ignores z.
using Vec3d = Vec<3, double>;

template <int D>
Vec<D> truncate(const Vec3d& v) {
  Vec<D> r;
  for (int i = 0; i < D; ++i) r[i] = static_cast<Real>(v[i]);
  return r;
}

}  // namespace rtsph
