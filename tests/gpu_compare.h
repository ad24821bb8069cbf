#pragma once
// What the GPU backend's GL tests share: the fixture that gives each test a headless GL context
// (or skips it), and comparisons of a GPU run with a CPU run particle by particle (by id).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>

#include "gl_test_context.h"
#include "solvers/simulation.h"

namespace rtsph::test {

class GpuBackend : public ::testing::Test {
 protected:
  void SetUp() override { RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx_); }
  void TearDown() override { ctx_.reset(); }
  std::unique_ptr<render::HeadlessContext> ctx_;
};

// Where each particle id sits in a view.
inline std::unordered_map<std::uint32_t, std::size_t> index_by_id(const ParticleView& v) {
  std::unordered_map<std::uint32_t, std::size_t> m;
  for (std::size_t i = 0; i < v.count; ++i) m[v.id[i]] = i;
  return m;
}

inline double relative_rms_density(const Simulation& a, const Simulation& b) {
  const ParticleView va = a.fluid(), vb = b.fluid();
  EXPECT_EQ(va.count, vb.count);
  const auto ib = index_by_id(vb);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < va.count; ++i) {
    const double ra = va.density[i], rb = vb.density[ib.at(va.id[i])];
    num += (ra - rb) * (ra - rb);
    den += ra * ra;
  }
  return std::sqrt(num / den);
}

// The largest pressure difference between a particle in `a` and the same particle in `b` (Pa).
inline double worst_pressure_difference(const Simulation& a, const Simulation& b) {
  const ParticleView va = a.fluid(), vb = b.fluid();
  EXPECT_EQ(va.count, vb.count);
  const auto ib = index_by_id(vb);
  double worst = 0;
  for (std::size_t i = 0; i < va.count; ++i)
    worst = std::max(worst, std::abs(double(va.pressure[i]) - double(vb.pressure[ib.at(va.id[i])])));
  return worst;
}

// The largest distance between a particle in `a` and the same particle in `b`, seen across the
// seams of periodic axes (period L[k] > 0).
inline double worst_position_difference(const Simulation& a, const Simulation& b, const double* period) {
  const ParticleView va = a.fluid(), vb = b.fluid();
  EXPECT_EQ(va.count, vb.count);
  const auto ib = index_by_id(vb);
  double worst = 0;
  for (std::size_t i = 0; i < va.count; ++i) {
    const std::size_t j = ib.at(va.id[i]);
    for (int k = 0; k < a.dimension(); ++k) {
      double d = double(va.x[k][i]) - double(vb.x[k][j]);
      if (period[k] > 0) d -= period[k] * std::round(d / period[k]);
      worst = std::max(worst, std::abs(d));
    }
  }
  return worst;
}

}  // namespace rtsph::test
