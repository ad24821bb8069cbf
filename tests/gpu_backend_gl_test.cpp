// The GPU backend (OpenGL compute) against the CPU backend and against physics, on Mesa llvmpipe
// in CI: small scenes, a few hundred steps (llvmpipe is some 30x slower than the CPU solver).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include <fmt/format.h>

#include "gl_test_context.h"
#include "gpu_compare.h"
#include "gpu/backend.h"
#include "gpu/gl_compute.h"
#include "io/checkpoint.h"
#include "render/camera.h"
#include "render/renderer.h"
#include "hydrostatic_check.h"
#include "test_scenes.h"

using namespace rtsph;
using namespace rtsph::test;

namespace {

// The surge front: the largest x of any fluid particle (2D and 3D dam breaks run along x).
double front(const Simulation& s) {
  const ParticleView v = s.fluid();
  double m = 0;
  for (std::size_t i = 0; i < v.count; ++i) m = std::max(m, double(v.x[0][i]));
  return m;
}

SimSpec dam_break_3d(double a, double spacing) {
  SimSpec s;
  s.name = "dam_break_3d_test";
  s.dimension = 3;
  s.domain_min = {{0, 0, 0}};
  s.domain_max = {{4 * a, 2.5 * a, a}};
  s.spacing = spacing;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{a, 2 * a, a}}, {}});
  return s;
}

// Iteration counts of the two backends' solves, step by step: how many steps differ, and how
// the GPU's count moved (a stopping test on the device must see both rises and falls).
struct IterationTally {
  int differ = 0, rises = 0, falls = 0, last = -1, most = 0;
  bool add(int cpu, int gpu) {
    if (last >= 0 && gpu > last) ++rises;
    if (last >= 0 && gpu < last) ++falls;
    last = gpu;
    most = std::max(most, gpu);
    if (cpu == gpu) return true;
    ++differ;
    return false;
  }
};
}  // namespace

TEST_F(GpuBackend, EveryComputeShaderCompilesForEveryDimensionAndKernel) {
  EXPECT_EQ(gpu::compute_support_problem(), "");
  for (const auto& name : gpu::compute_shader_names())
    for (int dim : {2, 3})
      for (int kernel = 0; kernel < 4; ++kernel) {
        std::vector<std::string> d = {fmt::format("DIM {}", dim), fmt::format("KERNEL {}", kernel),
                                      "MODE 1", "FINAL 0", "COUNT 2"};
        EXPECT_NO_THROW(gpu::ComputeProgram(name, d)) << name << " DIM " << dim << " KERNEL " << kernel;
      }
}

class GpuMethods : public GpuBackend, public ::testing::WithParamInterface<const char*> {};
INSTANTIATE_TEST_SUITE_P(All, GpuMethods, ::testing::Values("wcsph", "pbf", "dfsph"));

// The same stable sort by the same cell keys: the GPU puts the particles in the CPU's order, and
// their densities agree to float round-off (the sums run in a different order).
TEST_P(GpuMethods, FirstStepMatchesTheCpuIn2DAnd3D) {
  for (int dim : {2, 3}) {
    SimSpec spec = dim == 2 ? test::dam_break_2d(0.1, 0.005) : dam_break_3d(0.1, 0.01);
    spec.method = GetParam();
    auto cpu = make_simulation(spec, 1);
    auto gpu = gpu::make_gpu_simulation(spec, 1);
    {
      const ParticleView c = cpu->fluid(), g = gpu->fluid();
      ASSERT_EQ(c.count, g.count);
      EXPECT_TRUE(std::equal(c.id, c.id + c.count, g.id)) << dim << "D: the sorted order differs";
      const double e0 = relative_rms_density(*cpu, *gpu);
      std::printf("%dD, %zu particles: density relative RMS at t = 0: %.3g\n", dim, c.count, e0);
      EXPECT_LT(e0, 1e-5);
    }
    cpu->step();
    gpu->step();
    EXPECT_EQ(cpu->stats().dt_s, gpu->stats().dt_s) << "the same state gives the same time step";
    const double e1 = relative_rms_density(*cpu, *gpu);
    std::printf("%dD: density relative RMS after the first step: %.3g\n", dim, e1);
    EXPECT_LT(e1, 1e-5);
  }
}

