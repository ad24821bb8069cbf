// The stages that keep the particles' arrangement uniform, on the GPU backend: particle shifting
// (solver.shifting; FluidWorld::shift_particles on the CPU, shaders/gpu/shift.comp and
// shift_apply.comp) and the transport-velocity formulation (solver.transport_velocity;
// FluidWorld::transport_velocity_shift and add_transport_velocity_stress, shaders/gpu/
// transport.comp, transport_stress.comp and kick_drift.comp's TRANSPORT). Each moves the
// particles as the CPU's does, to float round-off, in a periodic vortex (2D) and in a closed
// tank whose walls enter the sums (3D). Small scenes: llvmpipe in CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "gpu/backend.h"
#include "io/checkpoint.h"
#include "gpu_compare.h"

using namespace rtsph;
using namespace rtsph::test;

namespace {

// A Taylor–Green vortex in a periodic box (no walls), WCSPH.
SimSpec vortex(double shifting) {
  SimSpec s;
  s.name = "shifting_vortex";
  s.dimension = 2;
  s.spacing = 0.05;
  s.domain_max = {{1, 1, 0}};
  s.periodic = PeriodicAxes::XY;
  s.gravity = {{0, 0, 0}};
  s.speed_of_sound = 10;
  s.artificial_viscosity = 0;
  s.viscosity = 0.01;
  s.clamp_negative_pressure = false;
  s.shifting = shifting;
  s.fluid_blocks.push_back({{{0, 0, 0}}, s.domain_max, {}});
  return s;
}

void set_vortex(Simulation& sim) {
  const ParticleView v = sim.fluid();
  std::vector<float> vx(v.count), vy(v.count);
  for (std::size_t i = 0; i < v.count; ++i) {
    const double x = v.x[0][i], y = v.x[1][i], k = 2 * std::numbers::pi;
    vx[i] = float(-std::cos(k * x) * std::sin(k * y));
    vy[i] = float(std::sin(k * x) * std::cos(k * y));
  }
  std::vector<float> vz(v.count, 0.0f);
  const float* vel[3] = {vx.data(), vy.data(), vz.data()};
  std::vector<float> px(v.x[0], v.x[0] + v.count), py(v.x[1], v.x[1] + v.count), pz(v.count, 0.0f);
  const float* pos[3] = {px.data(), py.data(), pz.data()};
  sim.overwrite_fluid(pos, vel);
}

// A 3D tank with a block of water moving towards a wall under gravity: the walls' samples are
// part of the concentration gradient, and a shift that would cross a wall stops on it.
SimSpec tank(double shifting) {
  SimSpec s;
  s.name = "shifting_tank";
  s.dimension = 3;
  s.spacing = 0.025;
  s.domain_max = {{0.25, 0.25, 0.15}};
  s.shifting = shifting;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{0.15, 0.15, 0.15}}, {}});
  s.fluid_blocks[0].velocity = {{0.5, 0, 0}};
  return s;
}

// A 3D channel full of water, periodic along x and z, between walls across y, streaming under a
// body force: the transport velocity has no free surface to push off (it has no treatment for
// one), and the walls enter its sum.
SimSpec channel(double transport_velocity) {
  SimSpec s;
  s.name = "transport_channel";
  s.dimension = 3;
  s.spacing = 0.025;
  s.domain_max = {{0.2, 0.15, 0.2}};
  s.periodic = PeriodicAxes::XZ;
  s.gravity = {{0, 0, 0}};
  s.body_force = {{2.0, 0, 1.0}};
  s.speed_of_sound = 10;
  s.viscosity = 0.01;
  s.clamp_negative_pressure = false;
  s.transport_velocity = transport_velocity;
  s.fluid_blocks.push_back({{{0, 0, 0}}, s.domain_max, {}});
  s.fluid_blocks[0].velocity = {{0.5, 0, 0.25}};
  return s;
}

// Runs `on` on both backends and `off` (the stage switched off) on the CPU for `steps` steps,
// from the vortex's velocities in 2D: how far the GPU's particles are from the CPU's (diff), and
// how far the stage moved the CPU's (effect), seen across periodic seams.
struct Comparison {
  double diff, effect, ke_gpu, ke_cpu;
  std::size_t particles;
};
Comparison against_the_cpu(const SimSpec& on, const SimSpec& off, const double* period, int steps) {
  auto cpu = make_simulation(on, 1);
  auto gpu = gpu::make_gpu_simulation(on, 1);
  auto without = make_simulation(off, 1);
  if (on.dimension == 2) { set_vortex(*cpu); set_vortex(*gpu); set_vortex(*without); }
  for (int s = 0; s < steps; ++s) { cpu->step(); gpu->step(); without->step(); }
  EXPECT_EQ(gpu->stats().particles_put_back, 0u);
  return {worst_position_difference(*gpu, *cpu, period), worst_position_difference(*without, *cpu, period),
          gpu->stats().kinetic_energy_j, cpu->stats().kinetic_energy_j, cpu->stats().fluid_particles};
}

}  // namespace

