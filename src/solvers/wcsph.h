#pragma once
// Weakly compressible SPH (Becker & Teschner 2007; Monaghan 1994, 2005) on the CPU, templated
// on the dimension. State that outlives a step lives here; per-step scratch in StepContext.
#include <vector>

#include "core/grid.h"
#include "core/particles.h"
#include "solvers/geometry.h"
#include "solvers/simulation.h"

namespace rtsph {

/// Constants derived once from the spec (SI units).
struct ResolvedParams {
  double h = 0, support = 0;   // m: smoothing length and kernel support radius
  double mass = 0;             // kg per fluid particle
  double rho0 = 0, c0 = 0;     // kg/m³, m/s
  double tait_b = 0;           // Pa, B = ρ0 c0² / γ
  double stiffness = 0;        // m²/s², linear EOS p = k (ρ - ρ0)
  Vec3d domain_min{}, domain_max{};
};

/// Scratch rebuilt every step; nothing here needs saving in a checkpoint.
template <int D>
struct StepContext {
  UniformGrid<D> fluid_grid, boundary_grid;
  AlignedArray<Real> p_over_rho2;  // pᵢ/ρᵢ², symmetric pressure term
  AlignedArray<Real> inv_rho;      // 1/ρᵢ, Morris viscosity
  AlignedArray<Real> boundary_p_over_rho2;  // p_b/ρ0² extrapolated from the fluid (Adami 2012)
  AlignedArray<Real> tmp;          // permutation scratch (boundary)
  typename FluidParticles<D>::Spare spare;  // double buffers for the fluid reorder
  std::size_t bytes() const {
    return fluid_grid.bytes() + boundary_grid.bytes() + p_over_rho2.bytes() + inv_rho.bytes() +
           boundary_p_over_rho2.bytes() + tmp.bytes() + spare.bytes();
  }
};

/// Runtime state of a rigid obstacle.
struct ObstacleState {
  Pose pose;
  Vec3d velocity{}, angular_velocity{};  // m/s, rad/s
  bool user_driven = false;              // the viewer moved it: prescribed motion is off
  Vec3d user_target{};
};

struct EmitterState {
  double next_layer_s = 0;     // simulated time of the next emitted layer
  double emitted = 0;          // particles emitted so far
};

template <int D>
class Wcsph final : public Simulation {
 public:
  Wcsph(const SimSpec& spec, int threads);

  int dimension() const override { return D; }
  const SimSpec& spec() const override { return spec_; }
  void step() override;
  double time() const override { return time_; }
  std::uint64_t step_count() const override { return steps_; }
  SimStats stats() const override;
  const StageTimes& stage_times() const override { return times_; }
  void reset_stage_times() override { times_ = {}; }
  ParticleView fluid() const override;
  BoundaryView boundary() const override;
  void set_gravity(const Vec3d& g) override { spec_.gravity = g; }
  void set_brush(const Brush& b) override { brush_ = b; }
  void move_obstacle(int index, const Vec3d& center) override;
  Vec3d obstacle_center(int index) const override;
  Pose obstacle_transform(int index) const override;
  void set_live_parameters(const SimSpec& s) override;
  void prepare_state(std::size_t fluid_count) override;
  std::vector<StateField> state_fields() override;
  void state_loaded() override;

 private:
  // Stages of step(), in order.
  double choose_time_step() const;
  void kick(double dt);
  void drift(double dt);
  void move_obstacles(double t_new, double dt);
  void emit_particles(double t_new);
  void put_back_escaped();
  void sort_fluid_by_cell();
  void sort_boundary_by_cell();
  void compute_density();
  void compute_pressure();
  void extrapolate_boundary_pressure();
  void compute_accelerations();

  // Setup.
  void resolve_parameters();
  void build_boundary();
  void compute_boundary_psi();
  void add_fluid_particle(const Vec<D>& x, const Vec<D>& v);
  void update_forces();  // density → pressure → accelerations for the current positions

  SimSpec spec_;
  ThreadPool pool_;
  ResolvedParams prm_;
  FluidParticles<D> fluid_;
  BoundaryParticles<D> boundary_;
  std::vector<ObstacleState> obstacles_;
  std::vector<EmitterState> emitters_;
  StepContext<D> ctx_;
  Brush brush_;
  StageTimes times_;

  double time_ = 0, dt_ = 0;
  std::uint64_t steps_ = 0, put_back_ = 0;
  std::uint32_t next_id_ = 0;
  double density_error_ = 0, max_density_error_ = 0;
  bool boundary_moving_ = false;
};

}  // namespace rtsph
