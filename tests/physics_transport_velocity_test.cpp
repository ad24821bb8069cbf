// Issue 13's remedies: the transport-velocity formulation (solver.transport_velocity,
// src/solvers/transport_velocity.cpp, Adami, Hu & Adams 2013), the hydrostatic start
// (fluid.hydrostatic_start) and DFSPH's Jacobi relaxation for wide kernels: the properties they
// exist for, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "io/checkpoint.h"
#include "state_compare.h"
#include "test_scenes.h"

namespace rtsph {
namespace {

SimSpec taylor_green(int n, double transport_velocity) {
  SimSpec s;
  s.name = "taylor_green_test";
  s.dimension = 2;
  s.method = "wcsph";
  s.domain_min = {{0, 0, 0}};
  s.domain_max = {{1, 1, 0}};
  s.periodic = PeriodicAxes::XY;
  s.spacing = 1.0 / n;
  s.gravity = {};
  s.viscosity = 0.01;  // Re = U L / ν = 100
  s.speed_of_sound = 10;
  s.artificial_viscosity = 0;
  s.clamp_negative_pressure = false;
  s.kernel = KernelType::WendlandC2;
  s.smoothing_ratio = 2;
  s.transport_velocity = transport_velocity;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{1, 1, 0}}, {}});
  return s;
}

void set_vortex(Simulation& sim) {
  const auto v = sim.fluid();
  std::vector<float> x(v.x[0], v.x[0] + v.count), y(v.x[1], v.x[1] + v.count), vx(v.count), vy(v.count);
  const double k = 2 * M_PI;
  for (std::size_t i = 0; i < v.count; ++i) {
    vx[i] = float(-std::cos(k * x[i]) * std::sin(k * y[i]));
    vy[i] = float(std::sin(k * x[i]) * std::cos(k * y[i]));
  }
  const float* vs[3] = {vx.data(), vy.data(), nullptr};
  sim.overwrite_fluid(nullptr, vs);
}

double amplitude(const Simulation& sim) {  // √(2⟨|v|²⟩) = U e^{−bt} for the exact vortex
  const auto v = sim.fluid();
  double sum = 0;
  for (std::size_t i = 0; i < v.count; ++i) sum += double(v.v[0][i]) * v.v[0][i] + double(v.v[1][i]) * v.v[1][i];
  return std::sqrt(2 * sum / double(v.count));
}

// Least-squares slope of log(amplitude) over t ∈ [0, 1] s, sampled every 0.02 s.
double decay_rate(const SimSpec& spec) {
  auto sim = make_simulation(spec, 0);
  set_vortex(*sim);
  std::vector<double> t, la;
  double next = 0;
  while (sim->time() < 1.0) {
    if (sim->time() >= next) {
      t.push_back(sim->time());
      la.push_back(std::log(amplitude(*sim)));
      next += 0.02;
    }
    sim->step();
  }
  const double n = double(t.size());
  double st = 0, sl = 0, stt = 0, stl = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    st += t[i];
    sl += la[i];
    stt += t[i] * t[i];
    stl += t[i] * la[i];
  }
  return -(n * stl - st * sl) / (n * stt - st * st);
}

// Taylor–Green at Re = 100 (80², Wendland C2 at h = 2 spacings, c0 = 10 U): the amplitude decays
// at 8π²/Re. Measured 2026-11-24: with the transport velocity 0.7888 against 0.7896 (−0.1%);
// without it the particle arrangement disorders and the vortex decays 36% too fast (1.0744).
TEST(TransportVelocity, TaylorGreenDecaysAtTheViscousRate) {
  const double exact = 8 * M_PI * M_PI / 100;
  const double with = decay_rate(taylor_green(80, 1.0));
  const double without = decay_rate(taylor_green(80, 0.0));
  std::printf("Taylor-Green 80^2: decay rate %.4f with the transport velocity, %.4f without, exact %.4f\n", with,
              without, exact);
  EXPECT_NEAR(with / exact, 1.0, 0.05);
  EXPECT_GT(without / exact, 1.2);  // the stage is what brings it there
}

