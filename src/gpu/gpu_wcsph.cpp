#include "gpu/gpu_wcsph.h"

#include "core/timer.h"
#include "solvers/wcsph.h"

namespace rtsph::gpu {

template <int D>
GpuWcsph<D>::GpuWcsph(const SimSpec& spec, int threads) : GpuWorld<D>(spec, threads) {
  // Optional (fluid.hydrostatic_start), on the CPU arrays as the CPU's Wcsph does, then again
  // onto the GPU.
  if (spec.hydrostatic_start) {
    this->compress_hydrostatically();
    this->upload_fluid(0, this->fluid_.size());
  }
  update_forces();
  this->mark_stale();
  this->reset_stage_times();
}

// One step: kick-drift-kick leapfrog, as the CPU's Wcsph::step.
template <int D>
void GpuWcsph<D>::step() {
  double dt = this->spec_.dt;
  if (this->spec_.time_step_mode != TimeStepMode::Fixed) {
    const auto m = this->gpu_max_speed_and_acceleration();  // 32 bytes read back
    dt = wcsph_time_step(this->spec_, this->prm_, m.v2, m.a2, this->viscous_dt_limit());
  }
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    this->write_params(dt, 0.5 * dt);
    this->transport_velocity_gpu(0.5 * dt);              // optional: ṽ − v (Adami 2013)
    this->kick_drift();                                  // v(t+dt/2), x(t+dt), walls, put-back
    this->advance_scene_gpu(this->time_ + dt, dt);       // obstacles, emitters
  }
  update_forces();                                       // a(t+dt)
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    this->kick(0.5 * dt);                                // v(t+dt)
  }
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
  this->mark_stale();
}

template <int D>
void GpuWcsph<D>::update_forces() {
  {
    const auto timer = this->stage_timer(this->times_.neighbours_s);
    this->sort_particles();             // counting sort by cell (sort.h)
  }
  this->shift_particles_gpu(this->dt_);  // optional (solver.shifting), the last step's Δt
  {
    const auto timer = this->stage_timer(this->times_.density_s);
    this->density_and_pressure();       // Akinci 2012 eq. 6; Tait or linear EOS
    this->measure_density_error_gpu();
    this->boundary_pressure();          // Adami et al. 2012, eq. 27
  }
  const auto timer = this->stage_timer(this->times_.forces_s);
  this->forces();                       // pressure, viscosity, gravity, brush
  this->surface_forces();               // optional: Akinci 2013 cohesion, curvature, adhesion
  this->transport_stress_gpu();         // optional: Adami 2013's momentum correction
}

template class GpuWcsph<2>;
template class GpuWcsph<3>;

}  // namespace rtsph::gpu
