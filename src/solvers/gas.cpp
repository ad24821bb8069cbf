#include "solvers/gas.h"

#include <algorithm>
#include <cmath>

#include "core/pair_loop.h"
#include "core/timer.h"
#include "solvers/gas_kernel.h"

namespace rtsph {

using simd::f8;
using simd::i8;

namespace {
constexpr int kMaxNewtonIterations = 30;
constexpr double kNewtonTolerance = 1e-4;  // |Δh|/h (Price 2012, sec. 4.2)
// The grid's cell is 2 max(h) of the last step times this, so h may grow by as much during
// one solve and every neighbour within 2hᵢ is still in the 3^d stencil.
constexpr double kCellMargin = 1.25;
}  // namespace

template <int D>
Gas<D>::Gas(const SimSpec& spec, int threads) : W(spec, threads) {
  // Each particle carries the mass of its lattice cell, so a block starts at ρ0 on average.
  this->prm_.mass = spec.rest_density * std::pow(spec.spacing, D);
  for (auto* f : {&h_, &u_, &dudt_, &signal_, &phi_})
    this->add_method_field({.name = f == &h_ ? "h" : f == &u_ ? "u" : f == &dudt_ ? "dudt"
                                           : f == &signal_ ? "signal" : "phi",
                            .array = f});
  // Only within a step (predictor to corrector): sorted with the fluid, never saved.
  static const char* const kPrev[3] = {"a_prev.x", "a_prev.y", "a_prev.z"};
  for (int k = 0; k < D; ++k)
    this->add_method_field({.name = kPrev[k], .array = &a_prev_[k], .sorted = true, .saved = false});
  this->add_method_field({.name = "dudt_prev", .array = &dudt_prev_, .sorted = true, .saved = false});
  std::fill(h_.begin(), h_.end(), Real(spec.gas_eta * spec.spacing));
  update_forces();
  if (spec.gas_eos == GasEos::Adiabatic) {  // u from the polytrope's K at the first density
    const double g = spec.gas_gamma;
    for (std::size_t i = 0; i < this->fluid_.size(); ++i)
      u_[i] = Real(spec.gas_k * std::pow(double(this->fluid_.rho[i]), g - 1) / (g - 1));
    update_forces();
  }
  this->reset_stage_times();
}

// Kick-drift-kick leapfrog (velocity Verlet), as WCSPH; u is kicked with v. The viscosity and
// du/dt depend on the velocity, which at the force evaluation is known only at t + dt/2: they
// are evaluated at the predicted v* = v(t+dt/2) + a(t) dt/2 (and u* likewise), and the last
// kick replaces the predicted half kick by the real one (as Phantom does; Price et al. 2018,
// eqs. 202-205). Without the predictor the energy error is first order in dt (measured: 1.3%
// over 10 dynamical times at C = 0.3, halving with dt).
template <int D>
void Gas<D>::step() {
  const double dt = choose_time_step();  // Courant with hᵢ and the acceleration condition
  {
    ScopedTimer timer(this->times_.integrate_s);
    this->kick(0.5 * dt);                         // v(t+dt/2)
    kick_energy(0.5 * dt);
    this->drift(dt);                              // x(t+dt)
    this->advance_scene(this->time_ + dt, dt);
    predict(0.5 * dt);                            // v* = v(t+dt/2) + a(t) dt/2
  }
  update_forces();                                // a(t+dt) from x(t+dt), v*
  {
    ScopedTimer timer(this->times_.integrate_s);
    correct(0.5 * dt);                            // v(t+dt) = v* − a(t) dt/2 + a(t+dt) dt/2
  }
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
}

template <int D>
void Gas<D>::update_forces() {
  const std::size_t n = this->fluid_.size();
  const bool global = this->spec_.gas_smoothing == GasSmoothing::Global;
  double hg = 0;
  Real cell = 0;
  {
    ScopedTimer timer(this->times_.neighbours_s);
    const Real hmax = this->pool_.parallel_reduce(n, MaxOf<Real>{0}, [&](std::size_t b, std::size_t e) {
      MaxOf<Real> m{0};
      for (std::size_t i = b; i < e; ++i) m.value = std::max(m.value, h_[i]);
      return m;
    }).value;
    // New particles (an emitter's) start from h = η·spacing, so the cell must hold that too.
    const Real h_new = Real(this->spec_.gas_eta * this->spec_.spacing);
    hg = global ? global_h() : 0.0;
    cell = this->follow_fluid(global ? Real(support_ratio(KernelType::Gaussian) * hg)
                                     : Real(2 * kCellMargin) * std::max(hmax, h_new));
  }
  this->update_neighbours();  // timed as neighbours by itself
  {
    ScopedTimer timer(this->times_.density_s);
    for (auto* a : {&omega_, &zeta_, &p_term_, &a_coef_, &cs_, &mass_}) a->resize(n);
    for (auto& a : gacc_) a.resize(n);
    std::fill(mass_.begin(), mass_.end(), Real(this->prm_.mass));
    if (global)
      global_density(hg);
    else
      solve_density(Real(0.5) * cell);
    compute_pressure();
  }
  ScopedTimer timer(this->times_.forces_s);
  hydro_accelerations();
  if (this->spec_.self_gravity) add_self_gravity();
  else std::fill(phi_.begin(), phi_.end(), Real(0));
  add_external();
}

// Newton–Raphson on f(h) = Σⱼ mⱼ W(rᵢⱼ, h) − m (η/h)ᵈ (Price 2012, eqs. 10, 27-29), per particle
// from its last h. f'(h) = Σⱼ mⱼ ∂W/∂h + d ρ(h)/h = (d ρ/h) Ωᵢ, with
//   Ωᵢ = 1 − (∂hᵢ/∂ρᵢ) Σⱼ mⱼ ∂Wᵢⱼ(hᵢ)/∂hᵢ,  ∂h/∂ρ = −h/(d ρ).
// Where Ω ≤ 0 (Newton would walk away) the fixed-point step h = η (m/ρ)^(1/d) is taken. The
// values kept are those summed at the last h, so ρ, Ω and ζ belong to the same h exactly.
template <int D>
void Gas<D>::solve_density(Real hcap) {
  const std::size_t n = this->fluid_.size();
  const double m = this->prm_.mass, eta = this->spec_.gas_eta;
  const bool gravity = this->spec_.self_gravity;
  const auto& grid = this->ctx_.fluid_grid;
  const uint32_t* cells = grid.sorted_cells();
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = this->fluid_.x[k].data();
  Real* rho = this->fluid_.rho.data();
  this->pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Real xi[D];
      for (int k = 0; k < D; ++k) xi[k] = xs[k][i];
      // A new particle (an emitter's) has no h yet: start from its lattice spacing.
      double h = h_[i] > 0 ? std::min(double(h_[i]), double(hcap)) : eta * this->spec_.spacing;
      h = std::min(h, double(hcap));
      double sum_w = 0, sum_dw = 0, sum_dphi = 0;
      for (int it = 0; it < kMaxNewtonIterations; ++it) {
        const f8 inv_h = f8{} + float(1.0 / h);
        f8 w{}, dw{}, dphi{};
        const i8 self = simd::lane_index() + int(i);
        for_each_candidate_batch<D, false>(grid, cells[i], xs, xi, Real(4 * h * h),
                                           [&](auto j, const f8*, f8 r2, i8 mask) {
          const f8 q = simd::sqrt(r2) * inv_h;
          w += simd::select(mask, gas::value<D>(q, inv_h), f8{});
          dw += simd::select(mask, gas::dw_dh<D>(q, inv_h), f8{});
          if (gravity) {  // no self term: the potential energy has none (gravity_direct.h)
            const i8 other = mask & (simd::lane_index() + int(j) != self);
            dphi += simd::select(other, gas::dphi_dh(q, inv_h), f8{});
          }
        });
        sum_w = m * simd::hsum(w);
        sum_dw = m * simd::hsum(dw);
        sum_dphi = m * simd::hsum(dphi);
        const double rho_h = m * std::pow(eta / h, D);
        const double fp = sum_dw + D * rho_h / h;
        double hn = fp > 0 ? h - (sum_w - rho_h) / fp : eta * std::pow(m / sum_w, 1.0 / D);
        hn = std::clamp(hn, 0.7 * h, std::min(1.3 * h, double(hcap)));
        if (std::abs(hn - h) <= kNewtonTolerance * h) break;
        h = hn;
      }
      const double dh_drho = -h / (D * sum_w);
      h_[i] = Real(h);
      rho[i] = Real(sum_w);
      omega_[i] = Real(1.0 - dh_drho * sum_dw);
      zeta_[i] = Real(dh_drho * sum_dphi);
    }
  }, ThreadPool::kPairs);
}