// The stage gathers per particle in the fixed order of the other sums: 1 and 2 threads give the
// same bits, and it acts (the run differs from the one without it).
TEST(TransportVelocity, BitwiseIdenticalFor1And2ThreadsAndActs) {
  SimSpec s = taylor_green(30, 1.0);
  SimSpec off = s;
  off.transport_velocity = 0;
  auto one = make_simulation(s, 1), two = make_simulation(s, 2), ref = make_simulation(off, 1);
  for (auto* sim : {one.get(), two.get(), ref.get()}) set_vortex(*sim);
  for (int i = 0; i < 100; ++i) { one->step(); two->step(); ref->step(); }
  auto positions = [](const Simulation& sim) {
    const auto v = sim.fluid();
    std::vector<float> p(v.x[0], v.x[0] + v.count);
    p.insert(p.end(), v.x[1], v.x[1] + v.count);
    p.insert(p.end(), v.v[0], v.v[0] + v.count);
    return p;
  };
  EXPECT_TRUE(positions(*one) == positions(*two));
  EXPECT_FALSE(positions(*one) == positions(*ref));
}

// DFSPH steps with the flow (Δt = 0.005 s here, c0Δt = 2h), so the transport velocity's
// background pressure ρ0c0², an explicit pressure, would cross two smoothing lengths per step:
// the vortex blew up at step 5 (density error 54%). It is capped at ρ0(cfl·h/Δt)².
// The box is periodic and full, so the density solve targets the kernel sums' mean, not ρ0
// (Dfsph::correct_density_error): the strained lattice sums up to 1% high on average, which no
// velocity field can remove. Targeting ρ0 instead, most density solves stopped at their
// iteration cap (19 of 60 steps) and the amplitude fell to 0.43 by t = 0.3 s (exact 0.79); now
// 0.73, no solve at its cap. What is left is lost while the lattice first rearranges (t ≈ 0.1-0.2 s).
TEST(TransportVelocity, DfsphTaylorGreenKeepsItsAmplitude) {
  SimSpec s = taylor_green(40, 1.0);
  s.method = "dfsph";
  auto sim = make_simulation(s, 2);
  set_vortex(*sim);
  const double a0 = amplitude(*sim);
  double worst = 0;
  int capped = 0;  // steps whose density or divergence solve stopped at its iteration cap
  while (sim->time() < 0.3) {
    sim->step();
    capped += !sim->solver_failure().empty();
    worst = std::max(worst, sim->stats().max_density_error);
  }
  const double a = amplitude(*sim), exact = a0 * std::exp(-8 * M_PI * M_PI / 100 * sim->time());
  std::printf("DFSPH Taylor-Green with p_b = rho0 c0^2: %llu steps (%d at the iteration cap), "
              "amplitude %.4f -> %.4f (exact %.4f), worst density error %.3f%%\n",
              (unsigned long long)sim->step_count(), capped, a0, a, exact, 100 * worst);
  EXPECT_LT(worst, 0.05);
  EXPECT_EQ(capped, 0);
  EXPECT_GT(a / exact, 0.9);
  EXPECT_LT(a / exact, 1.0);  // nothing feeds the vortex
}

// ṽ − v (the transport_dv.* method fields) travels in checkpoints: a resumed run continues bitwise
// as the straight one. DFSPH at a small p_b (at ρ0c0² its CFL step overshoots, docs/validation.md).
TEST(TransportVelocity, CheckpointResumesBitwise) {
  for (const char* method : {"wcsph", "dfsph"}) {
    SCOPED_TRACE(method);
    SimSpec s = taylor_green(30, std::string(method) == "wcsph" ? 1.0 : 0.01);
    s.method = method;
    auto first = make_simulation(s, 2);
    set_vortex(*first);
    for (int i = 0; i < 30; ++i) first->step();
    const auto file = std::filesystem::temp_directory_path() / (std::string("rtsph_tvf_") + method + ".ckpt");
    io::write_checkpoint(file, *first, 42);
    auto resumed = make_simulation(s, 2);
    io::read_checkpoint(file, *resumed, 42);
    for (int i = 0; i < 30; ++i) { first->step(); resumed->step(); }
    test::expect_same_state(*first, *resumed);
    std::filesystem::remove(file);
  }
}

