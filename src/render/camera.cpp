#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace rtsph::render {

Vec3f Camera::forward() const {
  if (dim == 2) return {0, 0, -1};
  float cp = std::cos(pitch);
  return normalize(Vec3f{-cp * std::sin(yaw), -std::sin(pitch), -cp * std::cos(yaw)});
}

Vec3f Camera::eye() const {
  if (dim == 2) return target + Vec3f{0, 0, std::max(distance, 1.0f)};
  return target - forward() * distance;
}

Vec3f Camera::right() const {
  if (dim == 2) return {1, 0, 0};
  return normalize(cross(forward(), Vec3f{0, 1, 0}));
}

Vec3f Camera::up() const {
  if (dim == 2) return {0, 1, 0};
  return cross(right(), forward());
}

float Camera::znear() const {
  if (dim == 2) return 0.01f;
  return std::max(distance * 0.01f, std::max(distance - 4 * scene_radius, 1e-4f));
}

float Camera::zfar() const {
  if (dim == 2) return std::max(distance, 1.0f) * 2 + 1;
  return distance + 6 * scene_radius;
}

Mat4 Camera::view() const { return look_at(eye(), target, up()); }

Mat4 Camera::projection(float aspect) const {
  if (dim == 2) {
    float hw = half_height * aspect;
    return orthographic(-hw, hw, -half_height, half_height, znear(), zfar());
  }
  return perspective(fovy, aspect, znear(), zfar());
}

void Camera::frame(const Vec3f& lo, const Vec3f& hi, float aspect) {
  Vec3f size = hi - lo;
  target = (lo + hi) * 0.5f;
  if (dim == 2) {
    target.z = 0;
    half_height = std::max(size.y * 0.5f, size.x * 0.5f / std::max(aspect, 1e-3f)) * 1.1f;
    scene_radius = std::max(size.x, size.y);
    distance = 1;
    return;
  }
  float radius = 0.5f * length(size);
  scene_radius = std::max(radius, 1e-3f);
  float half_fov = 0.5f * fovy;
  float half_fov_x = std::atan(std::tan(half_fov) * aspect);
  float fov_min = std::min(half_fov, half_fov_x);
  distance = scene_radius / std::sin(fov_min) * 0.95f;
  yaw = 0.55f;
  pitch = 0.35f;
}

void Camera::orbit(float dyaw, float dpitch) {
  if (dim == 2) return;
  yaw = std::remainder(yaw + dyaw, 6.2831853f);
  pitch = std::clamp(pitch + dpitch, -1.55f, 1.55f);
}

float Camera::world_per_pixel(int viewport_height) const {
  float h = static_cast<float>(std::max(viewport_height, 1));
  if (dim == 2) return 2 * half_height / h;
  return 2 * distance * std::tan(0.5f * fovy) / h;
}

void Camera::pan(float dx_px, float dy_px, int viewport_height) {
  float s = world_per_pixel(viewport_height);
  target += right() * (-dx_px * s) + up() * (dy_px * s);
}

void Camera::zoom(float factor) {
  factor = std::clamp(factor, 0.05f, 20.0f);
  if (dim == 2)
    half_height = std::clamp(half_height * factor, 1e-4f, 1e5f);
  else
    distance = std::clamp(distance * factor, 1e-3f, 1e5f);
}

Ray Camera::ray(float px, float py, int width, int height) const {
  float w = static_cast<float>(std::max(width, 1)), h = static_cast<float>(std::max(height, 1));
  float nx = 2 * (px + 0.0f) / w - 1, ny = 1 - 2 * (py + 0.0f) / h;
  float aspect = w / h;
  if (dim == 2) {
    Vec3f o = target + Vec3f{nx * half_height * aspect, ny * half_height, std::max(distance, 1.0f)};
    return {o, {0, 0, -1}};
  }
  float t = std::tan(0.5f * fovy);
  Vec3f d = forward() + right() * (nx * t * aspect) + up() * (ny * t);
  return {eye(), normalize(d)};
}

ScreenPoint Camera::project(const Vec3f& p, int width, int height) const {
  float w = static_cast<float>(std::max(width, 1)), h = static_cast<float>(std::max(height, 1));
  Mat4 vp = projection(w / h) * view();
  Vec4f c = vp * Vec4f{p.x, p.y, p.z, 1};
  ScreenPoint s;
  s.in_front = c.w > 0;
  if (c.w == 0) return s;
  float nx = c.x / c.w, ny = c.y / c.w, nz = c.z / c.w;
  s.x = (nx * 0.5f + 0.5f) * w;
  s.y = (0.5f - ny * 0.5f) * h;
  s.depth = nz * 0.5f + 0.5f;
  return s;
}

bool intersect_plane(const Ray& r, const Vec3f& point, const Vec3f& n, Vec3f* hit) {
  float denom = dot(r.dir, n);
  if (std::fabs(denom) < 1e-8f) return false;
  float t = dot(point - r.origin, n) / denom;
  if (t < 0) return false;
  *hit = r.origin + r.dir * t;
  return true;
}

}  // namespace rtsph::render
