// Camera math: projection of known points, orbit/zoom/pan invariants, rays through pixels.
// Compiles the GL-free camera source directly (this test links only the non-GL layers).
#include "render/camera.cpp"  // NOLINT(bugprone-suspicious-include)

#include <gtest/gtest.h>

using namespace rtsph::render;

namespace {
constexpr int W = 640, H = 480;
float dist(const Vec3f& a, const Vec3f& b) { return length(a - b); }
}  // namespace

TEST(Camera, TargetProjectsToImageCentre) {
  Camera c;
  c.target = {0.3f, 0.2f, -0.1f};
  c.distance = 2.5f;
  for (float yaw : {0.0f, 0.7f, 2.0f, -1.2f})
    for (float pitch : {-0.5f, 0.0f, 0.4f, 1.2f}) {
      c.yaw = yaw;
      c.pitch = pitch;
      ScreenPoint s = c.project(c.target, W, H);
      EXPECT_TRUE(s.in_front);
      EXPECT_NEAR(s.x, W / 2.0f, 1e-3f);
      EXPECT_NEAR(s.y, H / 2.0f, 1e-3f);
      EXPECT_GT(s.depth, 0.0f);
      EXPECT_LT(s.depth, 1.0f);
    }
}

TEST(Camera, KnownPointsProjectWhereExpected) {
  // Eye on +z looking at the origin: +x goes right, +y goes up (smaller pixel y).
  Camera c;
  c.yaw = 0;
  c.pitch = 0;
  c.distance = 2;
  c.fovy = 1.5707963f;  // 90°: tan(45°) = 1, so x = ±d at the target's depth hits the edge
  EXPECT_NEAR(dist(c.eye(), {0, 0, 2}), 0, 1e-5f);
  ScreenPoint r = c.project({1, 0, 0}, W, H);  // 1 m right at distance 2 → ndc x = 1/(2·aspect)
  EXPECT_NEAR(r.x, W / 2.0f + 0.5f / (float(W) / H) * W / 2.0f, 1e-2f);
  EXPECT_NEAR(r.y, H / 2.0f, 1e-3f);
  ScreenPoint u = c.project({0, 2, 0}, W, H);  // top edge
  EXPECT_NEAR(u.y, 0.0f, 1e-2f);
  ScreenPoint behind = c.project({0, 0, 5}, W, H);
  EXPECT_FALSE(behind.in_front);
  // Nearer points have smaller depth.
  EXPECT_LT(c.project({0, 0, 1}, W, H).depth, c.project({0, 0, -1}, W, H).depth);
}

TEST(Camera, OrbitKeepsDistanceToTarget) {
  Camera c;
  c.target = {1, 2, 3};
  c.distance = 4;
  for (int i = 0; i < 50; ++i) {
    c.orbit(0.37f, (i % 7 - 3) * 0.11f);
    EXPECT_NEAR(dist(c.eye(), c.target), 4.0f, 1e-4f);
    ScreenPoint s = c.project(c.target, W, H);
    EXPECT_NEAR(s.x, W / 2.0f, 1e-2f);
    EXPECT_NEAR(s.y, H / 2.0f, 1e-2f);
  }
  c.orbit(0, 10);  // pitch is clamped short of the pole
  EXPECT_LT(c.pitch, 1.5708f);
  EXPECT_NEAR(dist(c.eye(), c.target), 4.0f, 1e-4f);
}

TEST(Camera, BasisIsOrthonormal) {
  Camera c;
  c.yaw = 0.9f;
  c.pitch = -0.4f;
  EXPECT_NEAR(length(c.forward()), 1, 1e-5f);
  EXPECT_NEAR(length(c.right()), 1, 1e-5f);
  EXPECT_NEAR(length(c.up()), 1, 1e-5f);
  EXPECT_NEAR(dot(c.forward(), c.right()), 0, 1e-5f);
  EXPECT_NEAR(dot(c.forward(), c.up()), 0, 1e-5f);
  EXPECT_NEAR(c.right().y, 0, 1e-5f);  // no roll
}

TEST(Camera, ZoomAndPan) {
  Camera c;
  c.distance = 2;
  c.zoom(0.5f);
  EXPECT_NEAR(c.distance, 1.0f, 1e-6f);
  Vec3f before = c.target;
  // Dragging right by 100 px moves the content right: the target moves left.
  c.pan(100, 0, H);
  EXPECT_LT(dot(c.target - before, c.right()), 0.0f);
  EXPECT_NEAR(length(c.target - before), 100 * c.world_per_pixel(H), 1e-5f);
}

TEST(Camera, RayThroughProjectedPointHitsIt) {
  Camera c;
  c.target = {0.5f, 0.4f, 0.5f};
  c.distance = 3;
  c.yaw = 0.4f;
  c.pitch = 0.3f;
  for (Vec3f p : {Vec3f{0.1f, 0.2f, 0.3f}, Vec3f{0.9f, 0.1f, 0.8f}, Vec3f{0.5f, 0.9f, 0.1f}}) {
    ScreenPoint s = c.project(p, W, H);
    Ray r = c.ray(s.x, s.y, W, H);
    Vec3f to = p - r.origin;
    float along = dot(to, r.dir);
    EXPECT_GT(along, 0);
    EXPECT_NEAR(length(to - r.dir * along), 0, 1e-4f);  // p lies on the ray
  }
  // Plane intersection: the centre ray meets the horizontal plane through the target there.
  Vec3f hit;
  ASSERT_TRUE(intersect_plane(c.ray(W / 2.0f, H / 2.0f, W, H), c.target, {0, 1, 0}, &hit));
  EXPECT_NEAR(dist(hit, c.target), 0, 1e-4f);
}

TEST(Camera, FrameContainsTheDomain) {
  Camera c;
  Vec3f lo{0, 0, 0}, hi{3.2f, 1.5f, 1.0f};
  c.frame(lo, hi, float(W) / H);
  for (int bits = 0; bits < 8; ++bits) {
    Vec3f p{bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z};
    ScreenPoint s = c.project(p, W, H);
    EXPECT_TRUE(s.in_front);
    EXPECT_GE(s.x, 0);
    EXPECT_LE(s.x, W);
    EXPECT_GE(s.y, 0);
    EXPECT_LE(s.y, H);
    EXPECT_GT(s.depth, 0);
    EXPECT_LT(s.depth, 1);
  }
}

TEST(Camera, TwoDimensionalIsOrthographic) {
  Camera c;
  c.dim = 2;
  c.frame({0, 0, 0}, {2, 1, 0}, float(W) / H);
  ScreenPoint a = c.project({0, 0, 0}, W, H), b = c.project({2, 1, 0}, W, H);
  EXPECT_GE(a.x, 0);
  EXPECT_LE(b.x, W);
  EXPECT_LT(b.y, a.y);  // y up on screen
  // Orthographic: ray directions are all -z; the ray through a projected point hits it.
  Ray r = c.ray(a.x, a.y, W, H);
  EXPECT_NEAR(r.dir.z, -1, 1e-6f);
  EXPECT_NEAR(r.origin.x, 0, 1e-4f);
  EXPECT_NEAR(r.origin.y, 0, 1e-4f);
  c.orbit(1, 1);  // no effect in 2D
  EXPECT_NEAR(c.project({0, 0, 0}, W, H).x, a.x, 1e-4f);
  float hh = c.half_height;
  c.zoom(2);
  EXPECT_NEAR(c.half_height, 2 * hh, 1e-5f);
}