// fluid.hydrostatic_start: a WCSPH tank starts with the pressure ρ0 g (H − y) below its surface
// layers instead of p = 0, and so starts without the settling slosh. Measured 2026-11-24: worst
// interior row 1.3% off; peak kinetic energy in the first 0.3 s 0.108 J against 0.285 J from the
// lattice at ρ0 (what is left: the surface rows, whose kernel sums are truncated, and the
// lattice's own rearrangement).
TEST(HydrostaticStart, TankStartsAtHydrostaticPressureAndStaysQuiet) {
  const double W = 0.5, H = 0.25, s = 0.0125, rho0 = 1000, g = 9.81;
  double ke[2] = {};
  for (int on = 0; on < 2; ++on) {
    SimSpec spec = test::tank(2, W, H, s);
    spec.hydrostatic_start = on;
    auto sim = make_simulation(spec, 0);
    if (on) {
      // Rows below the top three (whose kernel sums are truncated at the surface) and above
      // the bottom one (wall): layer-averaged pressure against ρ0 g (H − y) at the lattice
      // height, H the block's top.
      const auto v = sim->fluid();
      double worst = 0;
      for (int row = 1; row < int(H / s) - 3; ++row) {
        double p = 0, y = 0;
        int n = 0;
        for (std::size_t i = 0; i < v.count; ++i)
          if (v.x[0][i] > 3 * s && v.x[0][i] < W - 3 * s && int(std::floor(v.x[1][i] / s)) == row) {
            p += v.pressure[i];
            y += v.x[1][i];
            ++n;
          }
        ASSERT_GT(n, 0);
        const double exact = rho0 * g * (H - (row + 0.5) * s);
        worst = std::max(worst, std::abs(p / n - exact) / exact);
      }
      std::printf("hydrostatic start: worst interior row pressure error %.4f\n", worst);
      EXPECT_LT(worst, 0.05);
    }
    while (sim->time() < 0.3) {
      sim->step();
      ke[on] = std::max(ke[on], sim->stats().kinetic_energy_j);
    }
  }
  std::printf("peak kinetic energy in the first 0.3 s: %.4g J from the lattice, %.4g J hydrostatic start\n",
              ke[0], ke[1]);
  EXPECT_LT(ke[1], 0.5 * ke[0]);
}

// DFSPH's Jacobi ω comes from the rest lattice's stiffest mode (Dfsph::jacobi_relaxation): with
// the Wendland C2 kernel at h = 2 spacings (44 neighbours in 2D, λmax = 5.67) the fixed ω = 0.5
// amplified that mode 1.8-fold per sweep and a periodic box of fluid at rest blew up within 8
// steps (velocity noise ×4 per step, measured). It must stay at rest.
TEST(DfsphJacobi, WideKernelFluidAtRestStaysAtRest) {
  SimSpec s = taylor_green(50, 0.0);
  s.method = "dfsph";
  auto sim = make_simulation(s, 0);
  for (int i = 0; i < 40; ++i) sim->step();
  const auto v = sim->fluid();
  double vmax = 0;
  for (std::size_t i = 0; i < v.count; ++i) vmax = std::max({vmax, double(std::abs(v.v[0][i])), double(std::abs(v.v[1][i]))});
  std::printf("DFSPH, Wendland C2 h = 2s, periodic box at rest: max speed after 40 steps %.3g m/s\n", vmax);
  EXPECT_LT(vmax, 1e-3);
}

}  // namespace
}  // namespace rtsph
