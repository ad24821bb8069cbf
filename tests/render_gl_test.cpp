// Headless EGL rendering of fixed synthetic scenes (no solver): particles appear where they
// project and nowhere else, depth ordering is right, the legend shows the colour map, display
// modes filter boundary particles (only "all" shows them), frame sinks write files. Skips only
// when EGL offers no display at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "gl_test_context.h"
#include "render/gl_context.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "render/snapshot.h"

using namespace rtsph;
using namespace rtsph::render;

namespace {

struct Px {
  int r, g, b;
};

class RenderGl : public ::testing::TestWithParam<ParticlePrimitive> {
 protected:
  void SetUp() override {
    RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx_);
    renderer_ = std::make_unique<Renderer>();
  }
  void TearDown() override {
    renderer_.reset();
    ctx_.reset();
  }

  std::vector<unsigned char> render(const Camera& cam, int w, int h, const RenderSettings& s) {
    OffscreenTarget target(w, h);
    target.bind();
    renderer_->draw(cam, w, h, s);
    glFinish();
    auto px = target.read_rgba();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (const char* dump = std::getenv("RTSPH_TEST_DUMP")) {
      static int n = 0;
      write_png(std::string(dump) + "/" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                    std::to_string(n++) + ".png",
                w, h, px.data());
    }
    return px;
  }
  static Px at(const std::vector<unsigned char>& img, int w, int x, int y) {
    const unsigned char* p = img.data() + (static_cast<std::size_t>(y) * w + x) * 4;
    return {p[0], p[1], p[2]};
  }
  static RenderSettings plain() {
    RenderSettings s;
    s.primitive = GetParam();
    s.grid = false;
    s.walls = false;
    s.legend = false;
    return s;
  }
  static Px bg(const RenderSettings& s) {
    return {int(std::lround(s.background.r * 255)), int(std::lround(s.background.g * 255)),
            int(std::lround(s.background.b * 255))};
  }
  static bool is_water(Px p) { return p.b > 50 && p.b > p.r + 25 && p.b > p.g; }
  static bool is_bg(Px p, Px b) {
    return std::abs(p.r - b.r) <= 1 && std::abs(p.g - b.g) <= 1 && std::abs(p.b - b.b) <= 1;
  }

  std::unique_ptr<HeadlessContext> ctx_;
  std::unique_ptr<Renderer> renderer_;
};

// A small particle set as owned arrays.
struct Particles {
  int dim = 3;
  std::vector<float> x[3], v[3], rho, p;
  void add(float px, float py, float pz, float vx = 0, float vy = 0, float vz = 0,
           float density = 1000, float pressure = 0) {
    x[0].push_back(px); x[1].push_back(py); x[2].push_back(pz);
    v[0].push_back(vx); v[1].push_back(vy); v[2].push_back(vz);
    rho.push_back(density);
    p.push_back(pressure);
  }
  ParticleView view() const {
    ParticleView pv;
    pv.dim = dim;
    pv.count = x[0].size();
    for (int k = 0; k < dim; ++k) {
      pv.x[k] = x[k].data();
      pv.v[k] = v[k].data();
    }
    pv.density = rho.data();
    pv.pressure = p.data();
    return pv;
  }
};

}  // namespace

INSTANTIATE_TEST_SUITE_P(Primitives, RenderGl,
                         ::testing::Values(ParticlePrimitive::Points, ParticlePrimitive::Quads),
                         [](const auto& info) {
                           return info.param == ParticlePrimitive::Points ? "Points" : "Quads";
                         });

TEST_P(RenderGl, ContextIsCore43) {
  EXPECT_TRUE(gl_version_at_least_43());
  EXPECT_NE(ctx_->description().find("OpenGL"), std::string::npos);
  std::printf("%s\n", ctx_->description().c_str());
}

