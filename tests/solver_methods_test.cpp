// Every registered method on the shared framework: bitwise identical for 1 and 2 threads,
// bitwise exact checkpoint resume (with emitters and a moving obstacle), every built-in scene
// runs, and the properties each method promises (DFSPH's density tolerance and convergence,
// PBF's reported density error).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <cmath>

#include "io/checkpoint.h"
#include "io/fnv.h"
#include "scene/scene.h"
#include "solvers/health.h"
#include "sanitizer_scale.h"
#include "state_compare.h"
#include "test_scenes.h"

namespace fs = std::filesystem;

namespace rtsph {
namespace {

using test::sanitizer_scale;

void run_until(Simulation& sim, double t) {
  while (sim.time() < t) sim.step();
}

using test::expect_same_state;

SimSpec with_method(SimSpec s, const std::string& method) {
  s.method = method;
  return s;
}

class Methods : public ::testing::TestWithParam<std::string> {};

TEST_P(Methods, AreRegistered) {
  const auto names = solver_methods();
  EXPECT_NE(std::find(names.begin(), names.end(), GetParam()), names.end());
  auto sim = make_simulation(with_method(test::dam_break_2d(0.2, 0.02), GetParam()), 1);
  EXPECT_EQ(sim->stats().method, GetParam());
}

TEST_P(Methods, OneAndTwoThreadsAreBitwiseIdentical) {
  for (int dim : {2, 3}) {
    SimSpec s = dim == 2 ? test::dam_break_2d(0.2, 0.01) : test::tank(3, 0.2, 0.15, 0.02);
    if (dim == 3) s.fluid_blocks[0].max = {{0.08, 0.15, 0.2}};  // a column that collapses
    s = with_method(s, GetParam());
    auto one = make_simulation(s, 1), two = make_simulation(s, 2);
    run_until(*one, 0.1 * sanitizer_scale());
    run_until(*two, 0.1 * sanitizer_scale());
    SCOPED_TRACE(std::to_string(dim) + "D");
    EXPECT_GT(one->step_count(), 3u);
    expect_same_state(*one, *two);
  }
}

TEST_P(Methods, ResumeIsBitwiseExactWithEmittersAndMovingObstacle) {
  SimSpec s = with_method(load_scene("nozzle_moving_obstacle_2d"), GetParam());
  const double T = 0.15 * sanitizer_scale();
  const fs::path file = fs::temp_directory_path() /
                        ("rtsph_methods_" + GetParam() + std::to_string(::getpid()) + ".ckpt");
  const std::uint64_t hash = io::hash_bytes(scene_to_json(s));
  auto straight = make_simulation(s, 2);
  run_until(*straight, T);
  const auto n_at_T = straight->fluid().count;
  run_until(*straight, 2 * T);
  EXPECT_GT(straight->fluid().count, n_at_T) << "the emitter should keep adding particles";
  {
    auto first = make_simulation(s, 2);
    run_until(*first, T);
    io::write_checkpoint(file, *first, hash);
  }
  auto resumed = make_simulation(s, 2);
  io::read_checkpoint(file, *resumed, hash);
  run_until(*resumed, 2 * T);
  expect_same_state(*straight, *resumed);
  fs::remove(file);
}

TEST_P(Methods, SnapshotRestoreIsBitwiseExact) {
  SimSpec s = with_method(test::dam_break_2d(0.2, 0.01), GetParam());
  auto sim = make_simulation(s, 2);
  run_until(*sim, 0.05 * sanitizer_scale());
  StateSnapshot snap;
  snap.capture(*sim);
  auto other = make_simulation(s, 2);
  snap.restore(*other);
  for (int i = 0; i < 5; ++i) { sim->step(); other->step(); }
  expect_same_state(*sim, *other);
}

// overwrite_fluid (the Python API's set_positions/set_velocities) with the state a simulation
// already has changes nothing: the re-sort keeps the memory order, a/ρ/p stay with their
// particles, and the method's caches are rebuilt to the same bits. Then a real edit moves
// exactly the particles it names.
TEST_P(Methods, OverwritingTheFluidWithItsOwnStateChangesNothing) {
  SimSpec s = with_method(test::dam_break_2d(0.2, 0.01), GetParam());
  auto sim = make_simulation(s, 2), other = make_simulation(s, 2);
  run_until(*sim, 0.05 * sanitizer_scale());
  run_until(*other, 0.05 * sanitizer_scale());
  const ParticleView v = other->fluid();
  std::vector<float> x[2], vel[2];
  const float* xs[2];
  const float* vs[2];
  for (int k = 0; k < 2; ++k) {
    x[k].assign(v.x[k], v.x[k] + v.count);
    vel[k].assign(v.v[k], v.v[k] + v.count);
    xs[k] = x[k].data();
    vs[k] = vel[k].data();
  }
  other->overwrite_fluid(xs, vs);
  for (int i = 0; i < 5; ++i) { sim->step(); other->step(); }
  expect_same_state(*sim, *other);

  // Lift particle id 0 by 1 cm: only its row changes, and it keeps its id.
  const ParticleView w = sim->fluid();
  std::vector<float> lifted(w.x[1], w.x[1] + w.count);
  std::size_t row = 0;
  while (w.id[row] != 0) ++row;
  const float x0 = w.x[0][row], y0 = w.x[1][row];
  lifted[row] += 0.01f;
  const float* edit[2] = {w.x[0], lifted.data()};
  std::vector<float> keep_x(w.x[0], w.x[0] + w.count);
  edit[0] = keep_x.data();
  sim->overwrite_fluid(edit, nullptr);
  const ParticleView after = sim->fluid();
  std::size_t moved = 0;
  for (std::size_t i = 0; i < after.count; ++i)
    if (after.id[i] == 0) {
      EXPECT_EQ(after.x[0][i], x0);
      EXPECT_EQ(after.x[1][i], y0 + 0.01f);
      ++moved;
    }
  EXPECT_EQ(moved, 1u);
  sim->step();
  EXPECT_FALSE(check_health_message(*sim).has_value());
}

// Every built-in scene starts and takes steps with every method, and stays healthy.
// An emitter delivers its layers on time and its jet leaves the nozzle at the set speed, whichever
// method steps the fluid: a continuous 2D jet (a layer of width/spacing particles every
// spacing/speed) into an empty tank, no gravity, so nothing but the solver acts on the jet.
TEST_P(Methods, EmitterDeliversItsLayersAtItsSpeed) {
  // A gas jet into vacuum expands and accelerates under its own pressure (no rest density to
  // hold it together): the property is the liquids'.
  if (GetParam() == std::string("gas")) GTEST_SKIP() << "a gas jet expands into vacuum";
  SimSpec s = load_scene("nozzle_obstacle_2d");
  s = with_method(s, GetParam());
  s.obstacles.clear();
  s.gravity = {};
  s.spacing = 0.02;
  auto& e = s.emitters.at(0);
  e.direction = {{1, 0, 0}};
  e.speed = 1.0;
  e.width = 0.1;  // 5 particles per layer
  e.position = {{0.1, 0.6, 0}};
  auto sim = make_simulation(s, 1);
  const double T = 0.5;
  while (sim->time() < T) sim->step();
  const auto v = sim->fluid();
  const double t = sim->time();
  // Layers leave at 0, spacing/speed, 2 spacing/speed, ... up to t.
  const double layers = std::floor(t * e.speed / s.spacing + 1e-9) + 1;
  EXPECT_NEAR(double(v.count), 5 * layers, 5.0) << GetParam() << " at t = " << t;
  double vx = 0, vy = 0;
  for (std::size_t i = 0; i < v.count; ++i) { vx += v.v[0][i]; vy += v.v[1][i]; }
  vx /= double(v.count);
  vy /= double(v.count);
  std::printf("%s: %zu particles after %.3f s (%.0f layers of 5), mean velocity (%.3f, %.3f) m/s\n",
              std::string(GetParam()).c_str(), v.count, t, layers, vx, vy);
  EXPECT_NEAR(vx, e.speed, 0.1 * e.speed);
  EXPECT_NEAR(vy, 0.0, 0.05 * e.speed);
}

TEST_P(Methods, RunEveryBuiltInScene) {
  for (const auto& [name, description] : builtin_scenes()) {
    SimSpec s = load_scene(name);
    s.method = GetParam();
    // Coarse: this checks wiring, not physics. (A periodic extent must stay a whole number of
    // spacings, so those scenes, already small, keep theirs.)
    if (s.periodic == PeriodicAxes::None) s.spacing *= s.dimension == 3 ? 3.0 : 2.0;
    auto sim = make_simulation(s, 2);
    for (int i = 0; i < 8; ++i) sim->step();
    SCOPED_TRACE(name);
    EXPECT_FALSE(check_health(*sim).has_value()) << check_health_message(*sim).value_or("");
    EXPECT_GT(sim->time(), 0.0);
  }
}

// The same at each 2D scene's own resolution, for 0.1 s: the coarse 8 steps above did not see
// DFSPH's hydrostatic_2d (50 layers) go unstable at t = 0.076 s (fixed 2026-11-25, see
// Dfsph.DeepTankAtRestStaysStable). The 3D scenes at their resolution are too slow for CI; they
// were swept by hand (`rtsph run SCENE --set solver.method=M --until 1`, every scene and liquid
// method, 2026-11-25: none unstable, none put back).
TEST_P(Methods, RunEveryBuiltIn2DSceneAtItsResolution) {
  for (const auto& [name, description] : builtin_scenes()) {
    SimSpec s = load_scene(name);
    if (s.dimension != 2) continue;
    // The gas method models self-gravitating stars, not water: its own scenes only (on a liquid
    // channel its step shrinks to 1e-14 s).
    if (std::string(GetParam()) == "gas" && s.method != "gas") continue;
    s.method = GetParam();
    auto sim = make_simulation(s, 2);
    SCOPED_TRACE(name);
    while (sim->time() < 0.1 * sanitizer_scale()) {
      sim->step();
      ASSERT_FALSE(check_health(*sim).has_value()) << check_health_message(*sim).value_or("");
    }
    EXPECT_EQ(sim->stats().particles_put_back, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(All, Methods, ::testing::Values("wcsph", "pbf", "dfsph", "gas"),
                         [](const auto& info) { return info.param; });

// DFSPH keeps the mean density error at its tolerance through a collapsing column, with the
// mean iteration counts bounded, and a tighter tolerance gives a smaller error.
double dfsph_mean_error(double tolerance, double* worst, double* iterations) {
  SimSpec s = with_method(test::dam_break_2d(0.25, 0.0125), "dfsph");
  s.dfsph_max_density_error = tolerance;
  auto sim = make_simulation(s, 2);
  double sum = 0;
  int n = 0;
  *worst = 0;
  while (sim->time() < 0.3 * sanitizer_scale()) {
    sim->step();
    const auto st = sim->stats();
    sum += st.mean_density_error;
    *worst = std::max(*worst, st.mean_density_error);
    ++n;
  }
  *iterations = sim->stats().mean_pressure_iterations;
  return sum / n;
}

// WCSPH sums its fluid pairs once each (the half stencil: no lists, no periodic axes) and
// hands each partner its share; DFSPH walks each particle's full neighbour list. At the same
// positions (both constructors sum the density of the sampled scene) the two must give the same
// densities to float round-off: a pair missed or counted twice would move a particle's density by
// about 1/30 of itself, a thousand times the tolerance. A moving and a falling column, 2D and 3D.
TEST(Wcsph, HalfStencilDensityMatchesTheFullNeighbourWalk) {
  SimSpec tank3 = test::tank(3, 0.3, 0.2, 0.02);
  tank3.fluid_blocks[0].max = {{0.15, 0.2, 0.3}};
  for (const SimSpec& scene : {test::dam_break_2d(1.0, 0.04), tank3}) {
    auto half = make_simulation(with_method(scene, "wcsph"), 2);
    auto full = make_simulation(with_method(scene, "dfsph"), 2);
    const ParticleView a = half->fluid(), b = full->fluid();
    ASSERT_EQ(a.count, b.count);
    ASSERT_GT(a.count, 500u);
    std::vector<double> by_id(a.count, -1);
    for (std::size_t i = 0; i < b.count; ++i) by_id[b.id[i]] = b.density[i];
    double worst = 0;
    for (std::size_t i = 0; i < a.count; ++i) {
      ASSERT_GE(by_id[a.id[i]], 0.0);
      worst = std::max(worst, std::abs(a.density[i] - by_id[a.id[i]]) / by_id[a.id[i]]);
    }
    EXPECT_LT(worst, 2e-6) << scene.dimension << "D: largest relative density difference";
    EXPECT_GT(worst, 0.0) << scene.dimension << "D: the two sums ran the same code";
  }
}

TEST(Dfsph, HoldsItsDensityToleranceAndConverges) {
  double worst_loose, worst_default, worst_tight, it_loose, it_default, it_tight;
  const double loose = dfsph_mean_error(1e-2, &worst_loose, &it_loose);
  const double deflt = dfsph_mean_error(SimSpec{}.dfsph_max_density_error, &worst_default, &it_default);
  const double tight = dfsph_mean_error(1e-4, &worst_tight, &it_tight);
  std::printf("DFSPH mean density error: tolerance 1%% -> %.4f%% (worst step %.4f%%, %.1f it/step); "
              "0.1%% -> %.4f%% (worst %.4f%%, %.1f it/step); 0.01%% -> %.4f%% (worst %.4f%%, "
              "%.1f it/step)\n",
              100 * loose, 100 * worst_loose, it_loose, 100 * deflt, 100 * worst_default,
              it_default, 100 * tight, 100 * worst_tight, it_tight);
  EXPECT_LT(tight, loose);
  EXPECT_LT(deflt, loose);
  EXPECT_GT(it_tight, it_loose);
  // At the default tolerance the solve converges well inside its cap on average (0.01% can
  // sit at the cap while the column first takes its load).
  EXPECT_LT(it_default, 0.5 * SimSpec{}.dfsph_max_iterations);
  // The solve stops at the tolerance on the predicted density; the density measured after the
  // drift may exceed it by the part the projection could not see (walls, emitted particles).
  EXPECT_LT(worst_tight, 2e-3);
}

// Issue 9 §7: in 3D, DFSPH holds its default tolerance at every step of a collapsing column: each
// step's density solve brings the mean predicted density error ρ*/ρ0 − 1 (Bender & Koschier 2017,
// Algorithm 3's criterion) to 0.1% within its iteration cap, else the step reports a failure.
// The error measured after the drift is printed, not asserted: the first-order prediction
// misses part of it (0.17% worst here, at the surge's impact on the far wall).
TEST(Dfsph, HoldsTheDefaultToleranceAtEveryStepIn3D) {
  SimSpec s = with_method(test::dam_break_2d(0.1, 0.01), "dfsph");
  s.name = "dam_break_3d_dfsph";
  s.dimension = 3;
  s.domain_max = {{0.4, 0.25, 0.1}};
  s.fluid_blocks = {{{{0, 0, 0}}, {{0.1, 0.2, 0.1}}, {}}};
  auto sim = make_simulation(s, 2);
  double worst = 0, worst_t = 0;
  int max_it = 0;
  while (sim->time() < 0.4 * sanitizer_scale()) {
    sim->step();
    const auto st = sim->stats();
    if (st.mean_density_error > worst) { worst = st.mean_density_error; worst_t = st.time_s; }
    max_it = std::max(max_it, st.pressure_iterations);
    ASSERT_EQ(sim->solver_failure(), "");
  }
  std::printf("DFSPH 3D dam break, %zu particles, %llu steps to t = %.2f s: worst mean density error %.4f%% "
              "(t = %.3f s), most iterations %d, mean %.1f\n", sim->stats().fluid_particles,
              (unsigned long long)sim->step_count(), sim->time(), 100 * worst, worst_t, max_it,
              sim->stats().mean_pressure_iterations);
  EXPECT_LT(max_it, s.dfsph_max_iterations);
  EXPECT_EQ(sim->stats().capped_steps, 0u);
  EXPECT_GT(worst, 0.0);  // a real measurement
}

// The built-in hydrostatic_2d (50 layers, d = 1 cm) at rest: with only the velocity CFL the
// first steps took max_dt = 5 ms, the bottom layer's speeds grew fivefold per step and the run
// stopped unstable at t = 0.076 s; the head speed √(|g|H) in the step (Dfsph::choose_time_step)
// keeps it: the start from p = 0 still sets it moving (0.54 m/s at t = 0.3 s, worst density
// error 2.3%), and that dies down (0.07 m/s at 1 s, 0.03 at 2 s). Since the walls' artificial
// viscosity lets water slide along them (a free-slip ghost, fluid_sums.cpp) it dies down more
// slowly: the fastest particle 0.23 m/s at 0.25 s, 0.10-0.22 around 1 s, 0.037 at 2 s (rms speed
// 0.050, 0.026, 0.011 m/s), so the test runs to 2 s.
TEST(Dfsph, DeepTankAtRestStaysStable) {
  SimSpec s = load_scene("hydrostatic_2d");
  s.method = "dfsph";
  auto sim = make_simulation(s, 2);
  while (sim->time() < 2.0) {
    sim->step();
    ASSERT_FALSE(check_health(*sim).has_value()) << check_health_message(*sim).value_or("");
  }
  const auto st = sim->stats();
  std::printf("DFSPH hydrostatic_2d, %llu steps to t = %.2f s: worst density error %.2f%%, fastest "
              "particle %.3f m/s, %llu steps at the iteration cap\n", (unsigned long long)st.steps,
              st.time_s, 100 * st.max_density_error, st.max_speed, (unsigned long long)st.capped_steps);
  EXPECT_LT(st.max_density_error, 0.05);
  EXPECT_LT(st.max_speed, 0.15);
}

// A solve that stops at its cap above its tolerance is counted (`rtsph run` prints the count),
// and the count travels in checkpoints: with a cap of 2 sweeps and a 0.01% tolerance the
// collapsing column's density solve cannot converge.
TEST(Dfsph, CountsTheStepsWhoseSolveStoppedAtItsCap) {
  SimSpec s = with_method(test::dam_break_2d(0.25, 0.0125), "dfsph");
  s.dfsph_max_iterations = 2;
  s.dfsph_max_density_error = 1e-4;
  auto sim = make_simulation(s, 2);
  std::uint64_t seen = 0;
  for (int i = 0; i < 20; ++i) {
    sim->step();
    seen += !sim->solver_failure().empty();
  }
  EXPECT_GT(seen, 0u);
  EXPECT_EQ(sim->stats().capped_steps, seen);
  std::vector<StateField> fields = sim->state_fields();
  EXPECT_TRUE(std::any_of(fields.begin(), fields.end(),
                          [](const StateField& f) { return f.name == "dfsph.capped_steps"; }));
}

// The Chebyshev acceleration of the density solve (solver.dfsph.chebyshev) reaches the same
// tolerance in fewer sweeps than plain Jacobi on a collapsing 2D column (measured 10.6 → 4.6
// per step, neither at its cap; before the head speed bounded the first steps, 13.1 → 5.4 with
// plain Jacobi at its cap on two steps as the column took its load).
TEST(Dfsph, ChebyshevAccelerationNeedsFewerSweeps) {
  auto run = [](double rho, double* error, int* failed) {
    SimSpec s = with_method(test::dam_break_2d(0.1, 0.005), "dfsph");
    s.dfsph_chebyshev = rho;
    auto sim = make_simulation(s, 2);
    double worst = 0;
    *failed = 0;
    while (sim->time() < 0.25 * sanitizer_scale()) {
      sim->step();
      *failed += !sim->solver_failure().empty();
      worst = std::max(worst, sim->stats().mean_density_error);
    }
    *error = worst;
    return sim->stats().mean_pressure_iterations;
  };
  double e_plain, e_cheb;
  int f_plain, f_cheb;
  const double plain = run(0.0, &e_plain, &f_plain);
  const double cheb = run(SimSpec{}.dfsph_chebyshev, &e_cheb, &f_cheb);
  std::printf("DFSPH density sweeps per step: plain Jacobi %.2f (worst mean error %.4f%%, %d steps "
              "at the iteration cap), Chebyshev %.2f (%.4f%%, %d)\n", plain, 100 * e_plain,
              f_plain, cheb, 100 * e_cheb, f_cheb);
  EXPECT_LT(cheb, 0.8 * plain);
  EXPECT_EQ(f_cheb, 0);  // each of its solves reached the tolerance within the cap
  EXPECT_LE(f_cheb, f_plain);
  // The same tolerance, so the same error after the drift (0.1476% against 0.1469%).
  EXPECT_LE(e_cheb, 1.05 * e_plain);
}

// PBF reports the density error its constraint solve leaves; with a fixed count, more Jacobi
// iterations leave less of it (the solve converges). At default settings it iterates past
// solver.pbf.iterations while the compression its last λ pass measured is above
// solver.pbf.max_density_error (1%): in a 40-layer column, where four fixed iterations leave
// 2.4% at the worst step, the error after the last correction stays within 5% of that 1%
// (1.03% measured; the check is made before the correction, which saves a λ pass per substep).
struct PbfRun {
  double worst = 0;          // the worst step's mean density error
  int last_iterations = 0;   // the last step's
  double mean_iterations = 0;
  int most_iterations = 0;
};

PbfRun pbf_column(int iterations, double tolerance) {
  SimSpec s = with_method(test::dam_break_2d(0.25, 0.0125), "pbf");
  s.pbf_iterations = iterations;
  s.pbf_max_density_error = tolerance;
  auto sim = make_simulation(s, 2);
  PbfRun r;
  while (sim->time() < 0.3 * sanitizer_scale()) {
    sim->step();
    r.worst = std::max(r.worst, sim->stats().mean_density_error);
    r.most_iterations = std::max(r.most_iterations, sim->stats().pressure_iterations);
  }
  r.last_iterations = sim->stats().pressure_iterations;
  r.mean_iterations = sim->stats().mean_pressure_iterations;
  return r;
}

TEST(Pbf, ReportsItsDensityErrorAndConverges) {
  const int defaults = SimSpec{}.pbf_iterations;
  const PbfRun fixed = pbf_column(defaults, 0), many = pbf_column(4 * defaults, 0);
  std::printf("PBF mean density error, worst step, fixed count: %.3f%% at %d iterations, %.3f%% at %d\n",
              100 * fixed.worst, fixed.last_iterations, 100 * many.worst, many.last_iterations);
  EXPECT_EQ(fixed.last_iterations, defaults);
  EXPECT_EQ(fixed.mean_iterations, defaults);
  EXPECT_EQ(many.last_iterations, 4 * defaults);
  EXPECT_GT(fixed.worst, 0.0);  // a real measurement, not a placeholder
  EXPECT_LT(many.worst, 0.5 * fixed.worst);
  EXPECT_LT(fixed.worst, 0.05);  // the column stands: no collapse
}

TEST(Pbf, HoldsOnePercentAtDefaultSettings) {
  const SimSpec d;
  const PbfRun r = pbf_column(d.pbf_iterations, d.pbf_max_density_error);
  std::printf("PBF at defaults (tolerance %.1f%%): worst step %.3f%%, iterations mean %.2f, most %d (cap %d)\n",
              100 * d.pbf_max_density_error, 100 * r.worst, r.mean_iterations, r.most_iterations,
              d.pbf_max_iterations);
  EXPECT_LE(r.worst, 1.05 * d.pbf_max_density_error);
  EXPECT_GT(r.worst, 0.0);
  EXPECT_GT(r.most_iterations, d.pbf_iterations);  // this column needs more than the minimum
  EXPECT_LT(r.most_iterations, d.pbf_max_iterations);  // and gets there below the cap
  EXPECT_GE(r.mean_iterations, d.pbf_iterations);
}

// s_corr acts only on pairs closer than the kernel's gradient peak (pbf.cpp), and that is enough
// to keep spray apart: in the built-in 3D dam break at 0.04 m (3,000 particles) the closest pair
// over t = 0.5, 1, 1.5 and 2 s is 0.557 spacings apart; with s_corr off it is 0.061, and 22 to 36
// particles are within 0.3 spacings of another (docs/validation.md, session 27). Asserted above
// 0.4, well clear of both.
double closest_pair(const Simulation& sim, double spacing) {
  const ParticleView v = sim.fluid();
  double best2 = 1e30;
  for (std::size_t i = 0; i < v.count; ++i)
    for (std::size_t j = i + 1; j < v.count; ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(double(v.x[k][i]) - double(v.x[k][j]), 2);
      best2 = std::min(best2, d2);
    }
  return std::sqrt(best2) / spacing;
}

TEST(Pbf, SprayStaysApart) {
  double closest[2] = {};
  for (const double k : {SimSpec{}.pbf_scorr_k, 0.0}) {
    SimSpec s = load_scene("dam_break_3d");
    apply_override(s, "solver.method=pbf");
    apply_override(s, "fluid.spacing=0.04");
    s.pbf_scorr_k = k;
    auto sim = make_simulation(s, 2);
    double least = 1e30;
    for (double t = 0.5; t <= 1.5 * sanitizer_scale() + 0.5 + 1e-9; t += 0.5) {
      while (sim->time() < t) sim->step();
      least = std::min(least, closest_pair(*sim, s.spacing));
    }
    closest[k > 0 ? 0 : 1] = least;
  }
  std::printf("PBF 3D dam break at 0.04 m: closest pair %.3f spacings with s_corr, %.3f without\n", closest[0],
              closest[1]);
  EXPECT_GT(closest[0], 0.4);
  EXPECT_LT(closest[1], 0.3);  // the check can fail: without s_corr the spray clumps
}

}  // namespace
}  // namespace rtsph