// h = b (⟨|x|²⟩ − |⟨x⟩|²)^½: the particles' positional spread (Gingold & Monaghan 1977, eq. 4,
// with r the position vector, so h does not depend on where the origin is). Tiny clouds
// (one particle) fall back to η·spacing.
template <int D>
double Gas<D>::global_h() const {
  struct Moments {
    double s[D + 1] = {};
    Moments& operator+=(const Moments& o) {
      for (int k = 0; k <= D; ++k) s[k] += o.s[k];
      return *this;
    }
  };
  const auto& f = this->fluid_;
  const std::size_t n = f.size();
  const Moments m = this->pool_.parallel_reduce(n, Moments{}, [&](std::size_t b, std::size_t e) {
    Moments r;
    for (std::size_t i = b; i < e; ++i)
      for (int k = 0; k < D; ++k) {
        r.s[k] += f.x[k][i];
        r.s[D] += double(f.x[k][i]) * f.x[k][i];
      }
    return r;
  });
  double var = n ? m.s[D] / double(n) : 0.0;
  for (int k = 0; k < D; ++k) var -= n ? (m.s[k] / double(n)) * (m.s[k] / double(n)) : 0.0;
  const double h = this->spec_.gas_global_b * std::sqrt(std::max(var, 0.0));
  return h > 0 ? h : this->spec_.gas_eta * this->spec_.spacing;
}

