// Barnes-Hut octree (src/core/gravity_tree.h) against direct summation (gravity_direct.h),
// which is itself tested in core_gravity_test.cpp: the force error bound of issue 14
// (relative RMS ≤ 1e-3 at θ = 0.5) on a uniform and a clustered (Plummer) sphere, the error
// falling with θ, exactness at θ = 0 (every pair summed), bitwise determinism across thread
// counts, buffer reuse across rebuilds, and degenerate inputs (coincident particles, massless
// probes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/gravity_direct.h"
#include "core/gravity_tree.h"
#include "gravity_clouds.h"

namespace rtsph {
namespace {

struct Field {
  std::vector<float> a[3], pot;
  explicit Field(std::size_t n) {
    for (auto& v : a) v.resize(n);
    pot.resize(n);
  }
  float* acc[3] = {};
  float* const* ptr() {
    for (int k = 0; k < 3; ++k) acc[k] = a[k].data();
    return acc;
  }
};

Field direct(const test::Cloud& c, double G) {
  Field f(c.size());
  gravity_direct<3>(c.sources(), G, f.ptr(), f.pot.data(), ThreadPool(2));
  return f;
}

Field tree(const test::Cloud& c, double G, double theta, int threads, GravityTree* t = nullptr) {
  GravityTree local;
  GravityTree& tr = t ? *t : local;
  const ThreadPool pool(threads);
  tr.build(c.sources(), pool);
  Field f(c.size());
  tr.accelerations(G, theta, f.ptr(), f.pot.data(), pool);
  return f;
}

// √(Σ|aᵢ - bᵢ|² / Σ|bᵢ|²), the relative RMS error of the bound.
double rel_rms(const Field& got, const Field& ref) {
  double e = 0, s = 0;
  for (std::size_t i = 0; i < ref.pot.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double d = double(got.a[k][i]) - ref.a[k][i];
      e += d * d;
      s += double(ref.a[k][i]) * ref.a[k][i];
    }
  return std::sqrt(e / s);
}
double rel_rms_pot(const Field& got, const Field& ref) {
  double e = 0, s = 0;
  for (std::size_t i = 0; i < ref.pot.size(); ++i) {
    const double d = double(got.pot[i]) - ref.pot[i];
    e += d * d;
    s += double(ref.pot[i]) * ref.pot[i];
  }
  return std::sqrt(e / s);
}

// Smoothing lengths as SPH sets them: ~50 neighbours within 2h (uniform: n·(4/3)π(2h)³/V;
// Plummer: at the centre, h growing outward with the spacing).
test::Cloud sphere() { return test::uniform_sphere(4000, 1.0, 1.0, 0.10, 0.13, 21); }
test::Cloud clustered() { return test::plummer(4000, 1.0, 1.0, 0.12, 22); }

// Issue 14's bound at θ = 0.5, and the error falls monotonically as θ shrinks (0.9 → 0.3);
// at θ = 0 every node is opened, so the tree sums exactly the pairs of direct summation: equal
// to float rounding (1e-6).
void check_accuracy(const test::Cloud& c, const char* name) {
  const double G = 1.3;
  const Field ref = direct(c, G);
  double prev = 1;
  for (double theta : {0.9, 0.7, 0.5, 0.3}) {
    const Field f = tree(c, G, theta, 2);
    const double err = rel_rms(f, ref), perr = rel_rms_pot(f, ref);
    if (theta == 0.5) {
      EXPECT_LE(err, 1e-3) << name;
      EXPECT_LE(perr, 1e-3) << name;
      const std::string key = std::string(name) + "_theta_0.5";
      ::testing::Test::RecordProperty(key + "_force_err", std::to_string(err));
      ::testing::Test::RecordProperty(key + "_pot_err", std::to_string(perr));
    }
    EXPECT_LT(err, prev) << name << " θ=" << theta;
    prev = err;
    // The tree's pair terms are not antisymmetric (i may see j's node while j sums i), so
    // momentum holds only to the force error: |Σ mᵢaᵢ| ≤ 1e-3 Σ mᵢ|aᵢ| at θ ≤ 0.5.
    if (theta <= 0.5) {
      double p[3] = {0, 0, 0}, scale = 0;
      for (std::size_t i = 0; i < c.size(); ++i) {
        double a2 = 0;
        for (int k = 0; k < 3; ++k) {
          p[k] += double(c.m[i]) * f.a[k][i];
          a2 += double(f.a[k][i]) * f.a[k][i];
        }
        scale += c.m[i] * std::sqrt(a2);
      }
      const double ratio = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / scale;
      EXPECT_LE(ratio, 1e-3) << name << " θ=" << theta;
      if (theta == 0.5)
        ::testing::Test::RecordProperty(std::string(name) + "_theta_0.5_momentum",
                                        std::to_string(ratio));
    }
  }
  const Field exact = tree(c, G, 0.0, 2);
  EXPECT_LT(rel_rms(exact, ref), 1e-6) << name;
  EXPECT_LT(rel_rms_pot(exact, ref), 1e-6) << name;
}

TEST(GravityTree, UniformSphereMatchesDirectSum) { check_accuracy(sphere(), "uniform"); }
TEST(GravityTree, PlummerSphereMatchesDirectSum) { check_accuracy(clustered(), "plummer"); }

TEST(GravityTree, BitwiseIdenticalForOneAndTwoThreads) {
  const test::Cloud c = clustered();
  const Field one = tree(c, 1.0, 0.5, 1), two = tree(c, 1.0, 0.5, 2);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(0, std::memcmp(one.a[k].data(), two.a[k].data(), c.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(one.pot.data(), two.pot.data(), c.size() * sizeof(float)));
}

// Degenerate sizes: nothing to do, and a lone particle feels no force and no potential.
TEST(GravityTree, EmptyAndSingleParticle) {
  test::Cloud c;
  Field none = tree(c, 1.0, 0.5, 2);
  EXPECT_TRUE(none.pot.empty());
  const double p[3] = {1, 2, 3};
  c.push(p, 2.0, 0.1);
  const Field one = tree(c, 1.0, 0.5, 2);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(one.a[k][0], 0.0f);
  EXPECT_EQ(one.pot[0], 0.0f);
}

// A second build and walk of the same size reuses every buffer (no growth) and reproduces the
// first result bit for bit; moving the particles (a step later) does not grow them either
// beyond the first build's geometric headroom.
TEST(GravityTree, RebuildReusesBuffers) {
  test::Cloud c = clustered();
  GravityTree t;
  const Field first = tree(c, 1.0, 0.5, 2, &t);
  const std::size_t bytes = t.memory_bytes();
  const Field second = tree(c, 1.0, 0.5, 2, &t);
  EXPECT_EQ(t.memory_bytes(), bytes);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(0, std::memcmp(first.a[k].data(), second.a[k].data(), c.size() * sizeof(float)));
  EXPECT_GT(t.node_count(), c.size() / 8);
  EXPECT_GT(t.mean_node_interactions(), 0.0);
}

// Forty particles on one spot (more than a leaf holds, all in one Morton cell, so the build
// stops at the deepest level) plus a cluster, and massless probes far away: the tree still
// equals direct summation, and probes feel the field without adding to it.
TEST(GravityTree, CoincidentParticlesAndMasslessProbes) {
  test::Cloud c;
  const double spot[3] = {0.3, -0.2, 0.1};
  for (int i = 0; i < 40; ++i) c.push(spot, 0.01, 0.05);
  const test::Cloud cl = test::plummer(500, 0.5, 1.0, 0.02, 4);
  for (std::size_t i = 0; i < cl.size(); ++i) {
    const double p[3] = {cl.x[0][i], cl.x[1][i], cl.x[2][i]};
    c.push(p, cl.m[i], cl.h[i]);
  }
  for (int i = 0; i < 20; ++i) {
    const double p[3] = {5.0 + i, 3.0, -4.0};
    c.push(p, 0.0, 0.05);
  }
  const Field ref = direct(c, 1.0), f = tree(c, 1.0, 0.5, 2);
  EXPECT_LE(rel_rms(f, ref), 1e-3);
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(f.a[k][i])) << i;
  // The coincident particles pull each other with zero net force (r = 0): they move together.
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(f.a[k][0], f.a[k][39], 1e-6 * std::fabs(ref.a[k][0]) + 1e-9);
}

}  // namespace
}  // namespace rtsph
