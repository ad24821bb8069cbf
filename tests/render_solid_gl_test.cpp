// Obstacles drawn as solids from their geometry (headless EGL, synthetic scenes, no solver):
// 2D shapes are filled and rotate, 3D boxes and spheres occlude and are occluded by fluid
// impostors by true depth, spheres are lit, and the display modes decide what shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "gl_test_context.h"
#include "render/gl_context.h"
#include "render/image_io.h"
#include "render/renderer.h"

using namespace rtsph;
using namespace rtsph::render;

namespace {

struct Px {
  int r, g, b;
  int sum() const { return r + g + b; }
};

struct Fluid {
  explicit Fluid(int d = 3) : dim(d) {}
  int dim;
  std::vector<float> x[3], v[3];
  void add(float px, float py, float pz) {
    x[0].push_back(px); x[1].push_back(py); x[2].push_back(pz);
    for (auto& c : v) c.push_back(0);
  }
  ParticleView view() const {
    ParticleView pv;
    pv.dim = dim;
    pv.count = x[0].size();
    for (int k = 0; k < dim; ++k) {
      pv.x[k] = x[k].empty() ? nullptr : x[k].data();
      pv.v[k] = v[k].empty() ? nullptr : v[k].data();
    }
    return pv;
  }
};

SolidShape sphere(Vec3f c, float r) {
  SolidShape s;
  s.kind = SolidShape::Kind::Sphere;
  s.center = c;
  s.radius = r;
  return s;
}

SolidShape box(Vec3f c, Vec3f he, float angle_z = 0) {
  SolidShape s;
  s.center = c;
  s.half_extents = he;
  const float co = std::cos(angle_z), si = std::sin(angle_z);
  s.rotation = {co, si, 0, -si, co, 0, 0, 0, 1};
  return s;
}

class RenderSolid : public ::testing::Test {
 protected:
  void SetUp() override {
    RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx_);
    renderer_ = std::make_unique<Renderer>();
    s_.grid = s_.walls = s_.legend = false;
  }
  void TearDown() override {
    renderer_.reset();
    ctx_.reset();
  }

  // Draws fluid + solids and returns the image (RGBA, top row first).
  std::vector<unsigned char> render(const Camera& cam, const Fluid& f,
                                    const std::vector<SolidShape>& solids) {
    renderer_->upload(f.view(), nullptr);
    renderer_->upload_solids(solids);
    OffscreenTarget target(W, H);
    target.bind();
    stats_ = renderer_->draw(cam, W, H, s_);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    auto px = target.read_rgba();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (const char* dump = std::getenv("RTSPH_TEST_DUMP"))
      write_png(std::string(dump) + "/" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                    std::to_string(dumped_++) + ".png",
                W, H, px.data());
    return px;
  }
  Px at(const std::vector<unsigned char>& img, const Camera& cam, Vec3f p) const {
    const ScreenPoint sp = cam.project(p, W, H);
    const int x = int(sp.x), y = int(sp.y);
    EXPECT_TRUE(x >= 0 && x < W && y >= 0 && y < H) << p.x << "," << p.y << "," << p.z;
    const unsigned char* q = img.data() + (std::size_t(std::clamp(y, 0, H - 1)) * W +
                                           std::clamp(x, 0, W - 1)) * 4;
    return {q[0], q[1], q[2]};
  }
  static int c255(float v) { return int(std::lround(v * 255)); }
  bool is_bg(Px p) const {
    return std::abs(p.r - c255(s_.background.r)) <= 1 && std::abs(p.g - c255(s_.background.g)) <= 1 &&
           std::abs(p.b - c255(s_.background.b)) <= 1;
  }
  // The obstacle colour, possibly shaded: grey (r ≈ b) and clearly brighter than background.
  static bool is_solid(Px p) { return std::abs(p.r - p.b) < 25 && p.r > 45; }
  static bool is_water(Px p) { return p.b > 50 && p.b > p.r + 25 && p.b > p.g; }

  static Camera front_camera() {  // looking down −z at the origin
    Camera cam;
    cam.yaw = 0;
    cam.pitch = 0;
    cam.distance = 3;
    cam.scene_radius = 1;
    return cam;
  }
  static Camera camera_2d() {
    Camera cam;
    cam.dim = 2;
    cam.frame({0, 0, 0}, {1, 1, 0}, float(W) / H);
    return cam;
  }

  static constexpr int W = 120, H = 96;
  std::unique_ptr<HeadlessContext> ctx_;
  std::unique_ptr<Renderer> renderer_;
  RenderSettings s_;
  DrawStats stats_;
  int dumped_ = 0;
};

}  // namespace

