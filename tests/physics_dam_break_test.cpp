// 2D dam break against Martin & Moyce 1952, "An experimental study of the collapse of liquid
// columns on a rigid horizontal plane", Phil. Trans. R. Soc. A 244, n² = 2.
//
// The experiment's clock. Its first point (T = 0.41) sits where an instantly released column
// is; its front then advances only 0.11a up to T = 0.84 before moving at a steady speed. Every
// numerical study we know of (SPH, MPS, VOF), and rtsph at any resolution, kernel, h/spacing or
// c0, leads that data by 10–17% between T = 0.84 and 2.2 while matching the late front speed:
// the released column lags as if the release took a few milliseconds (Koshizuka & Oka's 1996
// repeat of the experiment lags the same way). So the comparison fits one parameter of the
// *experiment*, not of the solver: the time origin. The offset δT is chosen in [0, 0.3]
// (0 to 16 ms at Martin & Moyce's a = 57 mm) to minimise the largest error; the test asserts
// that such an offset exists with every point within 10%, and independently of any offset that
// the late front speed matches within 10%. The unshifted errors are printed and bounded too, so
// a solver change that moves the whole curve still fails. Figures: docs/validation.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "test_scenes.h"

namespace rtsph {
namespace {

// (T, Z) with T = t·√(2g/a) and Z = x/a, x the surge front measured from the back wall.
constexpr double kMartinMoyce[][2] = {{0.41, 1.11}, {0.84, 1.22}, {1.19, 1.44}, {1.43, 1.67},
                                      {1.63, 1.89}, {1.83, 2.11}, {1.98, 2.33}, {2.20, 2.56},
                                      {2.32, 2.78}, {2.51, 3.00}};
constexpr double kMaxOffset = 0.3;  // T units; ≈ 16 ms at a = 2.25 in

double front(const Simulation& sim, double spacing) {
  const auto v = sim.fluid();
  float xmax = 0;
  for (std::size_t i = 0; i < v.count; ++i) xmax = std::max(xmax, v.x[0][i]);
  return xmax + 0.5 * spacing;  // a particle stands for a cell of width one spacing
}

struct Trajectory {
  std::vector<double> T, Z;
  // Linear interpolation; before the start the column has not moved (Z = 1).
  double at(double t) const {
    if (t <= T.front()) return 1.0;
    const auto it = std::lower_bound(T.begin(), T.end(), t);
    if (it == T.end()) return Z.back();
    const std::size_t k = std::size_t(it - T.begin());
    const double w = (t - T[k - 1]) / (T[k] - T[k - 1]);
    return Z[k - 1] + w * (Z[k] - Z[k - 1]);
  }
  double max_error(double offset) const {
    double m = 0;
    for (const auto& row : kMartinMoyce) m = std::max(m, std::abs(at(row[0] - offset) / row[1] - 1));
    return m;
  }
};

// Every method, with the same checks: the surge front is the flow, not the pressure solver.
class DamBreak2D : public ::testing::TestWithParam<const char*> {};

TEST_P(DamBreak2D, SurgeFrontFollowsMartinMoyce) {
  const double a = 1.0, g = 9.81, spacing = 0.02;
  SimSpec spec = test::dam_break_2d(a, spacing);
  spec.method = GetParam();
  auto sim = make_simulation(spec, 0);
  const double time_scale = std::sqrt(2 * g / a);
  Trajectory tr;
  tr.T.push_back(0);
  tr.Z.push_back(front(*sim, spacing) / a);
  while (sim->time() * time_scale < 2.52) {
    sim->step();
    tr.T.push_back(sim->time() * time_scale);
    tr.Z.push_back(front(*sim, spacing) / a);
  }

  double best = 0;
  for (double off = 0; off <= kMaxOffset + 1e-9; off += 0.01)
    if (tr.max_error(off) < tr.max_error(best)) best = off;
  std::printf("%s: fitted clock offset dT = %.2f (%.1f ms at a = 2.25 in)\n", GetParam(), best,
              1e3 * best / std::sqrt(2 * g / 0.05715));
  for (const auto& row : kMartinMoyce) {
    const double T = row[0], z0 = tr.at(T), z = tr.at(T - best);
    std::printf("T = %.2f  Z_exp = %.2f  Z_sph = %.3f (%+5.1f%%)  shifted %.3f (%+5.1f%%)\n", T,
                row[1], z0, 100 * (z0 / row[1] - 1), z, 100 * (z / row[1] - 1));
    EXPECT_LT(std::abs(z / row[1] - 1), 0.10) << "at T = " << T << " with offset " << best;
    EXPECT_LT(std::abs(z0 / row[1] - 1), 0.20) << "unshifted, at T = " << T;
  }

  const double speed_sph = (tr.at(2.51) - tr.at(1.43)) / (2.51 - 1.43);
  const double speed_exp = (3.00 - 1.67) / (2.51 - 1.43);
  std::printf("front speed dZ/dT over T in [1.43, 2.51]: SPH %.3f, experiment %.3f\n", speed_sph,
              speed_exp);
  EXPECT_NEAR(speed_sph, speed_exp, 0.10 * speed_exp);
  EXPECT_EQ(sim->stats().particles_put_back, 0u);
  std::printf("max density error %.2f%%\n", 100 * sim->stats().max_density_error);
  // The worst particle's compression: WCSPH (c0 = 10 v_max) 1.2%, DFSPH 3.5%. DFSPH's walls
  // mirror the particle's velocity as its pressure (src/solvers/dfsph_solve.cpp), so its
  // prediction counts a particle's lift off the floor twice and the solve leaves the worst one,
  // at the surge front (t = 0.23 s), 3.5% compressed (1.6% with the wall counted once in the
  // rate, whose solve gained energy at rest). PBF's four Jacobi iterations leave single particles at the
  // impact up to 25% (measured 24.8%; its mean error is tested in solver_methods_test), so it is
  // printed, not bounded here.
  if (std::string(GetParam()) == "wcsph") {
    EXPECT_LT(sim->stats().max_density_error, 0.03);
  } else if (std::string(GetParam()) == "dfsph") {
    EXPECT_LT(sim->stats().max_density_error, 0.04);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, DamBreak2D, ::testing::Values("wcsph", "pbf", "dfsph"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace rtsph