TEST_F(GpuBackend, ShiftingAsOnTheCpu) {
  struct Case { SimSpec on, off; double period[3]; int steps; };
  const Case cases[] = {{vortex(2.0), vortex(0.0), {1, 1, 0}, 30}, {tank(1.0), tank(0.0), {0, 0, 0}, 30}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.on.name);
    const Comparison r = against_the_cpu(c.on, c.off, c.period, c.steps);
    std::printf("%s: %zu particles, %d steps: worst GPU - CPU position %.3g m; shifting moved a particle "
                "%.3g m against the unshifted run\n", c.on.name.c_str(), r.particles, c.steps, r.diff, r.effect);
    EXPECT_GT(r.effect, 0.01 * c.on.spacing);  // the stage acts
    EXPECT_LT(r.diff, 0.1 * r.effect);          // and the GPU's is the CPU's
    EXPECT_LT(r.diff, 2e-5 * c.on.spacing);     // round-off (a CPU that read unsorted ρⱼ: 4e-4)
  }
}

// Taylor–Green with the transport velocity at p_b = ρ0c0² (the validation case's choice) and a
// 3D channel between walls with it, on both backends, with WCSPH and with DFSPH (whose p_b is
// capped at ρ0 (cfl·h/Δt)², Dfsph::step). The vortex's amplitude is compared too: the stage is
// what holds it (physics_transport_velocity_test.cpp). DFSPH is compared after 10 steps: its
// solves stop on a tolerance, and where a mean error lands within round-off of it one backend
// sweeps once more (the DFSPH vortex after 30 steps: 4.5e-5 m apart, 0.3% of what the stage
// moved; after 10: 2.4e-7 m, as WCSPH's).
TEST_F(GpuBackend, TransportVelocityAsOnTheCpu) {
  auto with_tv = [](SimSpec s, double tv) { s.shifting = 0; s.transport_velocity = tv; return s; };
  auto dfsph = [](SimSpec s) { s.method = "dfsph"; s.name += "_dfsph"; return s; };
  struct Case { SimSpec on, off; double period[3]; int steps; };
  const Case cases[] = {{with_tv(vortex(0), 1.0), with_tv(vortex(0), 0.0), {1, 1, 0}, 30},
                        {channel(1.0), channel(0.0), {0.2, 0, 0.2}, 30},
                        {dfsph(with_tv(vortex(0), 1.0)), dfsph(with_tv(vortex(0), 0.0)), {1, 1, 0}, 10},
                        {dfsph(channel(1.0)), dfsph(channel(0.0)), {0.2, 0, 0.2}, 10}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.on.name);
    const Comparison r = against_the_cpu(c.on, c.off, c.period, c.steps);
    std::printf("%s with the transport velocity: %d steps: worst GPU - CPU position %.3g m (the stage "
                "moved a particle %.3g m); kinetic energy %.6g / %.6g J (GPU / CPU)\n", c.on.name.c_str(),
                c.steps, r.diff, r.effect, r.ke_gpu, r.ke_cpu);
    // The stage acts (in the channel, near the walls only: the stream is uniform), and the GPU's
    // is the CPU's to round-off.
    EXPECT_GT(r.effect, 1e-3 * c.on.spacing);
    EXPECT_LT(r.diff, 0.01 * r.effect);
    EXPECT_LT(r.diff, 2e-5 * c.on.spacing);
    EXPECT_NEAR(r.ke_gpu, r.ke_cpu, 1e-5 * r.ke_cpu);
  }
}

// ṽ − v travels in checkpoints across backends: GPU → checkpoint → CPU resumes as the GPU runs
// on, with WCSPH and with DFSPH (whose warm-start pressures travel too). DFSPH runs 5 steps on
// each side of the checkpoint: its solves stop on a tolerance (TransportVelocityAsOnTheCpu).
TEST_F(GpuBackend, TransportVelocityCheckpointResumesOnTheCpu) {
  for (const char* method : {"wcsph", "dfsph"}) {
    SCOPED_TRACE(method);
    SimSpec s = vortex(0);
    s.method = method;
    s.transport_velocity = 1.0;
    const int steps = s.method == "dfsph" ? 5 : 10;
    auto gpu = gpu::make_gpu_simulation(s, 1);
    set_vortex(*gpu);
    for (int i = 0; i < steps; ++i) gpu->step();
    const auto file = std::filesystem::temp_directory_path() / "rtsph_gpu_tvf.ckpt";
    io::write_checkpoint(file, *gpu, 7);
    auto cpu = make_simulation(s, 1);
    io::read_checkpoint(file, *cpu, 7);
    std::filesystem::remove(file);
    for (int i = 0; i < steps; ++i) { gpu->step(); cpu->step(); }
    const double period[3] = {1, 1, 0};
    const double diff = worst_position_difference(*gpu, *cpu, period);
    std::printf("%s, GPU -> checkpoint -> CPU with the transport velocity: worst position difference after %d "
                "more steps %.3g m\n", method, steps, diff);
    EXPECT_LT(diff, 2e-5 * s.spacing);
  }
}