TEST_P(RenderGl, WaterWherePartsProjectBackgroundElsewhere3D) {
  constexpr int W = 160, H = 120;
  Particles ps;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 4; ++k) ps.add(0.15f + 0.2f * i, 0.1f + 0.2f * j, 0.2f + 0.2f * k);
  renderer_->set_domain(3, {0, 0, 0}, {1, 1, 1});
  renderer_->upload(ps.view(), nullptr);
  Camera cam;
  cam.frame({0, 0, 0}, {1, 1, 1}, float(W) / H);
  RenderSettings s = plain();
  s.particle_radius = 0.03f;
  auto img = render(cam, W, H, s);

  std::vector<ScreenPoint> proj;
  float rad_px = 0;
  for (std::size_t i = 0; i < ps.x[0].size(); ++i) {
    Vec3f c{ps.x[0][i], ps.x[1][i], ps.x[2][i]};
    ScreenPoint sp = cam.project(c, W, H);
    ScreenPoint edge = cam.project(c + cam.right() * s.particle_radius, W, H);
    rad_px = std::max(rad_px, std::hypot(edge.x - sp.x, edge.y - sp.y));
    proj.push_back(sp);
    EXPECT_TRUE(is_water(at(img, W, int(sp.x), int(sp.y))))
        << "particle " << i << " at pixel " << sp.x << "," << sp.y;
  }
  ASSERT_GT(rad_px, 1.5f);
  int bg_checked = 0, water = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float dmin = 1e9f;
      for (auto& sp : proj) dmin = std::min(dmin, std::hypot(x + 0.5f - sp.x, y + 0.5f - sp.y));
      Px p = at(img, W, x, y);
      if (is_water(p)) ++water;
      if (dmin > rad_px * 1.3f + 1.5f) {
        ++bg_checked;
        EXPECT_TRUE(is_bg(p, bg(s))) << "stray pixel at " << x << "," << y;
        if (!is_bg(p, bg(s))) return;
      }
    }
  EXPECT_GT(bg_checked, W * H / 2);
  EXPECT_GT(water, static_cast<int>(proj.size()) * 3);
}

TEST_P(RenderGl, NearerSphereIsInFrontWhateverTheOrder) {
  constexpr int W = 96, H = 96;
  Camera cam;
  cam.yaw = 0;
  cam.pitch = 0;
  cam.target = {0, 0, 0};
  cam.distance = 3;
  cam.scene_radius = 1;
  RenderSettings s = plain();
  s.particle_radius = 0.3f;
  s.color = ColorMode::Pressure;
  s.auto_range = false;
  s.range_min = 0;
  s.range_max = 1;
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  const Rgb near_c = colormap(s.map, 0), far_c = colormap(s.map, 1);
  for (int order = 0; order < 2; ++order) {
    Particles ps;
    // Near sphere (pressure 0) on the camera axis at z = +0.5, far one (pressure 1) at z = -0.5,
    // offset sideways so that both are visible.
    if (order == 0) {
      ps.add(0, 0, 0.5f, 0, 0, 0, 1000, 0);
      ps.add(0.25f, 0, -0.5f, 0, 0, 0, 1000, 1);
    } else {
      ps.add(0.25f, 0, -0.5f, 0, 0, 0, 1000, 1);
      ps.add(0, 0, 0.5f, 0, 0, 0, 1000, 0);
    }
    renderer_->upload(ps.view(), nullptr);
    auto img = render(cam, W, H, s);
    ScreenPoint n = cam.project({0, 0, 0.5f}, W, H);
    ScreenPoint f = cam.project({0.25f + 0.25f, 0, -0.5f}, W, H);  // far sphere's right part
    Px pn = at(img, W, int(n.x), int(n.y));
    Px pf = at(img, W, int(f.x), int(f.y));
    // Lit colours are scaled copies of the base colour: compare hue via dominant channels.
    // Near: viridis(0) is violet (b > g); far: viridis(1) is yellow (r, g > b).
    EXPECT_GT(pn.b, pn.g) << "order " << order << ": near sphere hidden (" << pn.r << "," << pn.g
                          << "," << pn.b << ")";
    EXPECT_GT(pf.r, pf.b) << "order " << order << ": far sphere missing";
    EXPECT_GT(pf.g, pf.b);
    (void)near_c;
    (void)far_c;
  }
}

