#pragma once
// Orbit camera (3D, perspective) and pan/zoom camera (2D, orthographic) with the math the
// viewer needs for picking: projection of world points to pixels and rays through pixels.
// Pixel coordinates have their origin at the top-left corner, y pointing down (as GLFW).
#include "render/math.h"

namespace rtsph::render {

struct Ray {
  Vec3f origin, dir;  // dir is unit length
};

struct ScreenPoint {
  float x = 0, y = 0;   // pixels from the top-left corner
  float depth = 0;      // window depth in [0, 1] (0 = near plane)
  bool in_front = false;  // false when the point is behind the camera
};

class Camera {
 public:
  int dim = 3;
  Vec3f target{0, 0, 0};
  float distance = 3;           // m, eye to target (3D)
  float yaw = 0.55f;            // rad about +y; 0 puts the eye on the +z side of the target
  float pitch = 0.35f;          // rad above the horizontal plane, clamped to ±1.55
  float fovy = 0.7853982f;      // rad, vertical field of view (3D)
  float half_height = 1;        // m, half the visible height (2D)
  float scene_radius = 1;       // m, sets the near/far planes

  Vec3f eye() const;
  Vec3f forward() const;  // unit, eye → target
  Vec3f right() const;    // unit, screen x
  Vec3f up() const;       // unit, screen y (up)
  float znear() const;
  float zfar() const;
  Mat4 view() const;
  Mat4 projection(float aspect) const;

  /// Places the camera so that the box [lo, hi] fills the view (default angles in 3D).
  void frame(const Vec3f& lo, const Vec3f& hi, float aspect);
  void orbit(float dyaw, float dpitch);
  /// Moves the target by a mouse displacement in pixels (content follows the cursor).
  void pan(float dx_px, float dy_px, int viewport_height);
  /// factor < 1 zooms in.
  void zoom(float factor);

  Ray ray(float px, float py, int width, int height) const;
  ScreenPoint project(const Vec3f& p, int width, int height) const;
  /// Metres per pixel at the target's depth.
  float world_per_pixel(int viewport_height) const;
};

/// Intersection of a ray with the plane through `point` with normal `n`; false if parallel or
/// behind the origin.
bool intersect_plane(const Ray& r, const Vec3f& point, const Vec3f& n, Vec3f* hit);

}  // namespace rtsph::render
