// DFSPH step (Bender & Koschier 2017, Algorithm 1). Non-pressure forces are the shared ones
// (Morris and Monaghan viscosity, gravity, brush); the pressure solves are in dfsph_solve.cpp.
#include "solvers/dfsph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/timer.h"

namespace rtsph {

template <int D>
Dfsph<D>::Dfsph(const SimSpec& spec, int threads) : W(spec, threads) {
  // Several sums per step over one neighbourhood: walk lists, not the grid.
  this->keep_neighbour_lists();
  relax_ = dfsph::jacobi_relaxation<D>(spec_, prm_);
  if (spec_.dfsph_surface_density == SurfaceDensity::Lattice) cut_sums_ = CutSumTable::build<D>(spec_, prm_);
  // Derived after each neighbour update (saved, so a resumed step needs no recompute).
  this->add_method_field({"factor", &factor_, false, true});
  this->add_method_field({"neighbours", &neighbours_, false, true});
  // Scratch of one solve.
  this->add_method_field({"pressure", &pressure_, false, false});
  this->add_method_field({"last_step", &last_step_, false, false});
  // Warm start: the pressure of the last step travels with its particle.
  this->add_method_field({"warm_density", &warm_density_, true, true});
  this->add_method_field({"warm_divergence", &warm_divergence_, true, true});
  this->compute_density();
  this->measure_density_error();
  compute_factors();
  this->reset_stage_times();
}

template <int D>
void Dfsph<D>::step() {
  failure_.clear();
  {
    ScopedTimer timer(times_.forces_s);
    this->compute_inverse_density();
    this->accelerations({.viscosity = true, .external = true, .wall_hydrostatic = true});  // a_nonp            (line 4)
    this->add_transport_velocity_stress();                        // optional, Adami 2013
  }
  const double dt = choose_time_step();                           // CFL              (line 5)
  {
    ScopedTimer timer(times_.integrate_s);
    this->kick(dt);                                               // v* = v + Δt a    (line 6)
  }
  correct_density_error(dt);                                      // Algorithm 3      (line 7)
  {
    ScopedTimer timer(times_.integrate_s);
    // optional: Adami 2013. p_b acts as an explicit pressure, stable only while its signal
    // crosses less than cfl·h per step; DFSPH's step follows the flow, not c0 (Taylor–Green at
    // c0 = 10 U: c0Δt = 2h, the run blew up at step 5), so p_b is capped at ρ0 (cfl·h/Δt)².
    this->transport_velocity_shift(dt, dt, spec_.cfl * prm_.h / dt);
    this->drift(dt);                                              // x += Δt v*       (line 8)
    this->advance_scene(this->time_ + dt, dt);                    // obstacles, emitters
  }
  this->update_neighbours();                                      //                  (line 9)
  this->shift_particles(dt);                                      // optional shifting
  {
    ScopedTimer timer(times_.density_s);
    compute_factors(true);                                        // ρᵢ, αᵢ     (lines 10-11)
    this->measure_density_error();
  }
  correct_divergence_error(dt);                                   // Algorithm 2      (line 12)
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
  counters_.end_step(!failure_.empty());
}

// Δt = cfl·d/max(|v|max, √(|g|H)) (2017, eq. 13 with d the particle spacing, and the head
// speed below), also bounded by the force and viscous limits and max_dt; or the fixed step.
//
// The head speed √(|g|H), H the fluid's extent along gravity: each step starts by applying half
// the last step's pressure as it stands (the warm start), an explicit force whose stiffness
// grows with p, about p/(ρ0 d²), and a column at rest carries p up to ρ0|g|H. Where √(p/ρ0)·Δt
// passes about a spacing, a mode in the bottom layer grows from step to step faster than the few
// sweeps of a converged-looking solve take it back. Measured on the built-in hydrostatic_2d
// (0.5 m deep, d = 1 cm, √(|g|H) = 2.2 m/s), with the velocity CFL alone (Δt = max_dt = 5 ms at
// rest): the bottom layer's vertical speeds grew fivefold per step and the run stopped at
// t = 0.076 s, unstable, even when started from the exact hydrostatic pressure; with max_dt
// 3 ms the worst density error reached 7.1%, with 2 ms 1.1%; with this bound (1.8 ms) 2.3%
// over the first second. The solved pressure itself is no measure: a density error is corrected
// within one step, so its pressure grows as 1/Δt² and a bound on it shrinks the step without
// end (Taylor–Green went to Δt = 1e-20 s). √(|g|H) is also the speed of the column's gravity
// waves.
double dfsph::time_step(const SimSpec& s, const ResolvedParams& prm, double v2max, double a2max,
                        double head, double viscous_limit) {
  if (s.time_step_mode == TimeStepMode::Fixed) return s.dt;
  const double speed = std::max(std::sqrt(v2max), std::sqrt(head));
  double dt = s.max_dt;
  if (speed > 0) dt = std::min(dt, s.cfl * s.spacing / speed);
  if (a2max > 0) dt = std::min(dt, 0.25 * std::sqrt(prm.h / std::sqrt(a2max)));
  return std::min(dt, viscous_limit);
}

template <int D>
double Dfsph<D>::choose_time_step() const {
  if (spec_.time_step_mode == TimeStepMode::Fixed) return spec_.dt;
  const auto m = this->max_speed_and_acceleration();
  double g = 0;
  for (int k = 0; k < D; ++k) g += spec_.gravity[k] * spec_.gravity[k];
  double head = 0;  // |g| times the fluid's extent along gravity
  if (g > 0 && fluid_.size() > 0) {
    struct Extent {
      double lo = 1e300, hi = -1e300;
      Extent& operator+=(const Extent& o) { lo = std::min(lo, o.lo); hi = std::max(hi, o.hi); return *this; }
    };
    const Extent r = pool_.parallel_reduce(fluid_.size(), Extent{}, [&](std::size_t b, std::size_t e) {
      Extent out;
      for (std::size_t i = b; i < e; ++i) {
        double z = 0;  // −g·x: height times |g|
        for (int k = 0; k < D; ++k) z -= spec_.gravity[k] * double(fluid_.x[k][i]);
        out.lo = std::min(out.lo, z);
        out.hi = std::max(out.hi, z);
      }
      return out;
    });
    head = r.hi - r.lo;
  }
  return dfsph::time_step(spec_, prm_, m.v2, m.a2, head, this->viscous_dt_limit());
}

template <int D>
void Dfsph<D>::add_method_scalars(std::vector<StateField>& f) {
  counters_.add_scalars(f);
}

template <int D>
void Dfsph<D>::add_method_stats(SimStats& s) const {
  counters_.add_stats(s, this->steps_);
}

void dfsph::Counters::end_step(bool capped) {
  capped_steps += capped;
  density_iteration_sum += density_iterations;
  divergence_iteration_sum += divergence_iterations;
}

void dfsph::Counters::add_scalars(std::vector<StateField>& f) {
  f.push_back({"dfsph.density_iterations", &density_iterations, sizeof density_iterations});
  f.push_back({"dfsph.divergence_iterations", &divergence_iterations, sizeof divergence_iterations});
  f.push_back({"dfsph.density_iteration_sum", &density_iteration_sum, sizeof density_iteration_sum});
  f.push_back({"dfsph.divergence_iteration_sum", &divergence_iteration_sum, sizeof divergence_iteration_sum});
  f.push_back({"dfsph.capped_steps", &capped_steps, sizeof capped_steps});
}

void dfsph::Counters::add_stats(SimStats& s, std::uint64_t steps) const {
  s.pressure_iterations = density_iterations;
  s.divergence_iterations = divergence_iterations;
  const double n = double(std::max<std::uint64_t>(1, steps));
  s.mean_pressure_iterations = density_iteration_sum / n;
  s.mean_divergence_iterations = divergence_iteration_sum / n;
  s.capped_steps = capped_steps;
}

std::string dfsph::not_converged(const char* solve, int iterations, double t, double error,
                                 double tolerance) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "DFSPH %s solve did not converge in %d iterations at t = %.4g s (mean error "
                "%.3g%%, tolerance %.3g%%)",
                solve, iterations, t, 100 * error, 100 * tolerance);
  return buf;
}

template class Dfsph<2>;
template class Dfsph<3>;

}  // namespace rtsph
