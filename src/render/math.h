#pragma once
// Minimal float vector/matrix math for the renderer (column-major, OpenGL conventions).
#include <array>
#include <cmath>

namespace rtsph::render {

struct Vec3f {
  float x = 0, y = 0, z = 0;
  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr Vec3f operator+(const Vec3f& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3f operator-(const Vec3f& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f& operator+=(const Vec3f& o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr float operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
constexpr float dot(const Vec3f& a, const Vec3f& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3f cross(const Vec3f& a, const Vec3f& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3f& a) { return std::sqrt(dot(a, a)); }
inline Vec3f normalize(const Vec3f& a) {
  float l = length(a);
  return l > 0 ? a * (1.0f / l) : a;
}

struct Vec4f {
  float x = 0, y = 0, z = 0, w = 0;
};

/// Column-major 4×4 matrix: m[col * 4 + row], as glUniformMatrix4fv expects without transpose.
struct Mat4 {
  std::array<float, 16> m{};
  static Mat4 identity() {
    Mat4 r;
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1;
    return r;
  }
  float& at(int row, int col) { return m[col * 4 + row]; }
  float at(int row, int col) const { return m[col * 4 + row]; }
  const float* data() const { return m.data(); }
  Mat4 operator*(const Mat4& b) const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        float s = 0;
        for (int k = 0; k < 4; ++k) s += at(i, k) * b.at(k, j);
        r.at(i, j) = s;
      }
    return r;
  }
  Vec4f operator*(const Vec4f& v) const {
    const float in[4] = {v.x, v.y, v.z, v.w};
    float o[4];
    for (int i = 0; i < 4; ++i) o[i] = at(i, 0) * in[0] + at(i, 1) * in[1] + at(i, 2) * in[2] + at(i, 3) * in[3];
    return {o[0], o[1], o[2], o[3]};
  }
  Vec3f transform_point(const Vec3f& p) const {
    Vec4f r = (*this) * Vec4f{p.x, p.y, p.z, 1};
    return {r.x, r.y, r.z};
  }
};

/// Right-handed view matrix looking from eye at target.
inline Mat4 look_at(const Vec3f& eye, const Vec3f& target, const Vec3f& up) {
  Vec3f f = normalize(target - eye);
  Vec3f s = normalize(cross(f, up));
  Vec3f u = cross(s, f);
  Mat4 r = Mat4::identity();
  r.at(0, 0) = s.x; r.at(0, 1) = s.y; r.at(0, 2) = s.z; r.at(0, 3) = -dot(s, eye);
  r.at(1, 0) = u.x; r.at(1, 1) = u.y; r.at(1, 2) = u.z; r.at(1, 3) = -dot(u, eye);
  r.at(2, 0) = -f.x; r.at(2, 1) = -f.y; r.at(2, 2) = -f.z; r.at(2, 3) = dot(f, eye);
  return r;
}

/// OpenGL perspective projection (clip z in [-w, w]); fovy in radians.
inline Mat4 perspective(float fovy, float aspect, float znear, float zfar) {
  Mat4 r;
  float f = 1.0f / std::tan(fovy * 0.5f);
  r.at(0, 0) = f / aspect;
  r.at(1, 1) = f;
  r.at(2, 2) = (zfar + znear) / (znear - zfar);
  r.at(2, 3) = 2 * zfar * znear / (znear - zfar);
  r.at(3, 2) = -1;
  return r;
}

inline Mat4 orthographic(float left, float right, float bottom, float top, float znear, float zfar) {
  Mat4 r = Mat4::identity();
  r.at(0, 0) = 2 / (right - left);
  r.at(1, 1) = 2 / (top - bottom);
  r.at(2, 2) = -2 / (zfar - znear);
  r.at(0, 3) = -(right + left) / (right - left);
  r.at(1, 3) = -(top + bottom) / (top - bottom);
  r.at(2, 3) = -(zfar + znear) / (zfar - znear);
  return r;
}

}  // namespace rtsph::render