// 200 steps of a dam break: the surge front within 1% and the maximum density error within 0.5
// percentage points of the CPU's.
TEST_P(GpuMethods, DamBreakFollowsTheCpuFor200Steps) {
  const bool pbf = std::string(GetParam()) == "pbf";
  for (int dim : {2, 3}) {
    SimSpec spec = dim == 2 ? test::dam_break_2d(0.1, 0.005) : dam_break_3d(0.1, 0.0125);
    spec.method = GetParam();
    if (pbf) spec.pbf_time_step = 1.0 / 240;  // 200 PBF steps then reach the splash, as WCSPH's do
    auto cpu = make_simulation(spec, 2);
    auto gpu = gpu::make_gpu_simulation(spec, 2);
    double max_err_cpu = 0, max_err_gpu = 0;
    for (int s = 0; s < 200; ++s) {
      cpu->step();
      gpu->step();
      max_err_cpu = std::max(max_err_cpu, cpu->stats().density_error);
      max_err_gpu = std::max(max_err_gpu, gpu->stats().density_error);
    }
    const double fc = front(*cpu), fg = front(*gpu);
    std::printf("%s %dD after 200 steps: t = %.4f / %.4f s, front %.5f / %.5f m, max density error %.4f / %.4f (CPU / GPU)\n",
                GetParam(), dim, cpu->time(), gpu->time(), fc, fg, max_err_cpu, max_err_gpu);
    // PBF's Jacobi iterations amplify round-off, and the front is one particle, the foremost:
    // on one Intel host the 2D front read 0.36416 / 0.36440 m (CPU / GPU) in the release build and
    // 0.36870 / 0.36266 m in the ASan build, both backends moving with the build's flags (1.6%
    // apart there). So PBF's front is held to 2%, WCSPH's and DFSPH's to 1%.
    EXPECT_NEAR(fg, fc, (pbf ? 0.02 : 0.01) * fc);
    EXPECT_NEAR(max_err_gpu, max_err_cpu, 0.005);
    // The time after 200 steps follows the fastest particle of the splash against the far wall
    // (the step's CFL bound) and is chaotic there: the CPU alone, with gravity nudged by 1e-8 to
    // 3e-8 of itself, read 0.4686-0.4735 s in 3D with DFSPH (session 44, after the container
    // walls took the lattice's volume; 0.4548 s in all four draws before), and the GPU 0.4687.
    // So the bound is 2%, above the reference's own round-off spread.
    EXPECT_NEAR(gpu->time(), cpu->time(), 0.02 * cpu->time());
    EXPECT_EQ(gpu->stats().particles_put_back, cpu->stats().particles_put_back);
  }
}

TEST_P(GpuMethods, TwoRunsAreBitwiseIdentical) {
  SimSpec spec = test::dam_break_2d(0.1, 0.005);
  spec.method = GetParam();
  auto a = gpu::make_gpu_simulation(spec, 1);
  auto b = gpu::make_gpu_simulation(spec, 2);
  for (int s = 0; s < 60; ++s) { a->step(); b->step(); }
  const ParticleView va = a->fluid(), vb = b->fluid();
  ASSERT_EQ(va.count, vb.count);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(0, std::memcmp(va.x[k], vb.x[k], va.count * 4));
    EXPECT_EQ(0, std::memcmp(va.v[k], vb.v[k], va.count * 4));
  }
  EXPECT_EQ(0, std::memcmp(va.density, vb.density, va.count * 4));
  EXPECT_EQ(a->time(), b->time());
}

