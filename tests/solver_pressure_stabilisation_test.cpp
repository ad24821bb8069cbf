// solver.dfsph.pressure_stabilisation (solvers/dfsph_solve.cpp): a Laplacian of the pressure in
// DFSPH's density solve fixes the layer-alternating pressure that a lattice's gradient sums
// cannot see, and leaves a hydrostatic pressure alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "solvers/simulation.h"
#include "test_scenes.h"

namespace rtsph {
namespace {

constexpr double kSpacing = 0.0125;
constexpr int kColumns = 12, kLayers = 16;

// The quick 3D tank of `rtsph validate hydrostatic_3d` (16 layers at 0.0125 m, α = 0.1 to damp the
// start's slosh, the pressure's time-weighted mean over the last 0.3 s of 1 s), narrower (12 × 12
// columns instead of 24 × 24), with DFSPH at the standing wave's wide kernel (Wendland C2 at
// h = 1.5 spacings, three wall layers) and the lattice's surface sums, where the alternating
// mode was found (docs/validation-history.md, standing wave, session 47).
SimSpec tank(double beta) {
  const double w = kColumns * kSpacing, depth = kLayers * kSpacing;
  SimSpec s = test::tank(3, w, depth, kSpacing);
  s.method = "dfsph";
  s.artificial_viscosity = 0.1;
  s.kernel = KernelType::WendlandC2;
  s.smoothing_ratio = 1.5;
  s.boundary_layers = 3;
  s.dfsph_surface_density = SurfaceDensity::Lattice;
  s.dfsph_pressure_stabilisation = beta;
  return s;
}

// Mean pressure of each layer, bottom up (Pa), time-weighted over the window. The layers by
// height: the lattice keeps kColumns² particles in each (it stays a lattice).
std::vector<double> settle(double beta) {
  auto sim = make_simulation(tank(beta), 1);
  const std::size_t per = std::size_t(kColumns) * kColumns;
  std::vector<double> p(kLayers, 0.0);
  double weight = 0;
  std::vector<std::size_t> order;
  while (sim->time() < 1.0) {
    const double t0 = sim->time();
    sim->step();
    if (t0 < 0.7) continue;
    const double w = sim->time() - t0;
    const ParticleView f = sim->fluid();
    order.resize(f.count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return f.x[1][a] < f.x[1][b]; });
    for (int k = 0; k < kLayers; ++k) {
      double sum = 0;
      for (std::size_t n = 0; n < per; ++n) sum += f.pressure[order[k * per + n]];
      p[k] += w * sum / double(per);
    }
    weight += w;
  }
  for (double& v : p) v /= weight;
  return p;
}

// The second difference of the layer means, over a layer's hydrostatic step ρ0 g s: zero for a
// linear profile, ±4 times the amplitude for an alternating one. The worst interior layer.
double alternation(const std::vector<double>& p) {
  const double step = 1000.0 * 9.81 * kSpacing;
  double worst = 0;
  for (int k = 1; k + 1 < kLayers - 2; ++k)
    worst = std::max(worst, std::abs(p[k - 1] - 2 * p[k] + p[k + 1]) / step);
  return worst;
}

// The alternation falls as β grows, and the hydrostatic pressure stays. Measured (this tank; the
// worst second difference over ρ0 g s): 1.49 at β = 0, 0.93 at 1, 0.40 at 3; in the validate
// case's wider tank (24 × 24 columns) β = 1 took its profile's error from 4.8% to 0.7%
// (docs/validation-history.md, standing wave, session 48).
TEST(PressureStabilisation, FixesTheLayerAlternatingPressure) {
  const std::vector<double> off = settle(0.0), one = settle(1.0), three = settle(3.0);
  std::printf("worst second difference of the layer means over rho0 g s: beta 0: %.3f, 1: %.3f, 3: %.3f\n",
              alternation(off), alternation(one), alternation(three));
  for (int k = 0; k < kLayers; ++k) std::printf("  layer %2d: %8.1f %8.1f %8.1f Pa\n", k, off[k], one[k], three[k]);
  EXPECT_GT(alternation(off), 1.0);  // the mode is there to fix
  EXPECT_LT(alternation(one), 0.8 * alternation(off));
  EXPECT_LT(alternation(three), 0.4 * alternation(off));
  // The hydrostatic pressure itself stays: layer k carries the water above its middle,
  // (kLayers − k − ½) spacings of it.
  auto weight = [](int k) { return 1000.0 * 9.81 * (kLayers - k - 0.5) * kSpacing; };
  for (const auto* p : {&off, &one, &three})
    for (int k : {0, kLayers / 4, kLayers / 2}) EXPECT_NEAR((*p)[k], weight(k), 0.03 * weight(0)) << "layer " << k;
}

}  // namespace
}  // namespace rtsph
