// The viewer's real-time profile: scenes marked viewer.realtime run PBF at a spacing whose
// starting fluid fits the per-thread budget; unmarked scenes (validation) run as written.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene/realtime_profile.h"
#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {
namespace {

TEST(RealtimeProfile, MarkedSceneRunsPbfWithinTheBudget) {
  const SimSpec scene = load_scene("dam_break_3d");
  ASSERT_TRUE(scene.viewer_realtime);
  ASSERT_EQ(scene.method, "wcsph");
  const double written = count_particles(scene).fluid;
  for (int threads : {1, 2, 8}) {
    const RealtimeProfile p = realtime_profile(scene, threads);
    EXPECT_TRUE(p.applied);
    EXPECT_EQ(p.spec.method, "pbf");
    EXPECT_DOUBLE_EQ(p.budget, realtime_budget(p.spec, threads));
    const auto counts = count_particles(p.spec);
    const double n = counts.fluid + counts.emitted_max;
    EXPECT_EQ(n, p.fluid_particles);
    EXPECT_LE(n, p.budget);
    // Coarsened only as far as needed: within ~25% of the budget (lattice rounding), and
    // never finer than the scene.
    EXPECT_GT(n, 0.75 * std::min(p.budget, written)) << threads << " threads";
    EXPECT_GE(p.spec.spacing, scene.spacing);
    // A bounded iteration count (the scene has the defaults, 4 to 20).
    EXPECT_EQ(p.spec.pbf_iterations, kRealtimePbfIterations);
    EXPECT_EQ(p.spec.pbf_max_iterations, kRealtimePbfMaxIterations);
    // Everything but the method, its iterations and the spacing is the scene's (no emitters).
    SimSpec back = p.spec;
    back.method = scene.method;
    back.spacing = scene.spacing;
    back.pbf_iterations = scene.pbf_iterations;
    back.pbf_max_iterations = scene.pbf_max_iterations;
    EXPECT_EQ(scene_to_json(back), scene_to_json(scene));
  }
}

// A nozzle scene starts empty: its emitters' caps count, scaled so the emitted volume stays.
TEST(RealtimeProfile, EmittersCountAndKeepTheirVolume) {
  const SimSpec scene = load_scene("nozzle_obstacle_2d");
  ASSERT_FALSE(scene.emitters.empty());
  ASSERT_GT(double(scene.emitters[0].max_particles), realtime_budget(scene, 1));
  const RealtimeProfile p = realtime_profile(scene, 1);
  const auto counts = count_particles(p.spec);
  EXPECT_LE(counts.fluid + counts.emitted_max, p.budget);
  EXPECT_GT(p.spec.spacing, scene.spacing);
  const double volume = [](const SimSpec& s) {
    return double(s.emitters[0].max_particles) * s.spacing * s.spacing;
  }(p.spec);
  const double written = double(scene.emitters[0].max_particles) * scene.spacing * scene.spacing;
  EXPECT_NEAR(volume, written, 0.02 * written);  // floor() of the scaled cap
}

// The budget is a rate: a scene that takes twice the substeps per second gets half the
// particles (the 3D dam break sets 2 per frame, the double dam break keeps the default 4).
// On the CPU a jet's CFL substeps count (a collapse's front does not: the calm share absorbs
// that transient). The nozzle's 2.5 m/s jet falls 0.9 m: sqrt(2.5² + 2g·0.9) = 4.89 m/s, so at
// the profile's spacing s it asks 4.89/s substeps a second, more than the frame's 240, and the
// budget is the rate over those; the dam break keeps the frame's.
TEST(RealtimeProfile, CpuBudgetCountsAJetsSubsteps) {
  const SimSpec scene = load_scene("nozzle_obstacle_2d");
  const double rate = 1.92e6;  // particle-substeps/s per thread (the 2D cap on this machine kind)
  const RealtimeProfile p = realtime_profile(scene, 1, rate);
  const double jet = std::sqrt(2.5 * 2.5 + 2 * 9.81 * 0.9);
  EXPECT_NEAR(realtime_flow_speed(p.spec), jet, 1e-3);
  const double substeps = jet / (p.spec.pbf_cfl * p.spec.spacing);
  ASSERT_GT(substeps, 1.5 * p.spec.pbf_substeps / p.spec.pbf_time_step);
  EXPECT_NEAR(p.budget, rate / substeps, 1e-6 * p.budget);
  const auto counts = count_particles(p.spec);
  EXPECT_LE(counts.fluid + counts.emitted_max, p.budget);
  EXPECT_GT(counts.fluid + counts.emitted_max, 0.9 * p.budget);  // as fine as the budget allows
  // Over the frame's substeps the same rate would keep the scene as written (8,000 at 0.01 m).
  EXPECT_GE(realtime_budget(scene, 1, rate), 8000.0);
  EXPECT_LT(p.fluid_particles, 0.7 * 8000.0);
  // A dam break (no emitter) is budgeted over the frame's substeps, whatever its front's speed.
  const SimSpec dam = load_scene("dam_break_3d");
  const RealtimeProfile d = realtime_profile(dam, 1, 1.26e6);
  EXPECT_DOUBLE_EQ(d.budget, realtime_budget(d.spec, 1, 1.26e6));
}

TEST(RealtimeProfile, MoreSubstepsGetFewerParticles) {
  const SimSpec two = load_scene("dam_break_3d"), four = load_scene("double_dam_break_3d");
  ASSERT_EQ(two.pbf_substeps, 2);
  ASSERT_EQ(four.pbf_substeps, 4);
  ASSERT_EQ(two.pbf_time_step, four.pbf_time_step);
  EXPECT_DOUBLE_EQ(realtime_budget(two, 1), 2 * realtime_budget(four, 1));
  EXPECT_DOUBLE_EQ(realtime_budget(two, 2), 2 * realtime_budget(two, 1));
  // The measured point: one thread keeps the 3D dam break's 10,350 particles in real time.
  EXPECT_GE(realtime_profile(two, 1).fluid_particles, 10000);
}

// The viewer budgets with the rate it measured on its machine: the budget is proportional to
// it, and the profile says which rate it used.
TEST(RealtimeProfile, AMeasuredRateScalesTheBudget) {
  const SimSpec scene = load_scene("dam_break_3d");
  const double reference = realtime_particle_substeps_per_thread(3);
  const RealtimeProfile ref = realtime_profile(scene, 1);
  EXPECT_DOUBLE_EQ(ref.rate_per_thread, reference);
  EXPECT_NE(ref.describe().find("the reference machine's"), std::string::npos);
  const RealtimeProfile slow = realtime_profile(scene, 1, 0.4 * reference);
  EXPECT_DOUBLE_EQ(slow.rate_per_thread, 0.4 * reference);
  EXPECT_DOUBLE_EQ(slow.budget, 0.4 * ref.budget);
  EXPECT_LE(slow.fluid_particles, slow.budget);
  EXPECT_GT(slow.spec.spacing, ref.spec.spacing);
  EXPECT_NE(slow.describe().find("given"), std::string::npos);
}

// A measurement is a share of the calm rate, and one wild figure cannot empty or swamp a scene.
TEST(RealtimeProfile, CalibratedRateIsAShareWithinBounds) {
  const double reference = realtime_particle_substeps_per_thread(3);
  EXPECT_DOUBLE_EQ(calibrated_rate(reference, 3), realtime_calm_share(3) * reference);
  EXPECT_DOUBLE_EQ(calibrated_rate(1.0, 3), reference / 16);
  EXPECT_DOUBLE_EQ(calibrated_rate(1e12, 3), 2 * reference);
  EXPECT_DOUBLE_EQ(calibrated_rate(0.0, 2), realtime_particle_substeps_per_thread(2));  // no figure
  EXPECT_DOUBLE_EQ(calibrated_rate(std::nan(""), 2), realtime_particle_substeps_per_thread(2));
}

// The measurement steps the profiled scene itself (a coarse one here) and gives a positive,
// finite rate (its size is the machine's, so nothing more is asserted).
TEST(RealtimeProfile, MeasuringTheMachineStepsTheScene) {
  SimSpec scene = load_scene("dam_break_2d");
  apply_override(scene, "fluid.spacing=0.05");
  const RealtimeProfile p = realtime_profile(scene, 1);
  const double rate = measure_particle_substeps_per_thread(p.spec, 1, 0.01);
  EXPECT_TRUE(std::isfinite(rate));
  EXPECT_GT(rate, 0);
  // An empty scene (a nozzle before it emits) has nothing to measure: 0, and the reference rate.
  SimSpec empty = load_scene("nozzle_obstacle_2d");
  ASSERT_EQ(count_particles(empty).fluid, 0);
  EXPECT_EQ(measure_particle_substeps_per_thread(realtime_profile(empty, 1).spec, 1, 0.01), 0);
}

TEST(RealtimeProfile, MoreThreadsGiveAFinerSpacing) {
  const SimSpec scene = load_scene("dam_break_2d");
  EXPECT_GT(realtime_profile(scene, 1).spec.spacing, realtime_profile(scene, 4).spec.spacing);
}

TEST(RealtimeProfile, SmallSceneKeepsItsSpacing) {
  SimSpec scene = load_scene("dam_break_3d");
  apply_override(scene, "fluid.spacing=0.1");
  const RealtimeProfile p = realtime_profile(scene, 1);
  EXPECT_TRUE(p.applied);
  EXPECT_EQ(p.spec.method, "pbf");
  EXPECT_EQ(p.spec.spacing, 0.1);
}

// The profile only lowers PBF's iteration counts: a scene that asks for fewer keeps them.
TEST(RealtimeProfile, FewerIterationsAreKept) {
  SimSpec scene = load_scene("dam_break_3d");
  apply_override(scene, "solver.pbf.iterations=2");
  apply_override(scene, "solver.pbf.max_iterations=2");
  const RealtimeProfile p = realtime_profile(scene, 1);
  EXPECT_EQ(p.spec.pbf_iterations, 2);
  EXPECT_EQ(p.spec.pbf_max_iterations, 2);
}

TEST(RealtimeProfile, UnmarkedSceneRunsAsWritten) {
  const SimSpec scene = load_scene("hydrostatic_2d");  // a validation scene
  EXPECT_FALSE(scene.viewer_realtime);
  const RealtimeProfile p = realtime_profile(scene, 1);
  EXPECT_FALSE(p.applied);
  EXPECT_EQ(scene_to_json(p.spec), scene_to_json(scene));
  EXPECT_EQ(p.describe(), "as written");
}

TEST(RealtimeProfile, KeyReadsFromJsonAndSet) {
  SimSpec s = load_scene("hydrostatic_2d");
  apply_override(s, "viewer.realtime=true");
  EXPECT_TRUE(s.viewer_realtime);
  EXPECT_TRUE(parse_scene(scene_to_json(s), "round trip").viewer_realtime);
}

// The CFL bound's substeps at a scene's head speed (realtime_flow_speed, Ritter's front speed
// 2·sqrt(|g|H)): the 3D dam break's column is 0.8 m high, solver.pbf.cfl 1.5.
TEST(RealtimeProfile, FlowSpeedAndSubstepsFollowTheHead) {
  SimSpec dam = load_scene("dam_break_3d");
  EXPECT_NEAR(realtime_flow_speed(dam), 2 * std::sqrt(9.81 * 0.8), 1e-9);
  const double frame = dam.pbf_substeps / dam.pbf_time_step;
  EXPECT_NEAR(frame, 120, 1e-9);
  EXPECT_NEAR(realtime_substeps_per_second(dam), 2 * std::sqrt(9.81 * 0.8) / (1.5 * dam.spacing), 1e-9);
  apply_override(dam, "fluid.spacing=0.05");  // coarse: the frame's substeps rule
  EXPECT_DOUBLE_EQ(realtime_substeps_per_second(dam), frame);
  apply_override(dam, "fluid.spacing=0.005");
  apply_override(dam, "solver.pbf.cfl=0");  // no CFL bound: the frame's
  EXPECT_DOUBLE_EQ(realtime_substeps_per_second(dam), frame);
  // Gravity along x: the height is the extent along x, the column's 0.4 m.
  apply_override(dam, "gravity=[-9.81, 0, 0]");
  EXPECT_NEAR(realtime_flow_speed(dam), 2 * std::sqrt(9.81 * 0.4), 1e-9);
  // No gravity and no emitter: nothing moves the water.
  apply_override(dam, "gravity=[0, 0, 0]");
  EXPECT_EQ(realtime_flow_speed(dam), 0);
  // A jet faster than its fall: the jet's speed.
  SimSpec jet = load_scene("nozzle_obstacle_2d");
  ASSERT_FALSE(jet.emitters.empty());
  const double fall = realtime_flow_speed(jet);
  EXPECT_GE(fall, jet.emitters[0].speed);
  // A jet ten times faster: its speed, plus what it gains falling from the nozzle (less than the
  // water's whole fall).
  jet.emitters[0].speed = 10 * fall;
  EXPECT_GE(realtime_flow_speed(jet), 10 * fall);
  EXPECT_LE(realtime_flow_speed(jet), std::sqrt(101.0) * fall);
  // A block thrown down at 5 m/s with its top 0.5 m up: sqrt(5² + 2·9.81·0.5), more than a column
  // of that height's front, 2·sqrt(9.81·0.5).
  SimSpec thrown = load_scene("dam_break_3d");
  thrown.fluid_blocks = {FluidBlock{{0, 0.4, 0}, {0.1, 0.5, 0.1}, BlockShape::Box, {0, -5, 0}}};
  EXPECT_NEAR(realtime_flow_speed(thrown), std::sqrt(25 + 2 * 9.81 * 0.5), 1e-9);
  // Open, or periodic along gravity: the floor is the water's own bottom (0.4 m here).
  thrown.fluid_blocks[0].velocity = {};
  thrown.open = true;
  EXPECT_NEAR(realtime_flow_speed(thrown), 2 * std::sqrt(9.81 * 0.1), 1e-9);
}

// A GPU's budget (realtime_profile's `device`) may refine the scene: the smallest spacing whose
// water fits the rate over the substeps that spacing asks for, never below a quarter of the
// scene's; without `device` the scene's spacing is the finest (the CPU's budget), and the frame's
// substeps count.
TEST(RealtimeProfile, DeviceBudgetFillsWithTheSubstepsItsSpacingAsks) {
  const SimSpec scene = load_scene("dam_break_3d");
  const double written = count_particles(scene).fluid;
  const double frame = scene.pbf_substeps / scene.pbf_time_step;
  auto substeps = [](const SimSpec& s) { return realtime_substeps_per_second(s); };
  for (double want : {2.0, 10.0}) {
    const double rate = want * written * frame;  // `want` times the scene at the frame's substeps
    const RealtimeProfile p = realtime_profile(scene, 1, rate, /*device=*/true);
    EXPECT_LT(p.spec.spacing, scene.spacing);
    EXPECT_NEAR(p.budget, rate / substeps(p.spec), 1e-9 * rate);
    EXPECT_LE(p.fluid_particles * substeps(p.spec), rate);
    // The flow's substeps (more than the frame's at these spacings) leave room for fewer.
    EXPECT_GT(substeps(p.spec), frame);
    EXPECT_LT(p.fluid_particles, want * written);
    // Within the lattice's rounding of the budget: a spacing 1% finer no longer fits.
    SimSpec finer = p.spec;
    apply_override(finer, "fluid.spacing=" + std::to_string(0.99 * p.spec.spacing));
    EXPECT_GT(count_particles(finer).fluid * substeps(finer), rate) << want;
    EXPECT_GT(p.fluid_particles, 0.9 * p.budget) << want;
    EXPECT_EQ(realtime_profile(scene, 1, rate).spec.spacing, scene.spacing);  // not without device
    // The scene's iterations, not the CPU profile's 3 to 4.
    EXPECT_EQ(p.spec.pbf_iterations, scene.pbf_iterations);
    EXPECT_EQ(p.spec.pbf_max_iterations, scene.pbf_max_iterations);
    // Without the CFL bound the frame's substeps count: `want` times the scene.
    SimSpec no_cfl = scene;
    apply_override(no_cfl, "solver.pbf.cfl=0");
    const RealtimeProfile q = realtime_profile(no_cfl, 1, rate, true);
    EXPECT_NEAR(q.budget, want * written, 1e-6 * want * written);
    EXPECT_LE(q.fluid_particles, q.budget);
    EXPECT_GT(q.fluid_particles, 0.9 * q.budget);
  }
  // A budget beyond what a quarter of the spacing asks stops there.
  const double finest = kRealtimeFinest * scene.spacing;
  SimSpec at_finest = scene;
  apply_override(at_finest, "fluid.spacing=" + std::to_string(finest));
  const double beyond = 2 * count_particles(at_finest).fluid * substeps(at_finest);
  EXPECT_DOUBLE_EQ(realtime_profile(scene, 1, beyond, true).spec.spacing, finest);
  // A smaller budget still coarsens: without the CFL bound to what the CPU's budget gives (or a
  // little finer: the device's coarsening ends by bisection); with it, further, as long as the
  // spacing's flow asks for more than the frame's substeps (the 0.025 m this budget gives the CPU
  // asks for 146 a second). Either way it fills the budget.
  const double half = 0.5 * written * frame;
  SimSpec no_cfl = scene;
  apply_override(no_cfl, "solver.pbf.cfl=0");
  const RealtimeProfile cpu = realtime_profile(scene, 1, half);
  const RealtimeProfile plain = realtime_profile(no_cfl, 1, half, true);
  EXPECT_LE(plain.spec.spacing, cpu.spec.spacing);
  EXPECT_LE(plain.fluid_particles, plain.budget);
  EXPECT_GT(plain.fluid_particles, 0.9 * plain.budget);
  const RealtimeProfile coarser = realtime_profile(scene, 1, half, true);
  EXPECT_GT(coarser.spec.spacing, cpu.spec.spacing);
  EXPECT_LE(coarser.fluid_particles * substeps(coarser.spec), half);
  EXPECT_GT(coarser.fluid_particles * substeps(coarser.spec), 0.9 * half);
}

// A device's rate round-trips: the profile at measure_device_budget's rate holds about the
// particles the budget counted, and its substeps at their spacing cost what the share allows.
TEST(RealtimeProfile, DeviceRateRoundTripsThroughTheProfile) {
  const SimSpec scene = load_scene("dam_break_3d");
  auto cost = [](double n) { return 1e-3 + n / 5e7; };
  const DeviceBudget b = measure_device_budget(realtime_profile(scene, 1).spec, 0.4, 0.25 * scene.spacing,
                                               [&](const SimSpec& s) {
                                                 const double n = count_particles(s).fluid;
                                                 return StepProbe{n, cost(n)};
                                               });
  ASSERT_GT(b.particles, 0);
  const RealtimeProfile p = realtime_profile(scene, 1, b.rate, /*device=*/true);
  EXPECT_NEAR(p.fluid_particles, b.particles, 0.1 * b.particles);
  EXPECT_LE(cost(p.fluid_particles) * realtime_substeps_per_second(p.spec), 0.4 * 1.02);
}

// A slow device's budget coarsens a scene past what its own checks allow (the nozzle's 0.08 m
// emitter at a spacing wider than it): the spacing steps back until they pass, no error.
TEST(RealtimeProfile, ACoarseBudgetStillGivesAValidScene) {
  for (const char* name : {"nozzle_obstacle_2d", "nozzle_moving_obstacle_2d"}) {
    const SimSpec scene = load_scene(name);
    for (double rate : {6e4, 2e4, 1e3}) {
      SCOPED_TRACE(std::string(name) + " at " + std::to_string(rate));
      RealtimeProfile p;
      ASSERT_NO_THROW(p = realtime_profile(scene, 1, rate, /*device=*/true));
      ASSERT_FALSE(p.spec.emitters.empty());
      EXPECT_GE(p.spec.emitters[0].width, p.spec.spacing);
      EXPECT_GE(p.spec.spacing, scene.spacing);
      ASSERT_NO_THROW(realtime_profile(scene, 1, rate));
    }
  }
}

// particles_in_real_time: the size a device keeps in real time, from probes of its substep cost.
TEST(RealtimeProfile, ParticlesInRealTimeFitsAFixedAndAPerParticleCost) {
  // t = 1 ms + N / 1e8 s; with one substep a second `share` is the time a substep may take.
  auto t = [](double n) { return 1e-3 + n / 1e8; };
  auto one = [](double) { return 1.0; };
  auto in_time = [&](const std::vector<StepProbe>& probes, double seconds) {
    return particles_in_real_time(probes, seconds, 2, one);
  };
  EXPECT_NEAR(in_time({{1e4, t(1e4)}, {8e4, t(8e4)}}, 1.5e-3), 5e4, 1);
  // In any order; a probe slower than a larger one (here a slow outlier at 1e3) reads as the
  // larger one's time.
  EXPECT_NEAR(in_time({{8e4, t(8e4)}, {1e3, 5e-3}, {1e4, t(1e4)}}, 1.5e-3), 5e4, 1);
  // Probes far above the time do not hide a fixed part that is over it (llvmpipe: 10 ms a substep
  // at any size, 6.25 ms allowed).
  EXPECT_EQ(in_time({{10350, 0.132}, {1320, 0.0202}, {192, 0.0109}}, 6.25e-3), 0);
  // Never more than twice the largest size probed (4 ms would be 3e5 on the line).
  EXPECT_DOUBLE_EQ(in_time({{1e4, t(1e4)}, {8e4, t(8e4)}}, 4e-3), 1.6e5);
  // One probe: t ∝ N.
  EXPECT_NEAR(in_time({{8e4, 1.8e-3}}, 0.9e-3), 4e4, 1);
  // The fixed part alone over the time: nothing fits. No usable probe: 0.
  EXPECT_EQ(in_time({{1e4, t(1e4)}, {8e4, t(8e4)}}, 0.5e-3), 0);
  EXPECT_EQ(in_time({}, 1e-3), 0);
  EXPECT_EQ(in_time({{1e4, 0}}, 1e-3), 0);
  // A cost that does not rise with N: the fixed part up to the largest size probed, t ∝ N beyond.
  EXPECT_EQ(in_time({{2e4, 2e-3}, {1e4, 2e-3}}, 1e-3), 0);
  EXPECT_NEAR(in_time({{2e4, 2e-3}, {1e4, 2e-3}}, 3e-3), 3e4, 1);
  // Probes of one size read as their mean: a repeat does not flatten the line beyond it.
  EXPECT_NEAR(in_time({{1e4, t(1e4)}, {8e4, t(8e4)}, {8e4, t(8e4)}}, 1.9e-3), 9e4, 1);
  EXPECT_NEAR(in_time({{1e4, t(1e4)}, {8e4, 1.7e-3}, {8e4, 1.9e-3}}, 1.9e-3), 9e4, 1);

  // Substeps that rise with N (a finer spacing's CFL bound): t(N)·substeps(N) = share. Here
  // substeps 100 + N/100 a second and 75% of real time: (1e-3 + N/1e8)(100 + N/100) = 0.75.
  const double n = particles_in_real_time({{1e4, t(1e4)}, {8e4, t(8e4)}}, 0.75, 2,
                                          [](double n) { return 100 + n / 100; });
  EXPECT_NEAR(t(n) * (100 + n / 100), 0.75, 1e-6);
  EXPECT_LT(n, (0.75 / 100 - 1e-3) * 1e8);  // fewer than at a constant 100 a second
}

// measure_device_budget against a device whose substep costs 1 ms + N / 5e7 s (3D dam break,
// 75% of each substep's real time): from the CPU reference size it probes upward at most 8 times
// per step and lands on the size whose substep takes 75% of 1/substeps-per-second at its spacing.
// Without the CFL bound that is 75% of 1/120 s = 6.25 ms: 262,500 particles.
TEST(RealtimeProfile, DeviceBudgetProbesUpToTheSizeThatFits) {
  for (bool cfl : {false, true}) {
    SimSpec scene = load_scene("dam_break_3d");
    if (!cfl) apply_override(scene, "solver.pbf.cfl=0");
    const RealtimeProfile start = realtime_profile(scene, 1);
    std::vector<double> sizes;
    auto cost = [](double n) { return 1e-3 + n / 5e7; };
    const DeviceBudget b = measure_device_budget(start.spec, 0.75, 0.25 * scene.spacing, [&](const SimSpec& s) {
      const double n = count_particles(s).fluid;
      sizes.push_back(n);
      return StepProbe{n, cost(n)};
    });
    ASSERT_GE(b.probes.size(), 2u);
    EXPECT_LE(b.probes.size(), 4u);
    EXPECT_NEAR(sizes.front(), start.fluid_particles, 0.5);  // the first probe is the profile as given
    for (std::size_t i = 1; i < sizes.size(); ++i) EXPECT_LE(sizes[i], 8.5 * sizes[i - 1]);
    // The substeps per second at the budget's spacing (N ∝ spacing^-3 from the first probe).
    SimSpec at = start.spec;
    at.spacing = start.spec.spacing * std::cbrt(sizes.front() / b.particles);
    const double substeps = realtime_substeps_per_second(at);
    if (!cfl) {
      const double expected = (6.25e-3 - 1e-3) * 5e7;
      EXPECT_NEAR(b.particles, expected, 0.01 * expected);  // the model is a line: the fit is exact
      EXPECT_DOUBLE_EQ(substeps, 120);
    } else {
      EXPECT_GT(substeps, 120);  // at these sizes the CFL bound asks for more substeps
      EXPECT_LT(b.particles, 0.5 * (6.25e-3 - 1e-3) * 5e7);
    }
    EXPECT_NEAR(cost(b.particles) * substeps, 0.75, 1e-6);
    EXPECT_NEAR(b.rate, b.particles * substeps, 1e-6 * b.rate);
    EXPECT_NE(b.describe().find(" particles "), std::string::npos);
    // A device slower than the time at any size: nothing fits, and it stops probing.
    const DeviceBudget slow = measure_device_budget(start.spec, 0.75, 0.25 * scene.spacing, [](const SimSpec& s) {
      const double n = count_particles(s).fluid;
      return StepProbe{n, 10e-3 + n / 5e7};
    });
    EXPECT_EQ(slow.particles, 0);
  }
}

}  // namespace
}  // namespace rtsph