// Pair forces are antisymmetric, so a free block (no gravity, away from the walls) keeps its
// total momentum while its particles scatter.
TEST_F(GpuBackend, FreeBlockConservesMomentum) {
  SimSpec spec;
  spec.name = "free_block";
  spec.dimension = 3;
  spec.domain_min = {{0, 0, 0}};
  spec.domain_max = {{1, 1, 1}};
  spec.spacing = 0.02;
  spec.gravity = {};
  spec.speed_of_sound = 20;
  spec.fluid_blocks.push_back({{{0.4, 0.4, 0.4}}, {{0.6, 0.6, 0.6}}, {}});
  auto gpu = gpu::make_gpu_simulation(spec, 1);
  const ParticleView v0 = gpu->fluid();
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0, 0.3f);
  std::vector<float> vel[3];
  for (int k = 0; k < 3; ++k) {
    vel[k].resize(v0.count);
    double mean = 0;
    for (auto& x : vel[k]) { x = noise(rng); mean += x; }
    mean /= double(v0.count);
    for (auto& x : vel[k]) x -= float(mean);
  }
  const float* vp[3] = {vel[0].data(), vel[1].data(), vel[2].data()};
  gpu->overwrite_fluid(nullptr, vp);
  for (int s = 0; s < 100; ++s) gpu->step();
  const ParticleView v = gpu->fluid();
  double p[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < v.count; ++i)
    for (int k = 0; k < 3; ++k) {
      p[k] += v.v[k][i];
      scale += std::abs(v.v[k][i]);
    }
  const double pn = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  std::printf("after %.4f s: |sum v| / sum |v| = %.3g\n", gpu->time(), pn / scale);
  EXPECT_GT(scale, 0);
  EXPECT_LT(pn / scale, 1e-5);
  EXPECT_EQ(gpu->stats().particles_put_back, 0u);
}

// The counting sort ranks each cell's particles by their previous index (cell_sort_order.comp),
// which is quadratic in a cell's count: a cell with more than 4096 keeps the atomics' order. Two
// piles, 3,000 particles on one point (ranked) and 5,000 on another (not), must still sort into
// a permutation of the fluid, and step.
TEST_F(GpuBackend, SortSurvivesPilesOfParticlesInOneCell) {
  SimSpec spec = test::dam_break_2d(0.2, 0.002);
  spec.speed_of_sound = 20;
  auto gpu = gpu::make_gpu_simulation(spec, 1);
  const ParticleView v0 = gpu->fluid();
  ASSERT_GT(v0.count, 9000u);
  std::vector<float> x(v0.x[0], v0.x[0] + v0.count), y(v0.x[1], v0.x[1] + v0.count);
  for (std::size_t i = 0; i < 3000; ++i) { x[i] = 0.05f; y[i] = 0.05f; }
  for (std::size_t i = 3000; i < 8000; ++i) { x[i] = 0.15f; y[i] = 0.15f; }
  std::vector<float> z(v0.count, 0.0f);
  const float* xp[3] = {x.data(), y.data(), z.data()};
  gpu->overwrite_fluid(xp, nullptr);
  gpu->step();
  const ParticleView v = gpu->fluid();
  ASSERT_EQ(v.count, v0.count);
  std::vector<int> seen(v.count, 0);
  for (std::size_t i = 0; i < v.count; ++i) {
    ASSERT_LT(v.id[i], v.count);
    ++seen[v.id[i]];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(v.count));
}

