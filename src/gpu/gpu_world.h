#pragma once
// The GPU backend's shared fluid world (OpenGL 4.3 compute): the CPU FluidWorld samples the
// scene, owns the scalars (time, obstacles, emitters, counters) and serves checkpoints, while
// the particles live and are stepped in GPU buffers. A GPU method (gpu_wcsph.h) derives from
// this and writes its step() from the stages here, as CPU methods do from FluidWorld's.
//
// The host copies of the particle arrays are refreshed only when something reads them
// (fluid(), boundary(), state_fields()); a step reads back a few bytes at most: the maximum
// speed and acceleration for an adaptive time step. Every call needs the OpenGL context that
// was current when the simulation was made to be current on the calling thread.
#include <array>
#include <cmath>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "gpu/gl_compute.h"
#include "gpu/layout.h"
#include "gpu/sort.h"
#include "solvers/fluid_world.h"

namespace rtsph::gpu {

/// Adds a stage's wall time to `sink`: with `sync`, the GPU's time to run it (glFinish at both
/// ends), else the host's time to queue it.
class GpuStageTimer {
 public:
  GpuStageTimer(bool sync, double& sink) : sync_(sync), sink_(sink) {
    if (sync_) glFinish();
    t0_ = std::chrono::steady_clock::now();
  }
  ~GpuStageTimer() {
    if (sync_) glFinish();
    sink_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  GpuStageTimer(const GpuStageTimer&) = delete;
  GpuStageTimer& operator=(const GpuStageTimer&) = delete;

 private:
  bool sync_;
  double& sink_;
  std::chrono::steady_clock::time_point t0_;
};

/// The largest sum whose mean over `count`, sum / count in double, is still within `tolerance`:
/// a device-side stopping test that checks sum > threshold decides exactly as the host's
/// mean > tolerance did (the rounded quotient grows with the sum), with no division there.
double sum_threshold(double tolerance, std::size_t count);

template <int D>
class GpuWorld : public FluidWorld<D> {
 public:
  ~GpuWorld() override;
  void wait_idle() const override { glFinish(); }
  void set_stage_sync(bool on) override { stage_sync_ = on; }
  ParticleView fluid() const override;
  BoundaryView boundary() const override;
  SimStats stats() const override;
  /// From the density pass's reduction (positions and velocities as they were before the step's
  /// last half kick; a NaN born in that kick is seen one step later).
  std::optional<HealthFacts> health_facts() const override;
  std::optional<DeviceParticles> device_particles() const override;
  void prepare_state(std::size_t fluid_count) override;
  std::vector<StateField> state_fields() override;
  void state_loaded() override;
  void overwrite_fluid(const float* const* x, const float* const* v) override;
  /// The renderer's zero-copy path: fluid positions (vec4, cell order) and their count.
  GLuint position_buffer() const { return pos_.id(); }
  GLuint velocity_buffer() const { return vel_.id(); }
  GLuint density_buffer() const { return dens_.id(); }

 protected:
  /// Copies fluid particles [first, first + count) of the CPU arrays into the GPU buffers.
  void upload_fluid(std::size_t first, std::size_t count);
  GpuWorld(const SimSpec& spec, int threads);

  /// Times a stage into `sink` (set_stage_sync()).
  GpuStageTimer stage_timer(double& sink) const { return GpuStageTimer(stage_sync_, sink); }