TEST_F(RenderSolid, CircleIsAFilledDiscWithADarkerRim) {
  renderer_->set_domain(2, {0, 0, 0}, {1, 1, 0});
  const Camera cam = camera_2d();
  const float r = 0.25f;
  auto img = render(cam, Fluid{2}, {sphere({0.5f, 0.5f, 0}, r)});
  const Px centre = at(img, cam, {0.5f, 0.5f, 0});
  EXPECT_NEAR(centre.r, c255(s_.obstacle.r), 2);
  EXPECT_NEAR(centre.g, c255(s_.obstacle.g), 2);
  EXPECT_NEAR(centre.b, c255(s_.obstacle.b), 2);
  // Filled, not a ring: halfway out is still solid.
  EXPECT_TRUE(is_solid(at(img, cam, {0.5f + 0.5f * r, 0.5f, 0})));
  EXPECT_TRUE(is_solid(at(img, cam, {0.5f, 0.5f - 0.5f * r, 0})));
  // Rim darker than the centre, and nothing outside the radius (two pixels of margin).
  const Px rim = at(img, cam, {0.5f - 0.95f * r, 0.5f, 0});
  EXPECT_TRUE(is_solid(rim));
  EXPECT_LT(rim.sum(), centre.sum() - 30);
  const float out = r + 2.5f * cam.world_per_pixel(H);
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f + out, 0.5f, 0})));
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f, 0.5f + out, 0})));
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f + 0.75f * out, 0.5f + 0.75f * out, 0})));
  EXPECT_EQ(renderer_->solid_count(), 1u);
}

TEST_F(RenderSolid, RectangleFollowsItsRotation) {
  renderer_->set_domain(2, {0, 0, 0}, {1, 1, 0});
  const Camera cam = camera_2d();
  const float pi = 3.14159265f, a = pi / 4;
  auto img = render(cam, Fluid{2}, {box({0.5f, 0.5f, 0}, {0.3f, 0.08f, 0.1f}, a)});
  // Along the rotated long axis, near its end: solid.
  const float co = std::cos(a), si = std::sin(a);
  for (float t : {0.0f, 0.15f, 0.26f, -0.26f})
    EXPECT_TRUE(is_solid(at(img, cam, {0.5f + t * co, 0.5f + t * si, 0}))) << t;
  // Where the unrotated rectangle's ends were: background.
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f + 0.26f, 0.5f, 0})));
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f - 0.26f, 0.5f - 0.05f, 0})));
  // A rotated corner (pulled a little inside) is covered; the mirrored one is not.
  const Vec3f corner{0.5f + 0.27f * co - 0.06f * si, 0.5f + 0.27f * si + 0.06f * co, 0};
  EXPECT_TRUE(is_solid(at(img, cam, corner)));
  EXPECT_TRUE(is_bg(at(img, cam, {0.5f + 0.27f * co + 0.06f * si, 0.5f - 0.27f * si + 0.06f * co, 0})));
}

TEST_F(RenderSolid, FluidIsDrawnOverObstaclesIn2D) {
  renderer_->set_domain(2, {0, 0, 0}, {1, 1, 0});
  const Camera cam = camera_2d();
  Fluid f{2};
  f.add(0.5f, 0.7f, 0);  // overlapping the top of the disc
  s_.particle_radius = 0.04f;
  auto img = render(cam, f, {sphere({0.5f, 0.5f, 0}, 0.2f)});
  EXPECT_TRUE(is_water(at(img, cam, {0.5f, 0.7f, 0})));
  EXPECT_TRUE(is_solid(at(img, cam, {0.5f, 0.5f, 0})));
}

TEST_F(RenderSolid, BoxAndFluidOccludeByDepth) {
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  const Camera cam = front_camera();
  s_.particle_radius = 0.15f;
  const SolidShape b = box({0, 0, 0}, {0.3f, 0.3f, 0.3f}, 0.4f);
  for (ParticlePrimitive prim : {ParticlePrimitive::Points, ParticlePrimitive::Quads}) {
    s_.primitive = prim;
    Fluid behind;
    behind.add(0, 0, -0.6f);
    auto img = render(cam, behind, {b});
    EXPECT_TRUE(is_solid(at(img, cam, {0, 0, 0.3f}))) << "box must hide the fluid behind it";
    Fluid front;
    front.add(0, 0, 0.6f);
    img = render(cam, front, {b});
    EXPECT_TRUE(is_water(at(img, cam, {0, 0, 0.6f}))) << "fluid in front of the box is visible";
    // Away from the particle the box is still drawn.
    EXPECT_TRUE(is_solid(at(img, cam, {0.2f, -0.2f, 0.3f})));
  }
}

