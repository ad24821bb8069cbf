#pragma once
// The plain description of a simulation: what a scene file says, after parsing and validation
// (src/scene fills it; the solvers only read it). SI units throughout. Vectors are 3-component;
// 2D scenes use x and y and ignore z. Defaults here are the defaults of the parameter table.
#include <cstdint>
#include <string>
#include <vector>

#include "core/kernels.h"
#include "core/vec.h"

namespace rtsph {

enum class Eos { Tait, Linear };
enum class TimeStepMode { Cfl, Fixed };
enum class ObstacleShape { Box, Sphere };  // 2D: "rectangle" and "circle" map to these
enum class MotionKind { Static, Velocity, Path };
enum class BlockShape { Box, Ball };  // 2D: "rectangle" and "circle"
enum class GasEos { Polytropic, Adiabatic };
enum class GasSmoothing { Adaptive, Global };
enum class GravitySolver { Direct, Tree };
enum class SurfaceDensity { Rest, Lattice };  // solver.dfsph.surface_density
/// Periodic axes as a bit set (x = 1, y = 2, z = 4), spelled "none", "x", "y", "xy", … in JSON.
enum class PeriodicAxes { None, X, Y, XY, Z, XZ, YZ, XYZ };
inline bool axis_is_periodic(PeriodicAxes p, int axis) { return (int(p) >> axis) & 1; }

struct FluidBlock {
  Vec3d min{}, max{};     // m
  BlockShape shape = BlockShape::Box;  // Ball: the ball (disc) inscribed in [min, max]
  Vec3d velocity{};       // m/s
};

struct Keyframe {
  double time_s = 0;
  Vec3d position{};       // m, obstacle centre
  double angle_rad = 0;   // rotation about z (2D) or about `axis` (3D)
};

struct ObstacleSpec {
  ObstacleShape shape = ObstacleShape::Box;
  Vec3d center{};                  // m
  Vec3d half_extents{0.1, 0.1, 0.1};  // m, box/rectangle
  double radius = 0.1;             // m, sphere/circle
  MotionKind motion = MotionKind::Static;
  Vec3d velocity{};                // m/s, MotionKind::Velocity
  Vec3d angular_velocity{};        // rad/s about the centre (2D uses z)
  std::vector<Keyframe> path;      // MotionKind::Path, sorted by time, linear interpolation
};

struct EmitterSpec {
  Vec3d position{};                // m, nozzle centre
  Vec3d direction{1, 0, 0};        // jet direction (normalised on use)
  double speed = 2.0;              // m/s
  double width = 0.1;              // m, nozzle width (2D) or diameter (3D)
  double rate = 0;                 // particles/s; 0 = continuous jet (a layer every spacing/speed)
  double start_s = 0, stop_s = 1e30;
  std::int64_t max_particles = 100000;
};

struct SimSpec {
  std::string name = "scene";
  int dimension = 3;
  Vec3d domain_min{0, 0, 0}, domain_max{1, 1, 1};  // m, the container walls
  PeriodicAxes periodic = PeriodicAxes::None;      // axes that wrap (no walls there)
  bool open = false;  // open space: no walls, the domain only bounds the initial fluid

  // fluid
  double spacing = 0.02;           // m, initial particle spacing
  double rest_density = 1000.0;    // kg/m³
  double viscosity = 1e-6;         // m²/s, kinematic (Morris et al. 1997 laminar term)
  double surface_tension = 0;      // Akinci et al. 2013's γ (cohesion + curvature); 0 = off
  double adhesion = 0;             // Akinci et al. 2013's β (fluid to boundary); 0 = off

  // solver
  std::string method = "wcsph";
  std::string backend = "auto";    // "cpu", "gpu" or "auto" (the command's default; --backend wins)
  Eos eos = Eos::Tait;
  double speed_of_sound = 0;       // m/s; 0 = automatic, 10·sqrt(2 g H) (Monaghan 1994)
  double stiffness = 0;            // m²/s² (= Pa per kg/m³) for the linear EOS; 0 = c0²
  double tait_gamma = 7.0;
  KernelType kernel = KernelType::CubicSpline;
  double smoothing_ratio = 1.0;    // h / spacing
  double artificial_viscosity = 0.02;  // Monaghan α (dimensionless)
  bool clamp_negative_pressure = true;  // avoids tensile clumping at the free surface
  double shifting = 0;             // particle shifting A (Lind et al. 2012, D = A h |v| dt); 0 = off
  bool hydrostatic_start = false;  // WCSPH: blocks start compressed to their hydrostatic density
  double transport_velocity = 0;   // background pressure p_b / (ρ0 c0²) of Adami et al. 2013; 0 = off
  TimeStepMode time_step_mode = TimeStepMode::Cfl;
  double cfl = 0.4;                // CFL number for 0.4·h/(c0 + |v|max)
  double dt = 1e-4;                // s, fixed-step mode
  double max_dt = 5e-3;            // s, upper bound in CFL mode
  int boundary_layers = 1;         // Akinci: one layer suffices; more for thin fast jets

