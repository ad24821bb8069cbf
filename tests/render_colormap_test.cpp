// Colour maps: endpoints against the published maps, viridis' monotonic luminance, the LUT.
// The test links only the non-GL layers, so it compiles the (GL-free) source directly.
#include "render/colormap.cpp"  // NOLINT(bugprone-suspicious-include)

#include <gtest/gtest.h>

using namespace rtsph::render;

namespace {
void expect_near(Rgb c, float r, float g, float b, float tol) {
  EXPECT_NEAR(c.r, r, tol);
  EXPECT_NEAR(c.g, g, tol);
  EXPECT_NEAR(c.b, b, tol);
}
}  // namespace

TEST(Colormap, ViridisMatchesReferenceSamples) {
  // matplotlib viridis at 0, 0.25, 0.5, 0.75, 1.
  expect_near(colormap(ColorMap::Viridis, 0.0f), 0.267004f, 0.004874f, 0.329415f, 0.015f);
  expect_near(colormap(ColorMap::Viridis, 0.25f), 0.229739f, 0.322361f, 0.545706f, 0.015f);
  expect_near(colormap(ColorMap::Viridis, 0.5f), 0.127568f, 0.566949f, 0.550556f, 0.015f);
  expect_near(colormap(ColorMap::Viridis, 0.75f), 0.369214f, 0.788888f, 0.382914f, 0.02f);
  expect_near(colormap(ColorMap::Viridis, 1.0f), 0.993248f, 0.906157f, 0.143936f, 0.015f);
}

TEST(Colormap, TurboEndpointsAndMiddle) {
  // Dark blue-violet at 0, green-yellow in the middle, dark red at 1 (turbo's shape).
  Rgb lo = colormap(ColorMap::Turbo, 0), mid = colormap(ColorMap::Turbo, 0.5f),
      hi = colormap(ColorMap::Turbo, 1);
  expect_near(lo, 0.19f, 0.07f, 0.23f, 0.13f);
  expect_near(hi, 0.48f, 0.02f, 0.01f, 0.1f);
  EXPECT_GT(mid.g, 0.9f);
  EXPECT_LT(luminance(lo), luminance(mid));
  EXPECT_LT(luminance(hi), luminance(mid));
}

TEST(Colormap, ViridisLuminanceIsMonotonic) {
  float prev = -1;
  for (int i = 0; i <= 1000; ++i) {
    float l = luminance(colormap(ColorMap::Viridis, i / 1000.0f));
    EXPECT_GT(l, prev) << "t=" << i / 1000.0f;
    prev = l;
  }
  EXPECT_LT(luminance(colormap(ColorMap::Viridis, 0)), 0.03f);
  EXPECT_GT(luminance(colormap(ColorMap::Viridis, 1)), 0.7f);
}

TEST(Colormap, ClampsOutsideUnitInterval) {
  for (ColorMap m : {ColorMap::Viridis, ColorMap::Turbo}) {
    Rgb a = colormap(m, -3), b = colormap(m, 0), c = colormap(m, 7), d = colormap(m, 1);
    EXPECT_EQ(a.r, b.r);
    EXPECT_EQ(a.b, b.b);
    EXPECT_EQ(c.g, d.g);
    Rgb n = colormap(m, std::nanf(""));
    EXPECT_EQ(n.r, b.r);
    for (int i = 0; i <= 100; ++i) {
      Rgb x = colormap(m, i / 100.0f);
      for (float ch : {x.r, x.g, x.b}) {
        EXPECT_GE(ch, 0.0f);
        EXPECT_LE(ch, 1.0f);
      }
    }
  }
}

TEST(Colormap, LutEndsAreTheMapEnds) {
  for (ColorMap m : {ColorMap::Viridis, ColorMap::Turbo}) {
    auto lut = colormap_lut(m, 256);
    ASSERT_EQ(lut.size(), 256u * 4);
    Rgb lo = colormap(m, 0), hi = colormap(m, 1);
    EXPECT_NEAR(lut[0], lo.r * 255, 0.51);
    EXPECT_NEAR(lut[2], lo.b * 255, 0.51);
    EXPECT_NEAR(lut[255 * 4 + 0], hi.r * 255, 0.51);
    EXPECT_NEAR(lut[255 * 4 + 1], hi.g * 255, 0.51);
    EXPECT_EQ(lut[3], 255);
  }
}

TEST(Colormap, Names) {
  ColorMap m;
  EXPECT_TRUE(parse_colormap("turbo", &m));
  EXPECT_EQ(m, ColorMap::Turbo);
  EXPECT_EQ(colormap_name(m), "turbo");
  EXPECT_TRUE(parse_colormap("viridis", &m));
  EXPECT_EQ(m, ColorMap::Viridis);
  EXPECT_FALSE(parse_colormap("jet", &m));
}
