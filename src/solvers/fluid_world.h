#pragma once
// The fluid world every SPH method shares (CPU, templated on the dimension): particles and their
// storage, boundary samples and their volumes (Akinci et al. 2012), obstacles and their motion,
// emitters, put-back, neighbour grids and sorting, the brush, gravity, the non-pressure forces,
// statistics, checkpoint fields and live parameters. A method (wcsph.h, pbf.h, dfsph.h) derives
// from FluidWorld, owns only its own per-particle fields and writes its step() from the stages
// here; it copies none of them.
#include <limits>
#include <string>
#include <vector>

#include "core/grid.h"
#include "core/neighbour_list.h"
#include "core/pair_loop.h"
#include "core/particles.h"
#include "solvers/geometry.h"
#include "solvers/simulation.h"

namespace rtsph {

/// Constants derived once from the spec (SI units).
struct ResolvedParams {
  double h = 0, support = 0;   // m: smoothing length and kernel support radius
  double eta2 = 0;             // m²: η² in the viscous terms' 1/(r² + η²), 0.01 s² (resolve_parameters)
  double mass = 0;             // kg per fluid particle
  double rho0 = 0, c0 = 0;     // kg/m³, m/s (c0: WCSPH's sound speed; also scales Monaghan's Π)
  double tait_b = 0;           // Pa, B = ρ0 c0² / γ
  double stiffness = 0;        // m²/s², linear EOS p = k (ρ - ρ0)
  Vec3d domain_min{}, domain_max{};
};

/// Scratch rebuilt every step; nothing here needs saving in a checkpoint.
template <int D>
struct StepContext {
  UniformGrid<D> fluid_grid, boundary_grid;
  NeighbourList<D> fluid_list;     // fluid neighbours of the last sort, for iterative methods
  AlignedArray<Real> p_over_rho2;  // pᵢ/ρᵢ² (or a method's equivalent), symmetric pressure term
  AlignedArray<Real> inv_rho;      // 1/ρᵢ, Morris viscosity
  AlignedArray<Real> boundary_p_over_rho2;  // p_b/ρ0² extrapolated from the fluid (Adami 2012)
  // Boundary samples: the unit normal into the fluid and the sample's depth behind the wall
  // plane (m), for the no-slip extrapolation of the viscous term (Morris et al. 1997). Container
  // walls: from positions, after every boundary sort. Obstacles: the nearest face of the body
  // (obstacle_surface_point), its normal rotated to the current pose after every sort and
  // every obstacle move.
  AlignedArray<Real> wall_normal[D];
  AlignedArray<Real> wall_depth;
  AlignedArray<Real> surface_normal[D];  // Akinci 2013's nᵢ (or the shift δrᵢ), only when on
  AlignedArray<Real> packed_x;     // positions as (x, y, z, ·) or (x, y) records for one pair sum
  AlignedArray<Real> tmp;          // permutation scratch (boundary and method fields)
  typename FluidParticles<D>::Spare spare;  // double buffers for the fluid reorder
  std::size_t bytes() const {
    return fluid_grid.bytes() + boundary_grid.bytes() + p_over_rho2.bytes() + inv_rho.bytes() +
           boundary_p_over_rho2.bytes() + tmp.bytes() + spare.bytes() + fluid_list.bytes() +
           packed_x.bytes() +
           wall_depth.bytes() * (D + 1) + surface_normal[0].bytes() * D;
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

/// Which terms the shared acceleration sum adds (see accelerations()).
struct ForceTerms {
  const Real* pressure = nullptr;           // Pᵢ per fluid particle (p/ρ², or κ/ρ): symmetric
  const Real* boundary_pressure = nullptr;  //   pressure term; P_b per boundary sample, or
  bool mirror_boundary = false;             //   P_b = Pᵢ (true), or 0 (null, false)
  bool viscosity = true;   // Morris laminar + Monaghan artificial viscosity, fluid and walls
  bool external = true;    // gravity and the brush
  // With `external`: the hydrostatic part of the walls' pressure for methods whose solve mirrors
  // Pᵢ (DFSPH's κ, PBF's λ) onto the wall samples. Mirroring gives a wall sample the particle's own
  // pressure at every height, so a particle beside a vertical wall gets no support from it: the
  // truncated fluid sum alone under-supports it, and the water sinks along the walls and rises
  // in the middle, a circulation that never settles. Adami et al. 2012's p_b = pᵢ + ρᵢ g·(x_b − xᵢ)
  // restores it; its gᵢ·(x_b − xᵢ) part is fixed for the step and is added here.
  bool wall_hydrostatic = false;
  // With `external`: surface tension and adhesion (add_surface_forces) when they are on. PBF
  // asks for them apart, at its predicted positions (Pbf::surface_forces_at_prediction).
  bool surface = true;
};

/// What a pair loop over fluid and boundary neighbours reads, gathered once per sum. (Named
/// references to its members, not a structured binding: clang 14, the fuzz build, cannot
/// capture structured bindings in lambdas.)
template <int D>
struct PairArrays {
  const Real* fx[D];     // fluid positions, velocities (cell order)
  const Real* fv[D];
  const Real* bx[D];     // boundary positions, velocities
  const Real* bv[D];
  const Real* psi;       // boundary Ψ
  const Real* wall_normal[D];  // container-wall samples' normal into the fluid, and depth
  const Real* wall_depth;
  const uint32_t* cells; // fluid particle i's cell in either grid
};

template <int D>
class FluidWorld : public Simulation {
 public:
  int dimension() const override { return D; }
  const SimSpec& spec() const override { return spec_; }
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
  void overwrite_fluid(const float* const* x, const float* const* v) override;

 protected:
  /// Samples the fluid, walls and obstacles; the method then computes its initial fields.
  FluidWorld(const SimSpec& spec, int threads);

  /// A per-particle array a method owns. It is resized with the fluid, permuted when the fluid
  /// is sorted (when `sorted`), and saved in checkpoints (when `saved`).
  struct MethodField {
    std::string name;
    AlignedArray<Real>* array;
    bool sorted = true, saved = true;
  };
  void add_method_field(const MethodField& f) {
    f.array->resize(fluid_.size());
    method_fields_.push_back(f);
  }
  /// Method scalars that a checkpoint must carry (iteration counts, warm-start state).
  virtual void add_method_scalars(std::vector<StateField>&) {}
  /// Kinetic and potential energy and the maximum speed for stats() (the GPU backend reduces
  /// them where its particles live).
  virtual void measure_energies(SimStats& s) const;
  /// Method figures for the statistics (iterations, residual errors).
  virtual void add_method_stats(SimStats&) const {}
  /// Whether edited positions (overwrite_fluid) must be sorted into cells before the next step:
  /// true when the step's first pair sums use the previous step's grid (DFSPH). A method whose
  /// step sorts before its first pair sum answers false, and an edit then leaves the memory
  /// order, and so the bits of the run, exactly as they were.
  virtual bool sort_after_edit() const { return true; }
  /// Whether a stage reads the neighbours' ρⱼ between the sort and the next density sum, so the
  /// sort must carry ρ along (particle shifting; PBF's surface forces at x*).
  virtual bool density_read_after_sort() const { return spec_.shifting > 0; }

  // Shared stages, in the order a step usually calls them.
  struct Extremes { double v2 = 0, a2 = 0; };
  Extremes max_speed_and_acceleration() const;  // max |v|², |a|² over the fluid
  void kick(double dt);                  // v += a dt
  /// x += v dt, against impermeable container walls: a particle whose path would cross a wall
  /// plane stops on it and loses the velocity component into the wall (inelastic contact; the
  /// tangential velocity is kept). The samples (Akinci 2012) push only through pressure, and a
  /// particle with a deficient neighbourhood (spray, the tip of a sheet, a jet along a wall)
  /// has ρ < ρ0, so no pressure, until it is past the wall plane: a lone particle reaches ρ0
  /// only 0.4 spacing from a flat single-layer wall, 0.1 spacing beyond the plane. The contact
  /// is the wall's kinematic condition (v·n ≥ 0) for those; a particle the fluid pressure holds
  /// off never reaches the plane and never feels it.
  void drift(double dt);
  /// The container's wall planes, domain_min and domain_max: half a spacing outside the first
  /// fluid lattice layer and half a spacing inside the first wall sample layer, the faces of the
  /// volumes the samples stand for (geometry.h, sample_walls).
  struct WallPlanes { Real lo[D], hi[D]; };
  /// A periodic axis has no walls: its planes are at ±∞ and drift wraps instead.
  WallPlanes wall_planes() const {
    WallPlanes w;
    const Real inf = std::numeric_limits<Real>::infinity();
    for (int k = 0; k < D; ++k) {
      const bool wrap = ctx_.fluid_grid.periodic(k) || spec_.open;  // open space: no walls
      w.lo[k] = wrap ? -inf : Real(prm_.domain_min[k]);
      w.hi[k] = wrap ? inf : Real(prm_.domain_max[k]);
    }
    return w;
  }
  /// Gravity plus the scene's body force: the uniform acceleration every particle feels.
  Vec3d external_acceleration() const { return spec_.gravity + spec_.body_force; }
  void move_obstacles(double t_new, double dt);  // prescribed or user-driven rigid motion
  /// move_obstacles' first half: the obstacles' poses and velocities at t_new. True when their
  /// samples must be moved (then call stop_user_driven_obstacles() after moving them).
  bool update_obstacle_states(double t_new, double dt);
  void stop_user_driven_obstacles();
  void emit_particles(double t_new);     // nozzle layers due by t_new
  void put_back_escaped();               // the safety net (a diagnostic): nothing is ever lost
  void advance_scene(double t_new, double dt) {  // the three above, timed as integration
    move_obstacles(t_new, dt);
    emit_particles(t_new);
    put_back_escaped();
  }
  void update_neighbours();              // sort fluid (and moving boundary) by cell
  /// Re-covers the fluid grid with the fluid's bounding box and cells of edge `cell` (coarsened
  /// so the grid never has more than ~4 cells per particle), for methods whose support changes
  /// (adaptive h) or whose fluid moves in open space; call before update_neighbours(). Memory
  /// stays bounded however far the cloud drifts. Returns the cell edge used.
  Real follow_fluid(Real cell);
  /// Methods that sum over the same neighbourhood many times per step ask for neighbour lists:
  /// update_neighbours() then also lists each particle's fluid neighbours, and every shared
  /// and method pair sum walks the list instead of the grid until the next update.
  /// Called from a method's constructor; lists the sampled fluid at once.
  void keep_neighbour_lists() { keep_lists_ = true; build_neighbour_lists(); }
  /// The fluid pair walk every sum uses: particle i's list when one is current, else its
  /// grid cells. fn(j, d, r2, mask) reads neighbour fields with simd::at(array, j).
  /// With packed from pack_positions() (lists current), the list walk reads the positions as
  /// records, eight loads per batch instead of one gather per axis.
  template <bool kPeriodic, class Fn>
  [[gnu::always_inline]] void for_each_fluid_batch(std::size_t i, const Real* const xs[D],
                                                   const Real xi[D], Real support2, Fn&& fn,
                                                   const Real* packed = nullptr) const {
    if (packed) return for_each_listed_batch_packed<D>(ctx_.fluid_list, i, packed, xi, support2, fn);
    if (lists_current())
      for_each_listed_batch<D>(ctx_.fluid_list, i, xs, xi, support2, fn);
    else
      for_each_candidate_batch<D, kPeriodic>(ctx_.fluid_grid, ctx_.fluid_grid.sorted_cells()[i], xs, xi,
                                             support2, fn);
  }
  /// With current lists, copies the positions into ctx_.packed_x as records (16 bytes in 3D, 8 in
  /// 2D) for the pair sum about to run (for_each_fluid_batch's packed argument); else nullptr.
  const Real* pack_positions();
  void compute_density();                // ρᵢ = Σⱼ mⱼ Wᵢⱼ + Σ_b Ψ_b W_ib (Akinci 2012, eq. 6)
  void measure_density_error();          // max and mean compression (ρ-ρ0)/ρ0 ≥ 0
  void compute_inverse_density();        // ctx_.inv_rho for the viscosity terms
  void extrapolate_boundary_pressure();  // p_b from fluid_.p (Adami et al. 2012, eq. 27)
  /// aᵢ (fluid_.a) = pressure + viscosity + gravity + brush, as `terms` selects; one pair loop.
  /// With `external` it also adds the surface forces (add_surface_forces) when they are on.
  void accelerations(const ForceTerms& terms);
  /// Surface tension and adhesion (Akinci, Akinci & Teschner 2013), added to fluid_.a: the
  /// surface normals in one pass, then cohesion, curvature and adhesion in a second. A
  /// non-pressure force every method gets through accelerations(); nothing when
  /// fluid.surface_tension and fluid.adhesion are 0 (surface_tension.cpp).
  bool surface_forces_active() const { return spec_.surface_tension > 0 || spec_.adhesion > 0; }
  void add_surface_forces();
  /// Particle shifting (Lind et al. 2012; D = A h |v| Δt, Skillen et al. 2013), A =
  /// solver.shifting: moves each particle down its concentration gradient. Call right after
  /// update_neighbours(), before the density. Nothing when A = 0 (shifting.cpp).
  void shift_particles(double dt);
  /// 1/W(Δp), Δp the initial spacing: the scale of the shift's anti-clumping weight.
  Real shifting_inv_w_dp() const;
  /// The largest shift in one step (m).
  Real shifting_max_shift() const;
  /// With fluid.hydrostatic_start (a weakly compressible method's constructor calls it, before
  /// its first neighbour update): moves each particle of a fluid block along gravity so the
  /// block's lattice is compressed to the density ρ(d) its equation of state gives the
  /// hydrostatic pressure ρ0 g d, d the depth below the block's top.
  void compress_hydrostatically();
  /// Transport-velocity formulation (Adami, Hu & Adams 2013): moves each particle by
  /// Δt_drift·Δt_kick·a_b, the acceleration of a uniform background pressure p_b =
  /// solver.transport_velocity·ρ0c0², which keeps the arrangement uniform. Call just before
  /// drift, with the positions and densities the step's forces came from. Nothing when the
  /// parameter is 0 (transport_velocity.cpp). Methods whose step is not bounded by c0 pass
  /// max_signal_speed: p_b is then capped at ρ0·max_signal_speed².
  void transport_velocity_shift(double dt_kick, double dt_drift,
                                double max_signal_speed = std::numeric_limits<double>::infinity());
  /// The momentum correction of the same formulation (Adami et al. 2013, eq. 8's second term):
  /// aᵢ += Σⱼ m (1/ρᵢ² + 1/ρⱼ²) ½(Aᵢ + Aⱼ)·∇Wᵢⱼ with A = ρ v ⊗ (ṽ − v), which transports the
  /// momentum with the particles' transport velocity. Call after accelerations(). Nothing when
  /// solver.transport_velocity is 0.
  void add_transport_velocity_stress();
  /// Adds shift[k][i] to the positions: periodic axes wrap, wall planes clamp. The sort stays
  /// valid for displacements far below a cell.
  void displace_fluid(const Real* const shift[D]);
  PairArrays<D> pair_arrays() const {
    PairArrays<D> a;
    for (int k = 0; k < D; ++k) {
      a.fx[k] = fluid_.x[k].data();
      a.fv[k] = fluid_.v[k].data();
      a.bx[k] = boundary_.x[k].data();
      a.bv[k] = boundary_.v[k].data();
    }
    a.psi = boundary_.psi.data();
    for (int k = 0; k < D; ++k) a.wall_normal[k] = ctx_.wall_normal[k].data();
    a.wall_depth = ctx_.wall_depth.data();
    a.cells = ctx_.fluid_grid.sorted_cells();
    return a;
  }
  /// Σⱼ |m∇Wᵢⱼ|² for a particle inside the rest lattice (kg²/m^(2d+2)): the scale of the
  /// implicit methods' diagonals (PBF's Σ|∇C|², DFSPH's 1/α), for relative tolerances.
  double lattice_gradient_sum() const;
  /// Viscous time-step limit 0.125 h²/ν, with Monaghan's α counted as ν = α c0 h / (2(D+2)).
  double viscous_dt_limit() const;

  SimSpec spec_;
  ThreadPool pool_;
  ResolvedParams prm_;
  FluidParticles<D> fluid_;
  BoundaryParticles<D> boundary_;
  std::vector<ObstacleState> obstacles_;
  std::vector<unsigned> obstacle_skip_axes_;  // per obstacle: obstacle_seamless_axes (from the spec)
  std::vector<EmitterState> emitters_;
  StepContext<D> ctx_;
  Brush brush_;
  StageTimes times_;

  double time_ = 0, dt_ = 0;
  std::uint64_t steps_ = 0, put_back_ = 0;
  std::uint32_t next_id_ = 0;
  double density_error_ = 0, max_density_error_ = 0, mean_density_error_ = 0;
  bool boundary_moving_ = false;
  // ṽ − v of the last transport_velocity_shift (m/s); a method field when the parameter is on.
  // (The GPU backend keeps it in a buffer and copies it here for checkpoints.)
  AlignedArray<Real> transport_dv_[D];

 private:
  void resolve_parameters();
  void build_boundary();
  void compute_boundary_psi();
  void sort_fluid_by_cell();
  void sort_boundary_by_cell();
  void compute_wall_geometry();  // ctx_.wall_normal/wall_depth for the boundary's current order
  /// ctx_.wall_normal/wall_depth of obstacle sample b (owner >= 0) at its owner's current pose.
  void obstacle_wall_geometry(std::size_t b) {
    const int o = boundary_.owner[b];
    Vec3d local{};
    for (int k = 0; k < D; ++k) local[k] = boundary_.local[k][b];
    const SurfacePoint sp = obstacle_surface_point(spec_.obstacles[std::size_t(o)], local, D,
                                                   obstacle_skip_axes_[std::size_t(o)]);
    const Vec3d n = obstacles_[std::size_t(o)].pose.rotate(sp.normal);
    for (int k = 0; k < D; ++k) ctx_.wall_normal[k][b] = Real(n[k]);
    ctx_.wall_depth[b] = Real(sp.depth);
  }
  void add_fluid_particle(const Vec<D>& x, const Vec<D>& v);
  template <bool kPressure, bool kViscosity, bool kExternal>
  void accelerations_impl(const ForceTerms& terms);

  /// Fluid pair sums visit each pair once when no neighbour lists are kept and no axis is
  /// periodic (WCSPH's grid walks): half the kernel evaluations (UniformGrid::for_each_forward_range).
  bool half_stencil() const { return !lists_current() && !ctx_.fluid_grid.any_periodic(); }
  /// Runs fn(begin, end) on the sorted fluid particles of each layer of grid cells across the
  /// slowest axis, one layer at a time in order within a call: the even layers in parallel, then
  /// the odd ones. A particle's forward stencil writes to its own layer and the next only, so no
  /// two layers of a phase touch the same particle, and what each particle receives arrives in an
  /// order that no thread count changes (results stay bitwise identical for 1 and N threads).
  template <class Fn>
  void for_each_layer_in_two_phases(Fn&& fn) const {
    const UniformGrid<D>& g = ctx_.fluid_grid;
    const int layers = g.layer_count();
    for (int phase = 0; phase < 2; ++phase) {
      const std::size_t count = std::size_t((layers - phase + 1) / 2);
      pool_.parallel_for(count, [&](std::size_t b, std::size_t e) {
        for (std::size_t l = b; l < e; ++l) {
          const int layer = int(2 * l) + phase;
          fn(std::size_t(g.layer_start(layer)), std::size_t(g.layer_start(layer + 1)));
        }
      }, 1);
    }
  }
  /// Zeroes arrays[0..count) over [0, n) (the half-stencil sums' starting value).
  void clear(Real* const* arrays, std::size_t n, int count = D);
  /// Runs particle(i, tag) for every fluid particle of a pair sum: with `half` (never on a
  /// periodic grid) layer by layer in two phases with tag std::true_type (the forward walk),
  /// else in parallel with std::false_type (the full walk).
  template <bool kPeriodic, class Particle>
  void for_each_pair_sum_particle(bool half, std::size_t n, Particle&& particle) const {
    if constexpr (!kPeriodic) {
      if (half) {
        for_each_layer_in_two_phases([&](std::size_t b, std::size_t e) {
          for (std::size_t i = b; i < e; ++i) particle(i, std::true_type{});
        });
        return;
      }
    }
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) particle(i, std::false_type{});
    }, ThreadPool::kPairs);
  }
  /// One particle's sum of an antisymmetric pair term (Newton's third law: j feels −c when i
  /// feels c). pair(j, d, r2, mask, c) writes i's term c for a batch. The forward walk (tag
  /// std::true_type, from for_each_pair_sum_particle) visits each pair once and adds −c to j in
  /// out; the full walk visits every neighbour, each particle summing its own. Adds Σc to acc.
  template <bool kPeriodic, class Tag, class Pair>
  [[gnu::always_inline]] void sum_antisymmetric_pairs(std::size_t i, Tag, const Real* const xs[D],
                                                      const Real xi[D], Real support2,
                                                      const Real* packed, Real* const out[D],
                                                      simd::f8* acc, Pair&& pair) const {
    if constexpr (Tag::value) {
      for_each_forward_batch<D>(ctx_.fluid_grid, ctx_.fluid_grid.sorted_cells()[i], uint32_t(i), xs, xi,
                                support2, [&](uint32_t j, const simd::f8* d, simd::f8 r2, simd::i8 m, int valid) {
                                  simd::f8 c[D];
                                  pair(j, d, r2, m, c);
                                  for (int k = 0; k < D; ++k) {
                                    acc[k] += c[k];
                                    add_forward(out[k], j, -c[k], valid);
                                  }
                                });
    } else {
      for_each_fluid_batch<kPeriodic>(i, xs, xi, support2, [&](auto j, const simd::f8* d, simd::f8 r2, simd::i8 m) {
        simd::f8 c[D];
        pair(j, d, r2, m, c);
        for (int k = 0; k < D; ++k) acc[k] += c[k];
      }, packed);
    }
  }
  bool lists_current() const {
    return ctx_.fluid_list.valid() && ctx_.fluid_list.size() == fluid_.size();
  }
  void build_neighbour_lists();

  std::vector<MethodField> method_fields_;
  bool keep_lists_ = false;
};

}  // namespace rtsph