  // PBF, position based fluids (Macklin & Müller 2013)
  double pbf_time_step = 1.0 / 60; // s, frame step, split into pbf_substeps
  int pbf_substeps = 4;            // 2 lets a 2 m deep column collapse (measured)
  int pbf_iterations = 4;          // Jacobi iterations of the density constraint per substep (at least)
  double pbf_max_density_error = 0.01;  // more iterations while the mean compression is above (0 = off)
  int pbf_max_iterations = 20;     // cap on those
  double pbf_cfl = 1.0;            // substeps shrink so no particle moves more than cfl·spacing
  double pbf_relaxation = 0.01;    // ε, relative to a full neighbourhood's Σ|∇C|²
  double pbf_omega = 1.0;          // Jacobi weight of λ (clamped constraint; 0.5 two-sided); 0 = stable
  double pbf_scorr_k = 0.1;        // artificial pressure s_corr = -k (W(r)/W(Δq))^n
  int pbf_scorr_n = 4;
  double pbf_scorr_dq = 0.2;       // Δq as a fraction of the kernel support
  double pbf_xsph = 0.01;          // XSPH viscosity c
  double pbf_vorticity = 0;        // m/s, vorticity confinement ε (0 = off)

  // DFSPH, divergence-free SPH (Bender & Koschier 2015, 2017)
  double dfsph_max_density_error = 1e-3;     // mean (ρ-ρ0)/ρ0 at which the density solve stops
  double dfsph_max_divergence_error = 1e-3;  // mean (Dρ/Dt)·dt/ρ0 at which the divergence solve stops
  int dfsph_max_iterations = 100;
  double dfsph_chebyshev = 0.95;             // ρ of the Chebyshev acceleration (0 = plain Jacobi)
  SurfaceDensity dfsph_surface_density = SurfaceDensity::Rest;  // the clamped solve's target under a cut kernel
  double dfsph_pressure_stabilisation = 0;   // β of the density solve's pressure Laplacian (0 = off)

  // Gas, self-gravitating SPH with adaptive smoothing lengths (method "gas"; docs/self-gravity.md)
  GasSmoothing gas_smoothing = GasSmoothing::Adaptive;
  double gas_eta = 1.2;            // hᵢ = η (mᵢ/ρᵢ)^(1/d)  (Price 2012, eq. 10)
  double gas_global_b = 0.1;       // global h = b (⟨|x|²⟩ − |⟨x⟩|²)^½  (Gingold & Monaghan 1977)
  GasEos gas_eos = GasEos::Polytropic;
  double gas_k = 1.0;              // polytropic constant K in p = K ρ^γ (SI: Pa·(m³/kg)^γ)
  double gas_gamma = 2.0;          // γ of the polytrope or the adiabatic ideal gas
  double gas_damping = 0;          // 1/s, a = −damping·v (relaxation to equilibrium)
  double gas_spring = 0;           // 1/s², a = −spring·x (the toy star's linear force)
  bool self_gravity = false;
  double gravitational_constant = 6.674e-11;  // m³/(kg s²); code units: 1
  GravitySolver gravity_solver = GravitySolver::Direct;
  double gravity_theta = 0.5;      // Barnes–Hut opening angle (tree)

  Vec3d gravity{0, -9.81, 0};      // m/s²
  Vec3d body_force{0, 0, 0};       // m/s², a further uniform acceleration (a pressure gradient's stand-in)
  std::vector<FluidBlock> fluid_blocks;
  std::vector<ObstacleSpec> obstacles;
  std::vector<EmitterSpec> emitters;
  double end_time = 2.0;           // s
  bool viewer_realtime = false;    // the viewer runs its real-time profile (scene/realtime_profile.h)
};

/// Copies the parameters that are safe to change while a simulation runs, because the solver
/// reads them afresh every step. (Gravity also sets the automatic c0, once, when the solver is
/// built: changing it later changes the force, not c0.) The parameter table's `live` flags
/// (src/scene/params.cpp) name the same set; tests/scene_live_params_test.cpp holds them together.
inline void copy_live_parameters(const SimSpec& from, SimSpec& to) {
  to.viscosity = from.viscosity;
  to.surface_tension = from.surface_tension;
  to.adhesion = from.adhesion;
  to.artificial_viscosity = from.artificial_viscosity;
  to.clamp_negative_pressure = from.clamp_negative_pressure;
  to.shifting = from.shifting;
  to.time_step_mode = from.time_step_mode;
  to.cfl = from.cfl;
  to.dt = from.dt;
  to.max_dt = from.max_dt;
  to.gravity = from.gravity;
  to.body_force = from.body_force;
  to.pbf_time_step = from.pbf_time_step;
  to.pbf_substeps = from.pbf_substeps;
  to.pbf_iterations = from.pbf_iterations;
  to.pbf_max_density_error = from.pbf_max_density_error;
  to.pbf_max_iterations = from.pbf_max_iterations;
  to.pbf_cfl = from.pbf_cfl;
  to.pbf_relaxation = from.pbf_relaxation;
  to.pbf_omega = from.pbf_omega;
  to.pbf_scorr_k = from.pbf_scorr_k;
  to.pbf_scorr_n = from.pbf_scorr_n;
  to.pbf_scorr_dq = from.pbf_scorr_dq;
  to.pbf_xsph = from.pbf_xsph;
  to.pbf_vorticity = from.pbf_vorticity;
  to.dfsph_max_density_error = from.dfsph_max_density_error;
  to.dfsph_max_divergence_error = from.dfsph_max_divergence_error;
  to.dfsph_max_iterations = from.dfsph_max_iterations;
  to.dfsph_chebyshev = from.dfsph_chebyshev;
  to.dfsph_pressure_stabilisation = from.dfsph_pressure_stabilisation;
  to.gas_damping = from.gas_damping;
  to.gas_spring = from.gas_spring;
  to.self_gravity = from.self_gravity;
  to.gravity_theta = from.gravity_theta;
}

}  // namespace rtsph