TEST_P(RenderGl, ImpostorDepthIsCurved) {
  // A small sphere placed just behind a big one's centre plane but in front of its surface
  // must be hidden: flat billboard depth would show it, ray-cast depth does not.
  constexpr int W = 96, H = 96;
  Camera cam;
  cam.yaw = 0;
  cam.pitch = 0;
  cam.distance = 3;
  RenderSettings s = plain();
  s.particle_radius = 0.4f;
  s.color = ColorMode::Pressure;
  s.auto_range = false;
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  Particles ps;
  ps.add(0, 0, 0, 0, 0, 0, 1000, 1);      // big sphere, yellow, front surface at z = 0.4
  ps.add(0, 0, 0.3f, 0, 0, 0, 1000, 0);   // same radius, centre 0.3 closer: its surface at 0.7
  renderer_->upload(ps.view(), nullptr);
  auto img = render(cam, W, H, s);
  ScreenPoint c = cam.project({0, 0, 0.3f}, W, H);
  Px p = at(img, W, int(c.x), int(c.y));
  EXPECT_GT(p.b, p.g) << "nearer sphere should cover the centre";
  // Now the nearer one is inside the other except for a cap: at the centre the front sphere
  // (z=0.3) still wins; near the silhouette of the back sphere only the back one shows.
  ScreenPoint edge = cam.project({0.38f, 0, 0.0f}, W, H);
  Px e = at(img, W, int(edge.x), int(edge.y));
  EXPECT_TRUE(e.r > 40 || e.g > 40) << "sphere edge missing";
}

TEST_P(RenderGl, DiscsIn2D) {
  constexpr int W = 128, H = 96;
  Particles ps;
  ps.dim = 2;
  std::vector<std::pair<float, float>> pts = {{0.2f, 0.2f}, {0.5f, 0.3f}, {0.8f, 0.7f}};
  for (auto [x, y] : pts) ps.add(x, y, 0);
  renderer_->set_domain(2, {0, 0, 0}, {1, 1, 0});
  renderer_->upload(ps.view(), nullptr);
  Camera cam;
  cam.dim = 2;
  cam.frame({0, 0, 0}, {1, 1, 0}, float(W) / H);
  RenderSettings s = plain();
  s.particle_radius = 0.05f;
  auto img = render(cam, W, H, s);
  for (auto [x, y] : pts) {
    ScreenPoint sp = cam.project({x, y, 0}, W, H);
    EXPECT_TRUE(is_water(at(img, W, int(sp.x), int(sp.y))));
  }
  ScreenPoint empty = cam.project({0.8f, 0.2f, 0}, W, H);
  EXPECT_TRUE(is_bg(at(img, W, int(empty.x), int(empty.y)), bg(s)));
  // The disc radius in pixels matches the world radius.
  ScreenPoint c = cam.project({0.5f, 0.3f, 0}, W, H);
  float rpx = 0.05f / cam.world_per_pixel(H);
  EXPECT_TRUE(is_water(at(img, W, int(c.x + rpx * 0.7f), int(c.y))));
  EXPECT_TRUE(is_bg(at(img, W, int(c.x + rpx * 1.3f + 1), int(c.y)), bg(s)));
}

TEST_P(RenderGl, LegendEndsMatchTheColourMap) {
  constexpr int W = 200, H = 160;
  Particles ps;
  for (int i = 0; i < 10; ++i) ps.add(0.1f * i, 0.5f, 0.5f, 0.3f * i, 0, 0);
  renderer_->set_domain(3, {0, 0, 0}, {1, 1, 1});
  renderer_->upload(ps.view(), nullptr);
  EXPECT_NEAR(renderer_->data_range(ColorMode::Speed).second, 2.7f, 1e-5f);
  Camera cam;
  cam.frame({0, 0, 0}, {1, 1, 1}, float(W) / H);
  for (ColorMap map : {ColorMap::Viridis, ColorMap::Turbo}) {
    RenderSettings s = plain();
    s.legend = true;
    s.color = ColorMode::Speed;
    s.map = map;
    auto img = render(cam, W, H, s);
    LegendLayout L = renderer_->legend_layout(W, H, s);
    ASSERT_TRUE(L.shown);
    EXPECT_NEAR(L.vmin, 0.0f, 1e-6f);
    EXPECT_NEAR(L.vmax, 2.7f, 1e-5f);
    // The bar maps its height linearly onto [0, 1]; compare the first and last rows with the
    // map at those rows' centres (turbo is steep at its ends).
    int cx = int(0.5f * (L.x0 + L.x1));
    int row_top = int(std::ceil(L.y0)), row_bottom = int(std::floor(L.y1)) - 1;
    float t_top = (L.y1 - (row_top + 0.5f)) / (L.y1 - L.y0);
    float t_bottom = (L.y1 - (row_bottom + 0.5f)) / (L.y1 - L.y0);
    EXPECT_GT(t_top, 0.97f);
    EXPECT_LT(t_bottom, 0.03f);
    Px top = at(img, W, cx, row_top), bottom = at(img, W, cx, row_bottom);
    Rgb hi = colormap(map, t_top), lo = colormap(map, t_bottom);
    const int tol = 4;
    EXPECT_NEAR(top.r, hi.r * 255, tol);
    EXPECT_NEAR(top.g, hi.g * 255, tol);
    EXPECT_NEAR(top.b, hi.b * 255, tol);
    EXPECT_NEAR(bottom.r, lo.r * 255, tol);
    EXPECT_NEAR(bottom.g, lo.g * 255, tol);
    EXPECT_NEAR(bottom.b, lo.b * 255, tol);
    // Range labels are drawn: some bright text pixels left of the bar.
    int text = 0;
    for (int y = int(L.y0); y < int(L.y1); ++y)
      for (int x = 0; x < int(L.x0); ++x) {
        Px p = at(img, W, x, y);
        if (p.r > 200 && p.g > 200 && p.b > 200) ++text;
      }
    EXPECT_GT(text, 10);
  }
  // Solid colour has no legend; a fixed range is reported as given.
  RenderSettings s = plain();
  s.legend = true;
  EXPECT_FALSE(renderer_->legend_layout(W, H, s).shown);
  s.color = ColorMode::Density;
  s.auto_range = false;
  s.range_min = 990;
  s.range_max = 1030;
  LegendLayout L = renderer_->legend_layout(W, H, s);
  EXPECT_EQ(L.vmin, 990);
  EXPECT_EQ(L.vmax, 1030);
}