// Checkpoints are the CPU's format: a GPU run resumes on the CPU and a CPU run on the GPU, and
// each resumed run continues as a straight run on that backend does.
TEST_P(GpuMethods, CheckpointsResumeAcrossBackends) {
  SimSpec spec = test::dam_break_2d(0.1, 0.005);
  spec.method = GetParam();
  // PBF at a fixed sweep count: its adaptive stop (mean compression under 1%) can fall one sweep
  // apart on the two backends when the mean sits near the line, and the comparison then reads
  // the extra sweep (1.7% RMS in the ASan build on an AMD EPYC host, session 31), not the resume.
  spec.pbf_max_density_error = 0;
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("rtsph_gpu_ckpt_{}", ::getpid());
  std::filesystem::create_directories(dir);
  for (bool gpu_first : {true, false}) {
    auto make = [&](bool on_gpu) { return on_gpu ? gpu::make_gpu_simulation(spec, 1) : make_simulation(spec, 1); };
    auto first = make(gpu_first);
    for (int s = 0; s < 40; ++s) first->step();
    const auto path = dir / "state.ckpt";
    io::write_checkpoint(path, *first, 42);
    // The straight run on the second backend from the same state, and the resumed one.
    auto resumed = make(!gpu_first);
    io::read_checkpoint(path, *resumed, 42);
    auto again = make(!gpu_first);
    io::read_checkpoint(path, *again, 42);
    EXPECT_EQ(resumed->time(), first->time());
    EXPECT_EQ(resumed->step_count(), 40u);
    {  // the loaded state is the saved one, bit for bit
      const ParticleView a = first->fluid(), b = resumed->fluid();
      ASSERT_EQ(a.count, b.count);
      EXPECT_TRUE(std::equal(a.id, a.id + a.count, b.id));
      for (int k = 0; k < 2; ++k) {
        EXPECT_EQ(0, std::memcmp(a.x[k], b.x[k], a.count * 4));
        EXPECT_EQ(0, std::memcmp(a.v[k], b.v[k], a.count * 4));
      }
    }
    // Then the two backends go on from it as from any state, float round-off apart (PBF's one-sided
    // constraint amplifies that within ten steps of a splash: 0.2% RMS in density between
    // straight CPU and GPU runs, so two steps are compared). PBF at its fixed 4 sweeps: 6.7e-4 to
    // 8.3e-4 RMS in the release build, 8.4e-4 to 9.3e-4 in the ASan build (AMD EPYC host, session
    // 31; the last also after one step): the unconverged sweeps carry each backend's round-off.
    const double tolerance = std::string(GetParam()) == "pbf" ? 2e-3 : 1e-3;
    for (int s = 0; s < 2; ++s) { first->step(); resumed->step(); again->step(); }
    const double e = relative_rms_density(*first, *resumed);
    std::printf("%s, %s -> %s: density relative RMS 2 steps after the resume: %.3g\n", GetParam(), gpu_first ? "GPU" : "CPU",
                gpu_first ? "CPU" : "GPU", e);
    EXPECT_LT(e, tolerance);
    EXPECT_NEAR(front(*resumed), front(*first), 0.01 * front(*first));
    const ParticleView a = resumed->fluid(), b = again->fluid();
    ASSERT_EQ(a.count, b.count);
    EXPECT_EQ(0, std::memcmp(a.x[0], b.x[0], a.count * 4)) << "resuming is deterministic";
  }
  std::filesystem::remove_all(dir);
}