TEST_F(RenderSolid, RotatedBoxCoversItsRotatedExtent) {
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  const Camera cam = front_camera();
  auto img = render(cam, Fluid{}, {box({0, 0, 0}, {0.5f, 0.08f, 0.08f}, 3.14159265f / 2)});
  EXPECT_TRUE(is_solid(at(img, cam, {0, 0.4f, 0.08f})));
  EXPECT_TRUE(is_solid(at(img, cam, {0, -0.4f, 0.08f})));
  EXPECT_TRUE(is_bg(at(img, cam, {0.4f, 0, 0.08f})));
  EXPECT_TRUE(is_bg(at(img, cam, {-0.4f, 0, 0.08f})));
}

TEST_F(RenderSolid, SphereIsLitAndHasCurvedDepth) {
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  const Camera cam = front_camera();
  const float r = 0.4f;
  s_.particle_radius = 0.05f;
  Fluid f;
  // In front of the sphere's centre plane but behind its surface there (z ≈ 0.26 at x = 0.3):
  // hidden with ray-cast depth, visible with a flat billboard's depth.
  f.add(0.3f, 0, 0.12f);
  f.add(0, 0, 0.6f);  // in front of the sphere: visible
  auto img = render(cam, f, {sphere({0, 0, 0}, r)});
  EXPECT_TRUE(is_solid(at(img, cam, {0.3f, 0, 0.26f})));
  EXPECT_TRUE(is_water(at(img, cam, {0, 0, 0.6f})));
  // The light comes from the upper right front (view space): that side is brighter.
  const Px lit = at(img, cam, {0.2f, 0.22f, 0.2f}), dark = at(img, cam, {-0.2f, -0.22f, 0.2f});
  EXPECT_TRUE(is_solid(lit));
  EXPECT_GT(lit.sum(), dark.sum() + 60);
  // Round silhouette: inside along the diagonal, background just outside the radius.
  EXPECT_TRUE(is_bg(at(img, cam, {0.31f, 0.31f, 0})));  // 0.44 from the centre
  EXPECT_FALSE(is_bg(at(img, cam, {0.25f, -0.25f, 0})));  // 0.35 from the centre
}

TEST_F(RenderSolid, DisplayModesAndDrawCalls) {
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  const Camera cam = front_camera();
  s_.particle_radius = 0.1f;
  Fluid f;
  f.add(-0.6f, 0, 0);
  // An obstacle sample above the solid and a wall particle to the right.
  std::vector<float> bx = {0.0f, 0.6f}, by = {0.6f, 0}, bz = {0, 0};
  std::vector<int32_t> owner = {0, -1};
  BoundaryView b;
  b.dim = 3;
  b.count = 2;
  b.x[0] = bx.data(); b.x[1] = by.data(); b.x[2] = bz.data();
  b.owner = owner.data();
  const std::vector<SolidShape> solids = {sphere({0, 0, 0}, 0.2f), box({0, -0.6f, 0}, {0.1f, 0.1f, 0.1f})};
  auto draw = [&](DisplayMode m) {
    s_.display = m;
    renderer_->upload(f.view(), &b);
    renderer_->upload_solids(solids);
    OffscreenTarget target(W, H);
    target.bind();
    stats_ = renderer_->draw(cam, W, H, s_);
    auto img = target.read_rgba();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return img;
  };
  auto fl = draw(DisplayMode::Fluid);
  EXPECT_TRUE(is_water(at(fl, cam, {-0.6f, 0, 0})));
  EXPECT_TRUE(is_bg(at(fl, cam, {0, 0, 0})));
  EXPECT_TRUE(is_bg(at(fl, cam, {0, -0.6f, 0.1f})));
  EXPECT_EQ(stats_.draw_calls, 1);
  auto ob = draw(DisplayMode::FluidObstacles);
  EXPECT_TRUE(is_solid(at(ob, cam, {0, 0, 0.2f})));
  EXPECT_TRUE(is_solid(at(ob, cam, {0, -0.6f, 0.1f})));
  EXPECT_TRUE(is_bg(at(ob, cam, {0, 0.6f, 0})));  // no obstacle samples
  EXPECT_TRUE(is_bg(at(ob, cam, {0.6f, 0, 0})));  // no wall particles
  EXPECT_EQ(stats_.draw_calls, 2);                 // one call for every solid
  auto all = draw(DisplayMode::All);
  EXPECT_TRUE(is_solid(at(all, cam, {0, 0, 0.2f})));
  EXPECT_FALSE(is_bg(at(all, cam, {0, 0.6f, 0})));
  EXPECT_FALSE(is_bg(at(all, cam, {0.6f, 0, 0})));
  EXPECT_EQ(stats_.draw_calls, 3);
}