// The GPU runs every liquid method, with every arrangement stage; it refuses the gas method,
// with the documented one line.
TEST_F(GpuBackend, RunsEveryLiquidMethodAndRefusesTheGas) {
  SimSpec s = vortex(1.0);
  s.transport_velocity = 1.0;
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  s.method = "dfsph";
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  s.transport_velocity = 0;
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  s.method = "pbf";
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  s.method = "gas";
  const std::string why = gpu::gpu_cannot_run(s);
  EXPECT_NE(why.find("\"gas\""), std::string::npos) << why;
  EXPECT_NE(why.find("use --backend cpu"), std::string::npos) << why;
}

// DFSPH's surface band at the rest lattice's cut sums (solver.dfsph.surface_density "lattice"):
// a 2D tank at rest, Wendland C2 at h = 1.5 spacings, three wall layers, on both backends for
// 10 steps (DFSPH's solves stop on a tolerance: TransportVelocityAsOnTheCpu says why 10). The
// target moves the top layers against ρ0's run, and the GPU's run is the CPU's.
SimSpec wide_kernel_tank() {
  SimSpec s;
  s.name = "lattice_tank";
  s.dimension = 2;
  s.spacing = 0.01;
  s.domain_max = {{0.2, 0.2, 0}};
  s.method = "dfsph";
  s.kernel = KernelType::WendlandC2;
  s.smoothing_ratio = 1.5;
  s.boundary_layers = 3;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{0.2, 0.1, 0}}, {}});
  return s;
}

TEST_F(GpuBackend, LatticeSurfaceDensityAsOnTheCpu) {
  SimSpec s = wide_kernel_tank();
  SimSpec rest = s;
  s.dfsph_surface_density = SurfaceDensity::Lattice;
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  auto cpu = make_simulation(s, 1), without = make_simulation(rest, 1);
  auto gpu = gpu::make_gpu_simulation(s, 1);
  for (int k = 0; k < 10; ++k) { cpu->step(); gpu->step(); without->step(); }
  const double zero[3] = {0, 0, 0};
  const double diff = worst_position_difference(*gpu, *cpu, zero);
  const double effect = worst_position_difference(*without, *cpu, zero);
  std::printf("lattice tank: 10 steps, worst GPU - CPU position %.3g m; the target moved a particle "
              "%.3g m against rho0's run\n", diff, effect);
  EXPECT_GT(effect, 1e-3 * s.spacing);  // the target acts (measured: 8.4e-4 m)
  EXPECT_LT(diff, 0.1 * effect);
  EXPECT_LT(diff, 2e-5 * s.spacing);     // round-off (measured: 4.5e-8 m)
}

// DFSPH's pressure stabilisation (solver.dfsph.pressure_stabilisation): the same tank with the
// lattice's surface sums and β = 1, against β = 0, on both backends for 10 steps. The Laplacian
// changes the pressure, and the GPU's is the CPU's.
TEST_F(GpuBackend, PressureStabilisationAsOnTheCpu) {
  SimSpec s = wide_kernel_tank();
  s.dfsph_surface_density = SurfaceDensity::Lattice;
  SimSpec off = s;
  s.dfsph_pressure_stabilisation = 1.0;
  EXPECT_EQ(gpu::gpu_cannot_run(s), "");
  auto cpu = make_simulation(s, 1), without = make_simulation(off, 1);
  auto gpu = gpu::make_gpu_simulation(s, 1);
  for (int k = 0; k < 10; ++k) { cpu->step(); gpu->step(); without->step(); }
  const double diff = worst_pressure_difference(*gpu, *cpu);
  const double effect = worst_pressure_difference(*without, *cpu);
  const double zero[3] = {0, 0, 0};
  std::printf("stabilised tank: 10 steps, worst GPU - CPU pressure %.3g Pa, position %.3g m; beta = 1 "
              "moved a pressure by %.3g Pa against beta = 0\n", diff,
              worst_position_difference(*gpu, *cpu, zero), effect);
  const double bottom = 1000.0 * 9.81 * 0.1;
  EXPECT_GT(effect, 1e-3 * bottom);  // the Laplacian acts (measured: 30.3 Pa)
  EXPECT_LT(diff, 0.05 * effect);
  EXPECT_LT(diff, 1e-4 * bottom);    // round-off (measured: 0.011 Pa)
}