// The CPU methods' tank test (hydrostatic_check.h) on the GPU, with each method's tolerance:
// WCSPH 5%, PBF 5% (at its stable weight, its bottom two rows), DFSPH 5% (below). (The 3D PBF tank measured 0.969 on the GPU, 3.1% low, against 0.9735 on the
// CPU: both sit at the edge of PBF's 3%, PBF's own deficit (issue 9), so only 2D is asserted here.)
TEST_F(GpuBackend, WcsphTankSettlesToRhoGH) {
  test::settles_to_hydrostatic(2, 1.0, 1.0, 0.025, "wcsph", 0.05, 0,
                               [](const SimSpec& s) { return gpu::make_gpu_simulation(s, 1); });
}
// PBF at the stable Jacobi weight (tests/physics_hydrostatic_test.cpp says why). Its bottom row's
// figure moves by a percent with round-off: with gravity nudged by 0, 1e-7 and 3e-7 of itself the
// GPU (llvmpipe) read 1.0549, 1.0478 and 1.0375, the CPU 1.0312, 1.0302 and 1.0269 (session 44,
// the lattice wall volumes), and before those walls 1.0404, 1.0307, 1.0288 and 1.0419, 1.0449,
// 1.0480: the CPU's 5% left no room for that spread on the GPU, and it was held to 6%. Since
// session 52 the PBF tank tests read the bottom two rows, one period of the floor's row-to-row
// alternation (hydrostatic_check.h): llvmpipe on the Intel Xeon guest read 1.0549 on the bottom
// row and 1.0226 on two, so the GPU is held to the CPU's 5% again.
TEST_F(GpuBackend, PbfTankSettlesToRhoGH) {
  test::settles_to_hydrostatic(2, 1.0, 1.0, 0.025, "pbf", 0.05, 3.0, [](const SimSpec& s) {
    SimSpec spec = s;
    spec.pbf_omega = 0;
    return gpu::make_gpu_simulation(spec, 1);
  }, 2);
}
// DFSPH with the CPU test's tolerance for the 2D tank (5%: the CPU reads 3.9%; tests/
// physics_hydrostatic_test.cpp says why it is not issue 9's 1%).
TEST_F(GpuBackend, DfsphTankSettlesToRhoGH) {
  test::settles_to_hydrostatic(2, 1.0, 1.0, 0.025, "dfsph", 0.05, 0,
                               [](const SimSpec& s) { return gpu::make_gpu_simulation(s, 1); });
}

// The GPU tests DFSPH's stopping rule on the device and the host reads the outcome once per batch
// of queued sweeps (dfsph_gate.comp): each solve must still stop after the sweeps the CPU's loop
// takes, whether the batch was too short (more are queued) or too long (the rest return at once).
// A tight tolerance makes the counts vary from step to step, so both happen.
TEST_F(GpuBackend, DfsphStopsEachSolveWhereTheCpuDoes) {
  SimSpec spec = test::dam_break_2d(0.1, 0.005);
  spec.method = "dfsph";
  spec.dfsph_max_density_error = 2e-4;
  spec.dfsph_max_divergence_error = 2e-4;
  auto cpu = make_simulation(spec, 1);
  auto gpu = gpu::make_gpu_simulation(spec, 1);
  IterationTally t;
  for (int s = 0; s < 40; ++s) {
    cpu->step();
    gpu->step();
    const SimStats c = cpu->stats(), g = gpu->stats();
    const bool same = t.add(c.pressure_iterations, g.pressure_iterations);
    if (!same || c.divergence_iterations != g.divergence_iterations) {
      if (same) ++t.differ;
      std::printf("step %d: sweeps %d + %d (CPU), %d + %d (GPU)\n", s, c.pressure_iterations,
                  c.divergence_iterations, g.pressure_iterations, g.divergence_iterations);
    }
  }
  std::printf("40 steps: %d with other sweep counts than the CPU's; the density solve's count rose %d "
              "and fell %d times, at most %d sweeps\n", t.differ, t.rises, t.falls, t.most);
  // The two backends' residuals differ by float round-off, so a solve that ends within round-off
  // of its tolerance may take one sweep more on one of them; never more than once here.
  EXPECT_LE(t.differ, 1);
  EXPECT_GT(t.rises, 0);
  EXPECT_GT(t.falls, 0);
  EXPECT_GT(t.most, 4);  // past the first batch of two
}

