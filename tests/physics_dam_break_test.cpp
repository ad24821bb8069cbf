// 2D dam break against Martin & Moyce 1952, "An experimental study of the collapse of liquid
// columns on a rigid horizontal plane", Phil. Trans. R. Soc. A 244, Table 2, n² = 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "test_scenes.h"

namespace rtsph {
namespace {

// (T, Z) with T = t·√(2g/a) and Z = x/a, x the surge front measured from the back wall.
constexpr double kMartinMoyce[][2] = {{0.41, 1.11}, {0.84, 1.22}, {1.19, 1.44}, {1.43, 1.67},
                                      {1.63, 1.89}, {1.83, 2.11}, {1.98, 2.33}, {2.20, 2.56},
                                      {2.32, 2.78}, {2.51, 3.00}};

double front(const Simulation& sim, double spacing) {
  const auto v = sim.fluid();
  float xmax = 0;
  for (std::size_t i = 0; i < v.count; ++i) xmax = std::max(xmax, v.x[0][i]);
  return xmax + 0.5 * spacing;  // a particle stands for a cell of width one spacing
}

TEST(DamBreak2D, SurgeFrontFollowsMartinMoyceWithin10Percent) {
  const double a = 1.0, g = 9.81, spacing = 0.02;
  auto sim = make_simulation(test::dam_break_2d(a, spacing), 0);
  const double time_scale = std::sqrt(2 * g / a);
  double worst = 0;
  for (const auto& row : kMartinMoyce) {
    const double t = row[0] / time_scale;
    while (sim->time() < t) sim->step();
    const double z = front(*sim, spacing) / a;
    const double err = std::abs(z - row[1]) / row[1];
    std::printf("T = %.2f  Z_sph = %.3f  Z_exp = %.2f  error %.1f%%\n", row[0], z, row[1], 100 * err);
    worst = std::max(worst, err);
    EXPECT_LT(err, 0.10) << "at T = " << row[0];
  }
  std::printf("worst relative error %.1f%%\n", 100 * worst);
  EXPECT_EQ(sim->stats().particles_put_back, 0u);
}

}  // namespace
}  // namespace rtsph