  // Stages, in the order a step calls them.
  struct Extremes { double v2 = 0, a2 = 0; };
  Extremes gpu_max_speed_and_acceleration();  // reads back 32 bytes
  /// The step's constants (SphParams) to the GPU; kick_dt is kick_drift's kick (WCSPH dt/2, PBF dt).
  void write_params(double dt, double kick_dt);
  void kick_drift();                          // v += a kick_dt; x += v dt; walls; put-back
  void advance_scene_gpu(double t_new, double dt);  // obstacles and emitters
  /// Fluid (and moving boundary) into cells. carry_density: ρ travels with the particles too
  /// (PBF's surface forces read ρⱼ after its sort; shifting always carries it).
  void sort_particles(bool carry_density = false);
  void density_and_pressure();                // ρ, p, p/ρ², 1/ρ (density.comp)
  void density_only();                        // ρ alone (FluidWorld::compute_density)
  void measure_density_error_gpu();           // max and mean compression, on the GPU
  /// The summed compression of the densities now in the buffer into stats slot
  /// RTSPH_STAT_SOLVE (its .y), on the device: PBF's stopping test reads it there. Its own slot,
  /// so the step's reported figures stay the final ones.
  void reduce_compression() const;
  /// |g| times the fluid's extent along gravity (DFSPH's head speed squared), read back.
  double gpu_head();
  /// The sum of the solve buffer's error column (RTSPH_B_DFSPH_SOLVE, bound by the caller) into
  /// stats slot RTSPH_STAT_RESIDUAL, on the device: DFSPH's stopping test reads it there.
  void reduce_solve_error() const;
  /// Runs a method's stopping-test gate (pbf_gate.comp, dfsph_gate.comp: the same uniforms) on
  /// one thread: `mode`, the iteration bounds and the threshold its sum is tested against.
  void run_gate(const ComputeProgram& gate, int mode, int least, int most, double threshold) const;
  /// One slot of the stats buffer, read back (32 bytes).
  glsl::dvec4 read_stat(unsigned slot) const;
  /// The mean density over the fluid, read back.
  double gpu_mean_density();
  void boundary_pressure();                   // Adami 2012's wall pressure
  void forces();                              // the acceleration sum (forces.comp)
  /// Adds surface tension and adhesion to the accelerations when the scene has them (Akinci
  /// 2013; FluidWorld::add_surface_forces), after the method's force pass.
  void surface_forces();
  /// Particle shifting when solver.shifting > 0 (FluidWorld::shift_particles): right after the
  /// sort, with the last step's Δt, as the CPU's WCSPH.
  void shift_particles_gpu(double dt);
  /// The transport-velocity formulation when solver.transport_velocity > 0 (Adami et al. 2013,
  /// FluidWorld::transport_velocity_shift): ṽ − v from the positions and densities of the last
  /// force stage, before kick_drift(), which then moves each particle by Δt_drift(ṽ − v) first.
  /// max_signal_speed caps the speed in p_b = solver.transport_velocity ρ0 c² (DFSPH's, as on the CPU).
  void transport_velocity_gpu(double dt_kick, double max_signal_speed = HUGE_VAL);
  /// Its momentum correction (FluidWorld::add_transport_velocity_stress), after the force stage.
  void transport_stress_gpu();
  void kick(double dt);                       // v += a dt
  /// After a step: the host copies are stale until the next read.
  void mark_stale() { host_fresh_ = scalars_fresh_ = boundary_fresh_ = false; }
  /// A per-particle vec4 array a GPU method keeps across steps. Its columns mirror up to four of
  /// the method's host fields (FluidWorld::add_method_field; nullptr for none), so checkpoints
  /// and read-backs see them: it is downloaded with the particle arrays and uploaded with them
  /// (emitted particles get the host's zeros, a loaded state its values), and every sort gathers
  /// it along when `sorted`.
  struct DeviceField {
    Buffer* buffer = nullptr;
    Buffer* alt = nullptr;  // the sort's gather target (sorted fields)
    std::array<AlignedArray<Real>*, 4> host{};
    bool sorted = false;
  };
  /// Registers a device field; reserves its buffers and uploads the host's current values.
  void add_device_field(const DeviceField& f);
  /// Binds every shared buffer to its layout.h binding (before a method's own passes too).
  void bind_all() const;
  const std::vector<std::string>& defines() const { return defines_; }
  /// The fluid buffer capacity (particles); a method sizes its own arrays to it.
  std::size_t capacity() const { return capacity_; }

  // Particle buffers (layout.h's bindings); *_alt are the sort's gather targets.
  Buffer pos_, vel_, acc_, dens_, id_, pos_alt_, vel_alt_, id_alt_;
  Buffer dens_alt_;  // the sort carries ρ along only for shifting (its ρⱼ) and PBF's surface forces
  Buffer put_back_counter_;

 private:
  void compile_programs();
  void reserve_device_fields();
  void upload_device_fields(std::size_t first, std::size_t count);
  void download_device_fields() const;
  void upload_boundary();
  void upload_obstacles();
  void sort_boundary();
  /// Reads the particle arrays back into the FluidWorld host copies (logically const: the
  /// simulation's state does not change, only where a copy of it lives).
  void sync_host() const;
  void sync_boundary_host() const;
  void sync_scalars() const;
  void measure_energies(SimStats& s) const override;

  std::vector<std::string> defines_;
  std::vector<DeviceField> device_fields_;
  std::unique_ptr<CellSorter> sorter_;
  ComputeProgram density_, density_only_, boundary_pressure_, forces_, kick_, kick_drift_, move_boundary_;
  ComputeProgram surface_normal_, surface_forces_;
  Buffer normal_;  // surface normals, one vec4 per fluid particle
  ComputeProgram shift_, shift_apply_;
  ComputeProgram transport_, transport_stress_, kick_drift_transport_;
  Buffer tdv_, tdv_alt_;  // ṽ − v per fluid particle, in the particles' order (sorted with them)
  bool transport() const {
    return this->spec_.transport_velocity > 0 && (this->spec_.method == "wcsph" || this->spec_.method == "dfsph");
  }
  Buffer shift_delta_;  // shifting's δx, one vec4 per fluid particle
  static constexpr int kReduceModes = 8;  // reduce.comp's MODEs
  ComputeProgram reduce_[kReduceModes], reduce_final_[kReduceModes];
  /// Runs reduction `mode` of reduce.comp into stats slot `slot` (two passes, fixed order).
  void reduce(int mode, unsigned slot) const;
  double reduce_first(int mode, unsigned slot, double divide);
  GLuint params_ubo_ = 0;
  Buffer bpos_, bvel_, bnormal_, blocal_, bpress_, bpos_alt_, bvel_alt_, bnormal_alt_, blocal_alt_;
  Buffer obstacles_buf_, partials_, stats_;
  SortedCells fluid_cells_, boundary_cells_;
  double params_dt_ = 0, params_kick_dt_ = 0;  // what write_params() last wrote
  std::size_t capacity_ = 0;        // fluid particles the buffers hold (emitters included)
  std::uint64_t put_back_base_ = 0; // put-backs before the GPU counter was last zeroed
  bool boundary_sorted_ = false;
  bool stage_sync_ = false;         // set_stage_sync()
  bool loading_ = false;            // prepare_state() .. state_loaded(): host copies are the truth
  mutable bool host_fresh_ = true, scalars_fresh_ = true, boundary_fresh_ = true;
};

}  // namespace rtsph::gpu