// PBF's stopping rule runs on the device too (pbf_gate.comp): each substep must still take the
// Jacobi iterations the CPU's loop takes, past the first batch and short of it. A tight
// tolerance with a low minimum makes the counts vary from substep to substep. Past ~25 substeps
// the two backends' states have drifted apart by round-off (and the GPU's neighbour lists reach
// past the support, the CPU's do not), enough to change counts near the tolerance: 6 of 40
// differed, all from substep 28 on.
TEST_F(GpuBackend, PbfStopsEachSubstepWhereTheCpuDoes) {
  SimSpec spec = test::dam_break_2d(0.1, 0.005);
  spec.method = "pbf";
  spec.pbf_iterations = 2;
  spec.pbf_max_density_error = 2e-3;
  spec.pbf_max_iterations = 40;
  auto cpu = make_simulation(spec, 1);
  auto gpu = gpu::make_gpu_simulation(spec, 1);
  IterationTally t;
  for (int s = 0; s < 25; ++s) {
    cpu->step();
    gpu->step();
    const SimStats c = cpu->stats(), g = gpu->stats();
    if (!t.add(c.pressure_iterations, g.pressure_iterations))
      std::printf("substep %d: %d iterations (CPU), %d (GPU)\n", s, c.pressure_iterations, g.pressure_iterations);
  }
  std::printf("25 substeps: %d with other iteration counts than the CPU's; the count rose %d and "
              "fell %d times, at most %d iterations\n", t.differ, t.rises, t.falls, t.most);
  // The backends' compressions differ by float round-off: a substep that ends within it of the
  // tolerance may take one iteration more on one of them, rarely.
  EXPECT_LE(t.differ, 1);
  EXPECT_GT(t.rises, 0);
  EXPECT_GT(t.falls, 0);
  EXPECT_GT(t.most, 4);  // past the first batch
}

// Drawing without a copy (issue 10, §3): the renderer pointed at the GPU's own buffers draws the
// same picture as from the arrays read back, in both styles and with colour by pressure.
TEST_F(GpuBackend, DrawsFromItsBuffersAsFromACopy) {
  SimSpec spec = dam_break_3d(0.1, 0.01);
  auto gpu = gpu::make_gpu_simulation(spec, 1);
  for (int s = 0; s < 30; ++s) gpu->step();
  const auto device = gpu->device_particles();
  ASSERT_TRUE(device.has_value());
  const ParticleView host = gpu->fluid();
  EXPECT_EQ(device->count, host.count);
  const int W = 160, H = 96;
  render::Camera cam;
  cam.frame({0, 0, 0}, {0.4f, 0.25f, 0.1f}, float(W) / H);
  for (auto style : {render::Style::Particles, render::Style::Surface}) {
    render::RenderSettings s;
    s.style = style;
    s.color = render::ColorMode::Pressure;
    s.legend = false;
    s.grid = false;
    s.walls = false;
    s.merge_interior = false;  // the CPU copy would merge interior splats; the device's cannot
    std::vector<unsigned char> img[2];
    for (int pass = 0; pass < 2; ++pass) {
      render::Renderer r;
      r.set_domain(3, {0, 0, 0}, {0.4f, 0.25f, 0.1f});
      if (pass == 0) r.use_device(*device, nullptr);
      else r.upload(host, nullptr);
      render::OffscreenTarget target(W, H);
      target.bind();
      r.draw(cam, W, H, s);
      img[pass] = target.read_rgba();
      if (pass == 1) {
        const auto [lo, hi] = r.data_range(render::ColorMode::Pressure);
        EXPECT_FLOAT_EQ(device->pressure_min, lo);
        EXPECT_FLOAT_EQ(device->pressure_max, hi);
      }
    }
    int worst = 0, water = 0;
    for (std::size_t i = 0; i < img[0].size(); ++i) worst = std::max(worst, std::abs(int(img[0][i]) - int(img[1][i])));
    for (std::size_t i = 0; i < img[0].size(); i += 4)  // drawn: not the background (corner pixel)
      water += std::abs(int(img[0][i]) - img[0][0]) + std::abs(int(img[0][i + 1]) - img[0][1]) +
                   std::abs(int(img[0][i + 2]) - img[0][2]) > 30;
    std::printf("style %d: %d fluid pixels, largest channel difference %d\n", int(style), water, worst);
    EXPECT_GT(water, 100);
    EXPECT_LE(worst, 1);
  }
}
