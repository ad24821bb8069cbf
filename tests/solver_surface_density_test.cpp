// solver.dfsph.surface_density (solvers/surface_density.h): the rest lattice's cut kernel sums
// under a flat free surface, and DFSPH's clamped solve keeping them instead of ρ0, so that the
// surface band of a wide kernel rests at the fluid's spacing instead of compacting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <tuple>

#include "core/kernels.h"
#include "solvers/simulation.h"
#include "solvers/surface_density.h"
#include "lattice_params.h"
#include "test_scenes.h"

namespace rtsph {
namespace {

using test::resolve_params;

// The 2D tank of the measurements in docs/validation-history.md (standing wave, session 47): 0.2 m wide, 0.1 m deep,
// spacing 0.01 m, DFSPH with Wendland C2 at h = 1.5 spacings and three wall layers.
SimSpec wide_tank(SurfaceDensity target) {
  SimSpec s = test::tank(2, 0.2, 0.1, 0.01);
  s.domain_max = {{0.2, 0.2, 0}};
  s.method = "dfsph";
  s.kernel = KernelType::WendlandC2;
  s.smoothing_ratio = 1.5;
  s.boundary_layers = 3;
  s.dfsph_surface_density = target;
  return s;
}

struct Layers {
  double top = 0, second = 0, surface = -1;  // mean ρ of the top two layers, highest particle's y
};

// The top two lattice layers, four spacings or more from the side walls (whose samples fill the
// cut there), as they stand now.
Layers layers(const Simulation& sim, double spacing, double width) {
  const ParticleView f = sim.fluid();
  Layers out;
  for (std::size_t i = 0; i < f.count; ++i) out.surface = std::max(out.surface, double(f.x[1][i]));
  double sum[2] = {}, n[2] = {};
  for (std::size_t i = 0; i < f.count; ++i) {
    const double x = f.x[0][i], depth = out.surface - f.x[1][i];
    if (x < 4 * spacing || x > width - 4 * spacing) continue;
    const int layer = depth < 0.5 * spacing ? 0 : depth < 1.5 * spacing ? 1 : 2;
    if (layer < 2) { sum[layer] += f.density[i]; n[layer] += 1; }
  }
  out.top = sum[0] / std::max(1.0, n[0]);
  out.second = sum[1] / std::max(1.0, n[1]);
  return out;
}

// The table is the lattice's own: τ = 1 in the bulk (|c| = 0), rows ascending in |c| with τ
// falling toward the surface, and a lattice at rest reads ρ0 τ in its top two layers, to float
// round-off (the solver's density sums the same kernel over the same points).
TEST(SurfaceDensity, TheTableIsTheRestLatticesOwnSums) {
  for (auto [kernel, ratio] : {std::pair{KernelType::CubicSpline, 1.0}, std::pair{KernelType::WendlandC2, 1.5},
                               std::pair{KernelType::WendlandC2, 2.0}}) {
    SimSpec s = wide_tank(SurfaceDensity::Lattice);
    s.kernel = kernel;
    s.smoothing_ratio = ratio;
    const CutSumTable t = CutSumTable::build<2>(s, resolve_params(s));
    const auto& rows = t.rows();
    ASSERT_GE(rows.size(), 2u);
    EXPECT_EQ(rows.front().first, 0.0);
    EXPECT_NEAR(rows.front().second, 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(t.fraction(0.0), 1.0);
    for (std::size_t k = 1; k < rows.size(); ++k) {
      EXPECT_GT(rows[k].first, rows[k - 1].first);
      EXPECT_LT(rows[k].second, rows[k - 1].second + 0.01);  // the bulk's sums may read just over 1
    }
    EXPECT_DOUBLE_EQ(t.fraction(10 * rows.back().first), std::min(1.0, rows.back().second));  // past the top: the top
    auto sim = make_simulation(s, 1);
    const Layers at0 = layers(*sim, s.spacing, 0.2);
    std::printf("kernel %d h = %.1f s: top layer %.2f kg/m3 (table %.2f), second %.2f (table %.2f)\n",
                int(kernel), ratio, at0.top, 1000 * rows.back().second, at0.second,
                1000 * rows[rows.size() - 2].second);
    EXPECT_NEAR(at0.top, 1000 * rows.back().second, 0.05);
    EXPECT_NEAR(at0.second, 1000 * std::min(1.0, rows[rows.size() - 2].second), 0.05);
  }
}

// Water at rest, 0.5 s: with ρ0 as every particle's target the top layer (748 kg/m³ at the
// lattice spacing) compacts toward ρ0 and the surface sinks (measured: 838 kg/m³, 0.7 mm, rms
// speed 1.6 cm/s); with the lattice's sums it keeps its density within 1% and stays put (753
// kg/m³, 0.1 mm, 0.27 cm/s).
TEST(SurfaceDensity, TheSurfaceBandKeepsTheLatticeSpacing) {
  auto run = [](SurfaceDensity target) {
    auto sim = make_simulation(wide_tank(target), 1);
    const Layers a = layers(*sim, 0.01, 0.2);
    while (sim->time() < 0.5) sim->step();
    const Layers b = layers(*sim, 0.01, 0.2);
    const SimStats st = sim->stats();
    const double rms = std::sqrt(2 * st.kinetic_energy_j / (1000 * 1e-4 * double(st.fluid_particles)));
    std::printf("%s: top layer %.1f -> %.1f kg/m3, second %.1f -> %.1f, surface %.5f -> %.5f m, rms %.4f m/s\n",
                target == SurfaceDensity::Rest ? "rest" : "lattice", a.top, b.top, a.second, b.second,
                a.surface, b.surface, rms);
    return std::tuple{a, b, rms};
  };
  const auto [ra, rb, rrms] = run(SurfaceDensity::Rest);
  const auto [la, lb, lrms] = run(SurfaceDensity::Lattice);
  EXPECT_GT(rb.top - ra.top, 50.0);                 // compacts: 5% of ρ0 or more
  EXPECT_LT(std::abs(lb.top - la.top), 10.0);       // keeps the lattice's 748 kg/m³ within 1%
  EXPECT_LT(std::abs(lb.second - la.second), 10.0);
  EXPECT_LT(std::abs(lb.surface - la.surface), 0.05 * 0.01);  // the surface stays within 0.05 s
  EXPECT_LT(lrms, 0.5 * rrms);
}

// The option changes nothing without a free surface to cut the kernel: a two-sided (unclamped)
// solve keeps ρ0 everywhere, as its rarefied particles pull anyway.
TEST(SurfaceDensity, TwoSidedSolvesKeepRhoZero) {
  SimSpec rest = wide_tank(SurfaceDensity::Rest), lattice = wide_tank(SurfaceDensity::Lattice);
  rest.clamp_negative_pressure = lattice.clamp_negative_pressure = false;
  auto a = make_simulation(rest, 1), b = make_simulation(lattice, 1);
  for (int k = 0; k < 20; ++k) { a->step(); b->step(); }
  const ParticleView fa = a->fluid(), fb = b->fluid();
  ASSERT_EQ(fa.count, fb.count);
  for (std::size_t i = 0; i < fa.count; ++i) ASSERT_EQ(fa.x[1][i], fb.x[1][i]) << i;
}

}  // namespace
}  // namespace rtsph