template <int D>
void Gas<D>::global_density(double h) {
  const std::size_t n = this->fluid_.size();
  const Real m = Real(this->prm_.mass);
  const Gaussian<D> K(h);
  const Real support2 = Real(9 * h * h);
  const auto& grid = this->ctx_.fluid_grid;
  const uint32_t* cells = grid.sorted_cells();
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = this->fluid_.x[k].data();
  Real* rho = this->fluid_.rho.data();
  this->pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Real xi[D];
      for (int k = 0; k < D; ++k) xi[k] = xs[k][i];
      f8 w{};
      for_each_candidate_batch<D, false>(grid, cells[i], xs, xi, support2,
                                         [&](auto, const f8*, f8 r2, i8 mask) {
        w += simd::select(mask, K.value(r2), f8{});
      });
      rho[i] = m * simd::hsum(w);
      h_[i] = Real(h);
      omega_[i] = 1;  // h depends on no single particle's density: no grad-h terms (G&M 1977)
      zeta_[i] = 0;
    }
  }, ThreadPool::kPairs);
}

template <int D>
double Gas<D>::specific_energy(std::size_t i) const {
  const auto& s = this->spec_;
  if (s.gas_eos == GasEos::Adiabatic) return u_[i];
  return s.gas_k * std::pow(double(this->fluid_.rho[i]), s.gas_gamma - 1) / (s.gas_gamma - 1);
}

// p = K ρ^γ or (γ−1) ρ u; c = √(γ p/ρ). The symmetric force reads pᵢ/(Ωᵢ ρᵢ²), plus, with
// self-gravity, the gravitational grad-h coefficient G ζᵢ/(2 Ωᵢ) that multiplies the same
// kernel gradient (Price & Monaghan 2007, eq. 31), folded in as one coefficient.
template <int D>
void Gas<D>::compute_pressure() {
  const auto& s = this->spec_;
  const double g = s.gas_gamma, K = s.gas_k;
  const bool adiabatic = s.gas_eos == GasEos::Adiabatic;
  const double half_G = s.self_gravity ? 0.5 * s.gravitational_constant : 0.0;
  auto& f = this->fluid_;
  this->pool_.parallel_for(f.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const double rho = f.rho[i];
      const double p = adiabatic ? (g - 1) * rho * std::max(0.0, double(u_[i])) : K * std::pow(rho, g);
      f.p[i] = Real(p);
      cs_[i] = Real(std::sqrt(g * p / rho));
      p_term_[i] = Real(p / (omega_[i] * rho * rho));
      a_coef_[i] = Real(p / (omega_[i] * rho * rho) + half_G * zeta_[i] / omega_[i]);
    }
  });
}

// a −= λ x (toy star), a −= ν v (damping), a += g (uniform); energy of the first in stats.
template <int D>
void Gas<D>::add_external() {
  const auto& s = this->spec_;
  const Vec3d g = this->external_acceleration();
  const Real lambda = Real(s.gas_spring), nu = Real(s.gas_damping);
  auto& f = this->fluid_;
  this->pool_.parallel_for(f.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k)
      for (std::size_t i = b; i < e; ++i)
        f.a[k][i] += Real(g[k]) - lambda * f.x[k][i] - nu * f.v[k][i];
  });
}