TEST_P(RenderGl, DisplayModesFilterBoundaryParticles) {
  constexpr int W = 96, H = 96;
  Camera cam;
  cam.yaw = 0;
  cam.pitch = 0;
  cam.distance = 3;
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  Particles ps;
  ps.add(-0.6f, 0, 0);
  std::vector<float> bx = {0.0f, 0.6f}, by = {0, 0}, bz = {0, 0};
  std::vector<int32_t> owner = {0, -1};  // an obstacle particle and a wall particle
  BoundaryView b;
  b.dim = 3;
  b.count = 2;
  b.x[0] = bx.data();
  b.x[1] = by.data();
  b.x[2] = bz.data();
  b.owner = owner.data();
  renderer_->upload(ps.view(), &b);
  EXPECT_EQ(renderer_->obstacle_count(), 1u);
  EXPECT_EQ(renderer_->wall_count(), 1u);
  RenderSettings s = plain();
  s.particle_radius = 0.2f;
  ScreenPoint pf = cam.project({-0.6f, 0, 0}, W, H), po = cam.project({0, 0, 0}, W, H),
              pw = cam.project({0.6f, 0, 0}, W, H);
  auto visible = [&](const std::vector<unsigned char>& img, ScreenPoint p) {
    return !is_bg(at(img, W, int(p.x), int(p.y)), bg(s));
  };
  s.display = DisplayMode::Fluid;
  auto a = render(cam, W, H, s);
  EXPECT_TRUE(visible(a, pf));
  EXPECT_FALSE(visible(a, po));
  EXPECT_FALSE(visible(a, pw));
  // Obstacles are drawn as solids (render_solid_gl_test), not from their boundary particles.
  s.display = DisplayMode::FluidObstacles;
  auto o = render(cam, W, H, s);
  EXPECT_TRUE(visible(o, pf));
  EXPECT_FALSE(visible(o, po));
  EXPECT_FALSE(visible(o, pw));
  s.display = DisplayMode::All;
  auto all = render(cam, W, H, s);
  EXPECT_TRUE(visible(all, po));
  EXPECT_TRUE(visible(all, pw));
  Px grey = at(all, W, int(po.x), int(po.y));
  EXPECT_LT(std::abs(grey.r - grey.b), 25);  // boundary samples are grey, not water blue
}

