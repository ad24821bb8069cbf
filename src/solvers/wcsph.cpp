#include "solvers/wcsph.h"

#include <algorithm>
#include <cmath>

#include "core/timer.h"

namespace rtsph {

template <int D>
Wcsph<D>::Wcsph(const SimSpec& spec, int threads) : W(spec, threads) {
  this->compress_hydrostatically();  // optional (fluid.hydrostatic_start); update_forces sorts
  update_forces();
  this->reset_stage_times();
}

// One step: kick-drift-kick leapfrog (velocity Verlet), symplectic and second order.
template <int D>
void Wcsph<D>::step() {
  const double dt = choose_time_step();  // CFL, force and viscous limits (Monaghan 1992)
  {
    ScopedTimer timer(this->times_.integrate_s);
    this->kick(0.5 * dt);                         // v(t+dt/2) = v(t) + a(t) dt/2
    this->transport_velocity_shift(0.5 * dt, dt);  // optional: x += dt·(dt/2)·a_b(t) (Adami 2013)
    this->drift(dt);                              // x(t+dt) = x(t) + v(t+dt/2) dt
    this->advance_scene(this->time_ + dt, dt);    // obstacles, emitters, put-back
  }
  update_forces();                                // a(t+dt) from x(t+dt), v(t+dt/2)
  {
    ScopedTimer timer(this->times_.integrate_s);
    this->kick(0.5 * dt);                         // v(t+dt) = v(t+dt/2) + a(t+dt) dt/2
  }
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
}

template <int D>
void Wcsph<D>::update_forces() {
  this->update_neighbours();
  this->shift_particles(this->dt_);         // optional (solver.shifting), the last step's Δt
  {
    ScopedTimer timer(this->times_.density_s);
    this->compute_density();                // ρᵢ = Σⱼ mⱼ Wᵢⱼ + Σ_b Ψ_b W_ib (Akinci 2012, eq. 6)
    compute_pressure();                     // Tait (Becker & Teschner 2007) or p = k(ρ - ρ0)
    this->extrapolate_boundary_pressure();  // wall pressure (Adami et al. 2012, eq. 27)
  }
  {
    ScopedTimer timer(this->times_.forces_s);
    // Symmetric pressure (Monaghan 1992), viscosity, gravity, brush: one pair loop.
    this->accelerations({.pressure = this->ctx_.p_over_rho2.data(),
                         .boundary_pressure = this->ctx_.boundary_p_over_rho2.data()});
    this->add_transport_velocity_stress();  // optional (solver.transport_velocity, Adami 2013)
  }
}

double wcsph_time_step(const SimSpec& s, const ResolvedParams& prm, double v2max, double a2max,
                       double viscous_limit) {
  if (s.time_step_mode == TimeStepMode::Fixed) return s.dt;
  const double h = prm.h;
  double dt = std::min(s.max_dt, s.cfl * h / (prm.c0 + std::sqrt(v2max)));
  if (a2max > 0) dt = std::min(dt, 0.25 * std::sqrt(h / std::sqrt(a2max)));
  return std::min(dt, viscous_limit);
}

template <int D>
double Wcsph<D>::choose_time_step() const {
  if (this->spec_.time_step_mode == TimeStepMode::Fixed) return this->spec_.dt;
  const auto m = this->max_speed_and_acceleration();
  return wcsph_time_step(this->spec_, this->prm_, m.v2, m.a2, this->viscous_dt_limit());
}

template <int D>
void Wcsph<D>::compute_pressure() {
  const auto& prm = this->prm_;
  const double rho0 = prm.rho0, B = prm.tait_b, k = prm.stiffness, gamma = this->spec_.tait_gamma;
  const bool tait = this->spec_.eos == Eos::Tait, clamp = this->spec_.clamp_negative_pressure;
  auto& fluid = this->fluid_;
  auto& ctx = this->ctx_;
  const std::size_t n = fluid.size();
  ctx.p_over_rho2.resize(n);
  ctx.inv_rho.resize(n);
  this->pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const double rho = fluid.rho[i], x = rho / rho0;
      double p;
      if (tait) {
        const double x7 = gamma == 7.0 ? x * x * x * x * x * x * x : std::pow(x, gamma);
        p = B * (x7 - 1.0);
      } else {
        p = k * (rho - rho0);
      }
      if (clamp && p < 0) p = 0;
      fluid.p[i] = Real(p);
      ctx.p_over_rho2[i] = Real(p / (rho * rho));
      ctx.inv_rho[i] = Real(1.0 / rho);
    }
  });
  this->measure_density_error();
}

template class Wcsph<2>;
template class Wcsph<3>;

}  // namespace rtsph
