// The surface's splat batch (render/splat_batch.h): interior cubes of a filled lattice merge
// into one thickness splat each, the particles near the surface stay, and the total volume
// (the splats' summed weights) is the particle count. GL-free: compiles the source directly.
#include "render/splat_batch.cpp"  // NOLINT(bugprone-suspicious-include)

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace rtsph::render;

namespace {
struct Block {
  std::vector<float> x, y, z;
};
// nx × ny × nz particles on a lattice of the given spacing, half a spacing from the origin.
Block lattice(int nx, int ny, int nz, float h) {
  Block b;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        b.x.push_back((i + 0.5f) * h);
        b.y.push_back((j + 0.5f) * h);
        b.z.push_back((k + 0.5f) * h);
      }
  return b;
}
double total_weight(const SplatBatch& s) {
  double w = 0;
  for (std::size_t i = 0; i < s.size(); ++i) w += s.data()[3 * s.size() + i];
  return w;
}
}  // namespace

TEST(SplatBatch, FilledBlockMergesItsInteriorAndKeepsEveryParticlesVolume) {
  const float h = 0.02f;
  Block b = lattice(20, 40, 30, h);  // the 3D dam break's starting block
  SplatBatch s;
  s.build(b.x.data(), b.y.data(), b.z.data(), b.x.size(), h);
  // Cubes of two spacings: 10 × 20 × 15 of 8 particles; the 8 × 18 × 13 inside the outer
  // layer of cubes merge.
  EXPECT_EQ(s.merged_cubes(), 8u * 18u * 13u);
  EXPECT_EQ(s.size(), b.x.size() - 7 * s.merged_cubes());
  EXPECT_DOUBLE_EQ(total_weight(s), double(b.x.size()));
  // A merged splat sits at its cube's centroid, inside the block's interior.
  for (std::size_t i = 0; i < s.merged_cubes(); ++i) {
    EXPECT_EQ(s.data()[3 * s.size() + i], 8.0f);
    const float x = s.data()[i];
    EXPECT_GT(x, 2 * h);
    EXPECT_LT(x, 20 * h - 2 * h);
  }
}

TEST(SplatBatch, ThinSheetsAndStrayParticlesAreNotMerged) {
  const float h = 0.02f;
  Block sheet = lattice(40, 4, 40, h);  // two cubes thick: no cube has full neighbours on all sides
  SplatBatch s;
  s.build(sheet.x.data(), sheet.y.data(), sheet.z.data(), sheet.x.size(), h);
  EXPECT_EQ(s.merged_cubes(), 0u);
  EXPECT_EQ(s.size(), sheet.x.size());
  // Particles flung far apart would need a huge grid: all kept, positions unchanged.
  std::vector<float> x = {0, 1000, -1000}, y = {0, 0, 5}, z = {0, 1000, 0};
  s.build(x.data(), y.data(), z.data(), 3, h);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.data()[1], 1000.0f);
  EXPECT_EQ(s.data()[3 * 3 + 2], 1.0f);
  // Without z (2D) nothing is merged.
  Block b = lattice(20, 20, 1, h);
  s.build(b.x.data(), b.y.data(), nullptr, b.x.size(), h);
  EXPECT_EQ(s.size(), b.x.size());
  EXPECT_EQ(s.merged_cubes(), 0u);
}

TEST(SplatBatch, NonFinitePositionsKeepEveryParticle) {
  const float h = 0.02f;
  Block b = lattice(12, 12, 12, h);
  b.y[5] = std::nanf("");
  SplatBatch s;
  s.build(b.x.data(), b.y.data(), b.z.data(), b.x.size(), h);
  EXPECT_EQ(s.size(), b.x.size());
}
