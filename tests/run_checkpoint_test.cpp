// Resuming is exact: running 0 → 2T straight, and running 0 → T, writing a checkpoint, loading
// it into a fresh Simulation and running on to 2T, give bitwise identical states (every state
// field, byte for byte). Covered: a plain dam break (2D and 3D), emitters and a moving obstacle,
// a fixed-dt scene, and the in-memory StateSnapshot used by the instability guard.
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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

std::uint64_t hash_of(const SimSpec& s) { return io::hash_bytes(scene_to_json(s)); }

void run_until(Simulation& sim, double t) {
  while (sim.time() < t) sim.step();
}

using test::expect_same_state;

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("rtsph_run_ckpt_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The straight run and the checkpointed run, compared at 2T; returns the steps taken.
std::uint64_t check_resume_is_exact(const SimSpec& spec, double T, int threads = 1) {
  TempDir dir;
  const fs::path file = dir.path() / "half.ckpt";

  auto straight = make_simulation(spec, threads);
  run_until(*straight, T);
  const std::uint64_t steps_at_T = straight->step_count();
  run_until(*straight, 2 * T);

  {
    auto first = make_simulation(spec, threads);
    run_until(*first, T);
    EXPECT_EQ(first->step_count(), steps_at_T);
    io::write_checkpoint(file, *first, hash_of(spec));
  }  // the first half's process is gone

  auto resumed = make_simulation(spec, threads);
  io::read_checkpoint(file, *resumed, hash_of(spec));
  EXPECT_EQ(resumed->step_count(), steps_at_T);
  run_until(*resumed, 2 * T);
  expect_same_state(*straight, *resumed);
  return straight->step_count();
}

TEST(RunCheckpoint, ResumeIsBitwiseExactDamBreak2D) {
  const auto steps = check_resume_is_exact(test::dam_break_2d(0.5, 0.02), 0.1 * sanitizer_scale());
  EXPECT_GT(steps, 50u);
}

TEST(RunCheckpoint, ResumeIsBitwiseExactDamBreak3D) {
  SimSpec s = load_scene("dam_break_3d");
  s.spacing = 0.04;  // ~3,000 particles
  check_resume_is_exact(s, 0.05 * sanitizer_scale());
}

TEST(RunCheckpoint, ResumeIsBitwiseExactWithEmittersAndMovingObstacle) {
  // The nozzle adds particles (emitter state, next ids) and the obstacle moves (pose, boundary
  // particles re-sorted every step).
  SimSpec s = load_scene("nozzle_moving_obstacle_2d");
  ASSERT_FALSE(s.emitters.empty());
  ASSERT_FALSE(s.obstacles.empty());
  auto probe = make_simulation(s, 1);
  const std::size_t n0 = probe->fluid().count;
  run_until(*probe, 0.3 * sanitizer_scale());
  EXPECT_GT(probe->fluid().count, n0) << "the emitter should have added particles by T";
  check_resume_is_exact(s, 0.3 * sanitizer_scale());
}

// DFSPH with the surface band at the rest lattice's cut sums (solver.dfsph.surface_density
// "lattice"): the per-particle targets are not saved but rebuilt from the positions on load
// (Dfsph::state_loaded), to the same bits.
TEST(RunCheckpoint, ResumeIsBitwiseExactDfsphLatticeSurface) {
  SimSpec s = test::dam_break_2d(0.5, 0.02);
  s.method = "dfsph";
  s.kernel = KernelType::WendlandC2;
  s.smoothing_ratio = 1.5;
  s.boundary_layers = 3;
  s.dfsph_surface_density = SurfaceDensity::Lattice;
  // Several steps in each half, also at the sanitizers' quarter length (0.05 s there: 20 steps).
  EXPECT_GE(check_resume_is_exact(s, 0.1 * sanitizer_scale()), 10u);
}

TEST(RunCheckpoint, ResumeIsBitwiseExactFixedDtTwoThreads) {
  SimSpec s = test::tank(2, 0.5, 0.3, 0.02);
  s.time_step_mode = TimeStepMode::Fixed;
  s.dt = 2e-4;
  check_resume_is_exact(s, 0.02 * sanitizer_scale(), 2);
}

TEST(RunCheckpoint, CheckpointOfAnotherSceneIsRefused) {
  TempDir dir;
  const SimSpec a = test::dam_break_2d(0.5, 0.02);
  SimSpec b = a;
  b.viscosity = 2e-6;
  auto sim = make_simulation(a, 1);
  sim->step();
  io::write_checkpoint(dir.path() / "a.ckpt", *sim, hash_of(a));
  auto other = make_simulation(b, 1);
  EXPECT_THROW(io::read_checkpoint(dir.path() / "a.ckpt", *other, hash_of(b)), io::CheckpointError);
  EXPECT_NE(hash_of(a), hash_of(b));
}

TEST(RunCheckpoint, SceneJsonRoundTripKeepsTheHash) {
  // `rtsph run --resume FILE` rebuilds the scene from the JSON stored next to the checkpoint;
  // the hash must survive that, including live changes such as a halved dt.
  for (const auto& [name, desc] : builtin_scenes()) {
    SimSpec s = load_scene(name);
    s.cfl *= 0.5;
    s.max_dt *= 0.5;
    const std::string json = scene_to_json(s);
    EXPECT_EQ(scene_to_json(parse_scene(json, name)), json) << name;
  }
}

TEST(RunCheckpoint, SnapshotRestoreIsBitwiseExact) {
  const SimSpec spec = test::dam_break_2d(0.5, 0.02);
  auto a = make_simulation(spec, 1);
  run_until(*a, 0.03 * sanitizer_scale());
  StateSnapshot snap;
  snap.capture(*a);
  EXPECT_EQ(snap.step(), a->step_count());
  EXPECT_GT(snap.bytes(), a->fluid().count * 4);
  run_until(*a, 0.06 * sanitizer_scale());  // a runs on from the snapshot

  // b: a fresh simulation restored from a's snapshot, and a itself rewound to it.
  auto b = make_simulation(spec, 1);
  snap.restore(*b);
  run_until(*b, 0.06 * sanitizer_scale());
  expect_same_state(*a, *b);

  snap.restore(*a);
  EXPECT_EQ(a->time(), snap.time());
  run_until(*a, 0.06 * sanitizer_scale());
  expect_same_state(*a, *b);
}

TEST(RunCheckpoint, SnapshotRefusesAnotherLayout) {
  auto a = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  auto b = make_simulation(load_scene("nozzle_obstacle_2d"), 1);  // has obstacles and emitters
  StateSnapshot empty;
  EXPECT_THROW(empty.restore(*a), std::logic_error);
  StateSnapshot snap;
  snap.capture(*a);
  EXPECT_THROW(snap.restore(*b), std::logic_error);
}

}  // namespace
}  // namespace rtsph