TEST_P(RenderGl, GridWallsAndLegendDrawWithoutErrors) {
  constexpr int W = 160, H = 120;
  Particles ps;
  for (int i = 0; i < 50; ++i) ps.add(0.02f * i, 0.1f, 0.5f, 0.1f * i, 0.05f * i, 0, 1000 + i, 10.0f * i);
  renderer_->set_domain(3, {0, 0, 0}, {1, 0.6f, 0.8f});
  renderer_->upload(ps.view(), nullptr);
  Camera cam;
  cam.frame({0, 0, 0}, {1, 0.6f, 0.8f}, float(W) / H);
  for (ColorMode m : {ColorMode::Solid, ColorMode::Speed, ColorMode::Velocity, ColorMode::Pressure,
                      ColorMode::Density, ColorMode::LogDensity}) {
    RenderSettings s;
    s.primitive = GetParam();
    s.color = m;
    s.particle_radius = 0.02f;
    OffscreenTarget t(W, H);
    t.bind();
    DrawStats st = renderer_->draw(cam, W, H, s);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << color_mode_name(m);
    EXPECT_LE(st.draw_calls, 8);  // a handful, independent of N
    EXPECT_EQ(st.particles_drawn, 50u);
    EXPECT_EQ(st.points, GetParam() == ParticlePrimitive::Points);
    auto img = t.read_rgba();
    EXPECT_FALSE(image_is_blank(img));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

TEST_P(RenderGl, AutoPrimitiveFallsBackToQuadsForHugeParticles) {
  if (GetParam() != ParticlePrimitive::Points) return;  // independent of the parameter
  constexpr int W = 64, H = 64;
  Particles ps;
  ps.add(0, 0, 0);
  renderer_->set_domain(3, {-1, -1, -1}, {1, 1, 1});
  renderer_->upload(ps.view(), nullptr);
  Camera cam;
  cam.frame({-1, -1, -1}, {1, 1, 1}, 1.0f);
  RenderSettings s = plain();
  s.primitive = ParticlePrimitive::Auto;
  s.particle_radius = 0.01f;
  OffscreenTarget t(W, H);
  t.bind();
  EXPECT_TRUE(renderer_->draw(cam, W, H, s).points);
  s.particle_radius = 0.5f;
  cam.distance = 1.2f;  // a sphere filling the view: wider than any point sprite allows
  EXPECT_FALSE(renderer_->draw(cam, 4096, 4096, s).points);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

TEST_P(RenderGl, SnapshotRoundTrip) {
  Particles ps;
  ps.add(1, 2, 3, 4, 5, 6, 1001, 7);
  std::vector<float> bx = {9}, by = {8}, bz = {7};
  std::vector<int32_t> owner = {-1};
  BoundaryView b;
  b.count = 1;
  b.x[0] = bx.data(); b.x[1] = by.data(); b.x[2] = bz.data();
  b.owner = owner.data();
  ParticleSnapshot snap;
  snap.copy_from(ps.view(), &b);
  ParticleView v = snap.fluid();
  ASSERT_EQ(v.count, 1u);
  EXPECT_EQ(v.x[2][0], 3);
  EXPECT_EQ(v.v[1][0], 5);
  EXPECT_EQ(v.density[0], 1001);
  EXPECT_EQ(v.pressure[0], 7);
  EXPECT_EQ(snap.boundary().x[0][0], 9);
  EXPECT_EQ(snap.boundary().owner[0], -1);
}

TEST(RenderOutput, PngSequenceAndFfmpeg) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("rtsph_render_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  constexpr int W = 33, H = 17;  // odd sizes: the MP4 encoder pads them
  std::vector<unsigned char> img(W * H * 4, 0);
  for (int i = 0; i < W * H; ++i) img[i * 4 + 0] = static_cast<unsigned char>(i), img[i * 4 + 3] = 255;
  EXPECT_FALSE(image_is_blank(img));
  EXPECT_TRUE(image_is_blank(std::vector<unsigned char>(16, 3)));
  std::string err;
  auto seq = make_png_sequence_sink((dir / "frames").string(), W, H, "frame_", &err);
  ASSERT_TRUE(seq) << err;
  EXPECT_TRUE(seq->write(img.data()));
  EXPECT_TRUE(seq->write(img.data()));
  EXPECT_TRUE(seq->close());
  EXPECT_TRUE(fs::exists(dir / "frames" / "frame_000000.png"));
  EXPECT_TRUE(fs::exists(dir / "frames" / "frame_000001.png"));
  std::string ffmpeg = find_on_path("ffmpeg");
  if (!ffmpeg.empty()) {
    auto mp4 = make_ffmpeg_sink(ffmpeg, (dir / "v.mp4").string(), W, H, 10, &err);
    ASSERT_TRUE(mp4) << err;
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(mp4->write(img.data()));
    EXPECT_TRUE(mp4->close()) << mp4->error();
    EXPECT_GT(fs::file_size(dir / "v.mp4"), 100u);
  }
  fs::remove_all(dir);
}