template <int D>
void Gas<D>::predict(double half_dt) {
  const Real hdt = Real(half_dt);
  const bool adiabatic = this->spec_.gas_eos == GasEos::Adiabatic;
  auto& f = this->fluid_;
  this->pool_.parallel_for(f.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k)
      for (std::size_t i = b; i < e; ++i) {
        a_prev_[k][i] = f.a[k][i];
        f.v[k][i] += f.a[k][i] * hdt;
      }
    if (adiabatic)
      for (std::size_t i = b; i < e; ++i) {
        dudt_prev_[i] = dudt_[i];
        u_[i] = std::max(Real(0), u_[i] + dudt_[i] * hdt);
      }
  });
}

template <int D>
void Gas<D>::correct(double half_dt) {
  const Real hdt = Real(half_dt);
  const bool adiabatic = this->spec_.gas_eos == GasEos::Adiabatic;
  auto& f = this->fluid_;
  this->pool_.parallel_for(f.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k)
      for (std::size_t i = b; i < e; ++i) f.v[k][i] += (f.a[k][i] - a_prev_[k][i]) * hdt;
    if (adiabatic)
      for (std::size_t i = b; i < e; ++i)
        u_[i] = std::max(Real(0), u_[i] + (dudt_[i] - dudt_prev_[i]) * hdt);
  });
}

template <int D>
void Gas<D>::kick_energy(double dt) {
  if (this->spec_.gas_eos != GasEos::Adiabatic) return;
  const Real fdt = Real(dt);
  this->pool_.parallel_for(this->fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) u_[i] = std::max(Real(0), u_[i] + dudt_[i] * fdt);
  });
}

// dt = min over i of C hᵢ/vsigᵢ (Courant, with the viscous signal speed of Monaghan 1992) and
// ¼ √(hᵢ/|aᵢ|) (the force condition), and of the damping's and spring's own limits.
template <int D>
double Gas<D>::choose_time_step() const {
  const auto& s = this->spec_;
  if (s.time_step_mode == TimeStepMode::Fixed) return s.dt;
  const auto& f = this->fluid_;
  struct Min {
    double value;
    Min& operator+=(const Min& o) { value = std::min(value, o.value); return *this; }
  };
  double dt = this->pool_.parallel_reduce(f.size(), Min{s.max_dt}, [&](std::size_t b, std::size_t e) {
    double m = 1e300;
    for (std::size_t i = b; i < e; ++i) {
      double a2 = 0;
      for (int k = 0; k < D; ++k) a2 += double(f.a[k][i]) * f.a[k][i];
      const double h = h_[i];
      if (signal_[i] > 0) m = std::min(m, s.cfl * h / signal_[i]);
      if (a2 > 0) m = std::min(m, 0.25 * std::sqrt(h / std::sqrt(a2)));
    }
    return Min{m};
  }).value;
  if (s.gas_damping > 0) dt = std::min(dt, 0.5 / s.gas_damping);
  if (s.gas_spring > 0) dt = std::min(dt, 0.1 / std::sqrt(s.gas_spring));
  return dt;
}

template <int D>
void Gas<D>::measure_energies(SimStats& st) const {
  W::measure_energies(st);  // kinetic, −m g·x, max speed
  struct E {
    double thermal = 0, grav = 0, spring = 0;
    E& operator+=(const E& o) { thermal += o.thermal; grav += o.grav; spring += o.spring; return *this; }
  };
  const double m = this->prm_.mass;
  const auto& f = this->fluid_;
  const E e = this->pool_.parallel_reduce(f.size(), E{}, [&](std::size_t b, std::size_t end) {
    E r;
    for (std::size_t i = b; i < end; ++i) {
      double x2 = 0;
      for (int k = 0; k < D; ++k) x2 += double(f.x[k][i]) * f.x[k][i];
      r.thermal += m * specific_energy(i);
      r.grav += 0.5 * m * phi_[i];
      r.spring += 0.5 * m * this->spec_.gas_spring * x2;
    }
    return r;
  });
  st.thermal_energy_j = e.thermal;
  st.gravitational_energy_j = e.grav;
  st.potential_energy_j += e.thermal + e.grav + e.spring;
}

template <int D>
void Gas<D>::add_method_stats(SimStats& st) const {
  double hmin = 0, cmax = 0;
  for (std::size_t i = 0; i < this->fluid_.size(); ++i) {
    hmin = i == 0 ? double(h_[i]) : std::min(hmin, double(h_[i]));
    if (i < cs_.size()) cmax = std::max(cmax, double(cs_[i]));
  }
  st.h = hmin;
  st.c0 = cmax;
}

template class Gas<2>;
template class Gas<3>;

}  // namespace rtsph
