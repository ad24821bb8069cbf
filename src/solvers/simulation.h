#pragma once
// The dimension-erased face of a running simulation: what apps, exporters and renderers use.
// Two Simulation objects share nothing, so they can run side by side (tests do).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/particles.h"
#include "solvers/geometry.h"
#include "solvers/spec.h"

namespace rtsph {

/// Wall-clock time per stage, accumulated since construction or reset_timings().
struct StageTimes {
  double neighbours_s = 0, density_s = 0, forces_s = 0, integrate_s = 0;
  double total() const { return neighbours_s + density_s + forces_s + integrate_s; }
};

struct SimStats {
  std::string method;                   // solver method name ("wcsph", "pbf", "dfsph")
  std::size_t fluid_particles = 0, boundary_particles = 0;
  std::uint64_t steps = 0;
  double time_s = 0, dt_s = 0;
  double c0 = 0;                        // m/s, speed of sound in use
  double h = 0;                         // m, smoothing length
  double density_error = 0;             // max (ρ-ρ0)/ρ0 over fluid, last step
  double max_density_error = 0;         // the same, maximum over the run
  double mean_density_error = 0;        // mean of max(0, (ρ-ρ0)/ρ0) over fluid, last step
  // Iterative methods: iterations of the last step and their mean over the run. "pressure" is
  // PBF's constraint solve or DFSPH's constant-density solve; "divergence" DFSPH's other solve.
  int pressure_iterations = 0, divergence_iterations = 0;
  double mean_pressure_iterations = 0, mean_divergence_iterations = 0;
  // DFSPH: steps in which a solve stopped at solver.dfsph.max_iterations above its tolerance
  // (the step goes on with the error it has; solver_failure() names the last one).
  std::uint64_t capped_steps = 0;
  std::uint64_t particles_put_back = 0; // escaped the domain and were put back inside
  double kinetic_energy_j = 0, potential_energy_j = 0;
  // The gas method's parts of potential_energy_j (which also holds the external potential):
  // thermal Σ m u and gravitational ½ Σ m Φ.
  double thermal_energy_j = 0, gravitational_energy_j = 0;
  double max_speed = 0;                 // m/s
  std::size_t bytes = 0;                // particle, grid and scratch storage
};

/// What the instability guard needs to know that all is well, for backends that can find it
/// without handing over every particle (the GPU reduces it where the particles live).
struct HealthFacts {
  bool non_finite = false;      // a NaN or Inf in a fluid position, velocity, density or pressure
  double max_density = 0;       // kg/m³, the largest fluid density
};

/// A radial push (strength > 0) or pull (< 0) applied by the viewer's mouse brush.
struct Brush {
  bool active = false;
  Vec3d center{};
  double radius = 0.2;      // m
  double strength = 50.0;   // m/s² at the centre, falling linearly to 0 at the radius
};

/// One named block of raw state, for checkpoints. Sizes are fixed once prepare_state() ran.
struct StateField {
  std::string name;
  void* data;
  std::size_t bytes;
};

class Simulation {
 public:
  virtual ~Simulation() = default;
  virtual int dimension() const = 0;
  virtual const SimSpec& spec() const = 0;

  /// Advances one time step (adaptive or fixed, per the spec).
  virtual void step() = 0;
  /// Blocks until the work step() queued has finished (a GPU backend returns from step() early);
  /// timings around steps call this before reading the clock.
  virtual void wait_idle() const {}
  virtual double time() const = 0;
  virtual std::uint64_t step_count() const = 0;
  virtual SimStats stats() const = 0;
  virtual const StageTimes& stage_times() const = 0;
  virtual void reset_stage_times() = 0;
  /// A backend that queues its work (the GPU) times each stage as the host's time to queue it,
  /// which says nothing about the stage's cost. On, it waits for the device at each stage's
  /// start and end, so stage_times() holds each stage's own run time, and steps run slower
  /// (rtsph bench's stage columns). The CPU's stages are timed exactly either way.
  virtual void set_stage_sync(bool) {}

  /// Views stay valid until the next step() (arrays are reordered every step).
  virtual ParticleView fluid() const = 0;
  virtual BoundaryView boundary() const = 0;

  // Interaction (viewer). Changes take effect at the next step.
  virtual void set_gravity(const Vec3d& g) = 0;
  virtual void set_brush(const Brush& b) = 0;
  /// Moves obstacle `index` kinematically towards `center` during the next step; the implied
  /// velocity (Δx/dt) acts on the fluid.
  virtual void move_obstacle(int index, const Vec3d& center) = 0;
  virtual Vec3d obstacle_center(int index) const = 0;
  /// Current rigid pose of obstacle `index` (centre and rotation; body → world), for drawing it
  /// from its geometry. The default knows only the centre.
  virtual Pose obstacle_transform(int index) const {
    Pose p;
    p.center = obstacle_center(index);
    return p;
  }
  /// Non-empty when the method's own solver gave up in the last step, e.g. "DFSPH density
  /// solve did not converge in 100 iterations at t = 0.1 s (...)". Not fatal by itself (a
  /// sudden load can need more sweeps than allowed); the instability guard names it as the
  /// cause when the state then fails its checks.
  virtual std::string solver_failure() const { return {}; }
  /// The GPU backend's buffers for drawing without a copy (valid until the next step); nullopt on
  /// the CPU. Needs the simulation's OpenGL context current.
  virtual std::optional<DeviceParticles> device_particles() const { return std::nullopt; }
  /// The guard's fast path: nullopt when the backend has nothing cheaper than fluid().
  virtual std::optional<HealthFacts> health_facts() const { return std::nullopt; }
  /// Applies parameters that are safe to change while running (viscosity, α, CFL, gravity…).
  virtual void set_live_parameters(const SimSpec& s) = 0;

  // Checkpoints: prepare_state(n) sizes the state for n fluid particles (use the count from the
  // file when loading); state_fields() then lists every block of memory the step depends on.
  virtual void prepare_state(std::size_t fluid_count) = 0;
  virtual std::vector<StateField> state_fields() = 0;
  /// Call after filling the fields from a checkpoint: rebuilds derived data (grids).
  virtual void state_loaded() = 0;

  /// Replaces the fluid's positions and/or velocities (scripting: the Python API). Arrays are in
  /// fluid()'s memory order, one per axis; nullptr leaves that quantity as it is. New positions
  /// are sorted into cells (each particle keeps its id, velocity and acceleration) and derived
  /// data rebuilt as after a checkpoint load, so the next step() starts from them.
  virtual void overwrite_fluid(const float* const* x, const float* const* v) = 0;
};

/// Creates the solver named by spec.method ("wcsph", "pbf", "dfsph"). threads = 0 uses all hardware threads.
/// Throws std::invalid_argument for an unknown method and std::length_error for a scene that
/// would not fit in memory.
std::unique_ptr<Simulation> make_simulation(const SimSpec& spec, int threads);

/// Bytes the simulation would allocate for this spec (particles, boundary, grids, scratch),
/// estimated from the geometry without allocating. Scene validation refuses specs that exceed
/// the machine's memory using this.
std::size_t estimate_memory_bytes(const SimSpec& spec);

/// The registered solver method names, for validation and help text.
std::vector<std::string> solver_methods();

}  // namespace rtsph
