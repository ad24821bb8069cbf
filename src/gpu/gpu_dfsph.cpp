#include "gpu/gpu_dfsph.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/timer.h"
#include "gpu/layout.h"
#include "solvers/dfsph.h"
#include "solvers/surface_density.h"

namespace rtsph::gpu {

namespace {
constexpr int kCutRows = RTSPH_CUT_ROWS;  // the factors shader's table (layout.h)
}  // namespace

template <int D>
GpuDfsph<D>::GpuDfsph(const SimSpec& spec, int threads) : GpuWorld<D>(spec, threads) {
  const auto& d = this->defines();
  {
    auto dn = d;
    dn.push_back("NONPRESSURE 1");
    nonpressure_ = ComputeProgram("forces.comp", dn);
  }
  factors_ = ComputeProgram("dfsph_factors.comp", d);
  apply_ = ComputeProgram("dfsph_apply.comp", d);
  residual_ = ComputeProgram("dfsph_residual.comp", d);
  sweep_ = ComputeProgram("dfsph_sweep.comp", d);
  totals_ = ComputeProgram("dfsph_totals.comp", d);
  gate_ = ComputeProgram("dfsph_gate.comp", d);
  relax_ = dfsph::jacobi_relaxation<D>(this->spec_, this->prm_);
  tiny_ = 1e-6 * this->lattice_gradient_sum();
  if (spec.dfsph_surface_density == SurfaceDensity::Lattice) {
    const CutSumTable t = CutSumTable::build<D>(spec, this->prm_);
    if (t.rows().size() > std::size_t(kCutRows))
      throw std::invalid_argument(fmt::format(
          "scene '{}': solver.dfsph.surface_density = \"lattice\": the kernel reaches {} lattice layers, the "
          "GPU backend's table holds {}; use --backend cpu", spec.name, t.rows().size(), kCutRows));
    for (const auto& [c, tau] : t.rows()) cut_table_.insert(cut_table_.end(), {float(c), float(tau)});
  }
  // The CPU's method fields, in the CPU's order (Dfsph's constructor): a checkpoint lists them.
  this->add_method_field({"factor", &factor_, false, true});
  this->add_method_field({"neighbours", &neighbours_, false, true});
  this->add_method_field({"pressure", &pressure_, false, false});
  this->add_method_field({"last_step", &last_step_, false, false});
  this->add_method_field({"warm_density", &warm_density_, true, true});
  this->add_method_field({"warm_divergence", &warm_divergence_, true, true});
  this->add_device_field({&warm_, &warm_alt_, {&warm_density_, &warm_divergence_, nullptr, nullptr}, true});
  this->add_device_field({&factor_buf_, nullptr, {&factor_, &neighbours_, nullptr, nullptr}, false});
  for (Buffer* b : {&solve_, &wgrad_}) b->reserve(this->capacity() * sizeof(glsl::vec4));
  this->sort_particles();  // the cell ranges (the fluid is already in cell order)
  factors(true);
  this->measure_density_error_gpu();
  this->mark_stale();
  this->reset_stage_times();
}

// Algorithm 1 of Bender & Koschier 2017, as the CPU's Dfsph::step.
template <int D>
void GpuDfsph<D>::step() {
  failure_.clear();
  const SimSpec& s = this->spec_;
  const std::size_t n = this->fluid_.size();
  for (Buffer* b : {&solve_, &wgrad_}) b->reserve(this->capacity() * sizeof(glsl::vec4));
  {
    const auto timer = this->stage_timer(this->times_.forces_s);
    this->write_params(this->dt_, 0);  // the force passes read no Δt
    this->bind_all();
    nonpressure_.dispatch(n);          // a_nonp: viscosity, gravity, walls, brush   (line 4)
    this->surface_forces();            // optional: Akinci 2013
    this->transport_stress_gpu();      // optional: Adami 2013's momentum correction
  }
  const double dt = choose_time_step();  // CFL and the head speed               (line 5)
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    this->write_params(dt, 0);
    this->kick(dt);                      // v* = v + Δt a_nonp                     (line 6)
  }
  // Where the fluid fills a periodic box with two-sided pressure, the density solve targets the
  // mean kernel sum (the CPU's Dfsph::correct_density_error says why).
  density_bias_ = dfsph::targets_mean_density<D>(s, n) ? this->gpu_mean_density() - this->prm_.rho0 : 0.0;
  counters_.density_iterations = solve(true, dt, s.dfsph_max_density_error, "density");  // Alg. 3 (line 7)
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    // optional: Adami 2013, p_b capped at ρ0 (cfl·h/Δt)² as on the CPU (Dfsph::step says why);
    // kick_drift then moves each particle by Δt(ṽ − v) before its drift.
    this->transport_velocity_gpu(dt, s.cfl * this->prm_.h / dt);
    this->kick_drift();                            // x += Δt v*, walls, put-back   (line 8)
    this->advance_scene_gpu(this->time_ + dt, dt); // obstacles, emitters
  }
  for (Buffer* b : {&solve_, &wgrad_}) b->reserve(this->capacity() * sizeof(glsl::vec4));  // emitted
  {
    const auto timer = this->stage_timer(this->times_.neighbours_s);
    this->sort_particles();                        //                              (line 9)
  }
  this->shift_particles_gpu(dt);                   // optional shifting
  {
    const auto timer = this->stage_timer(this->times_.density_s);
    factors(true);                                 // ρᵢ, αᵢ                 (lines 10-11)
    this->measure_density_error_gpu();
  }
  counters_.divergence_iterations = solve(false, dt, s.dfsph_max_divergence_error, "divergence");  // Alg. 2
  {
    // The step's pressure for output, p = ρ²(P_density + P_divergence).
    const auto timer = this->stage_timer(this->times_.forces_s);
    bind_method();
    totals_.set("mode", GLint(2));
    totals_.dispatch(this->fluid_.size());  // emitters may have added particles since n
  }
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
  counters_.end_step(!failure_.empty());
  this->mark_stale();
}

template <int D>
double GpuDfsph<D>::choose_time_step() {
  const SimSpec& s = this->spec_;
  if (s.time_step_mode == TimeStepMode::Fixed) return s.dt;
  const auto m = this->gpu_max_speed_and_acceleration();
  double g = 0;
  for (int k = 0; k < D; ++k) g += s.gravity[k] * s.gravity[k];
  const double head = g > 0 ? this->gpu_head() : 0.0;
  return dfsph::time_step(s, this->prm_, m.v2, m.a2, head, this->viscous_dt_limit());
}

template <int D>
void GpuDfsph<D>::bind_method() const {
  this->bind_all();
  solve_.bind(RTSPH_B_DFSPH_SOLVE);
  factor_buf_.bind(RTSPH_B_DFSPH_FACTOR);
  wgrad_.bind(RTSPH_B_WGRAD);
  warm_.bind(RTSPH_B_DFSPH_WARM);
}

template <int D>
void GpuDfsph<D>::factors(bool with_density) {
  bind_method();
  factors_.set("tiny", Real(tiny_));
  factors_.set("with_density", GLint(with_density ? 1 : 0));
  const GLint rows = GLint(cut_table_.size() / 2);
  factors_.set("cut_rows", rows);
  if (rows > 0)
    glProgramUniform2fv(factors_.id(), glGetUniformLocation(factors_.id(), "cut_table"), rows, cut_table_.data());
  factors_.dispatch(this->fluid_.size());
}

template <int D>
void GpuDfsph<D>::apply_pressure(int source) {
  bind_method();
  apply_.set("source", GLint(source));
  apply_.dispatch(this->fluid_.size());
}

template <int D>
void GpuDfsph<D>::residual(bool density, double dt) {
  bind_method();
  const GLuint prog = residual_.id();
  residual_.set("density", GLint(density ? 1 : 0));
  residual_.set("min_neighbours", dfsph::kMinNeighbours<D>);
  residual_.set("lattice", GLint(cut_table_.empty() ? 0 : 1));
  // The pressure stabilisation (the CPU's Dfsph::residual): the density solve only.
  const double beta = density ? this->spec_.dfsph_pressure_stabilisation : 0.0;
  const double mass = this->prm_.mass;
  glProgramUniform1d(prog, glGetUniformLocation(prog, "gain"), relax_ / (1.0 + beta));
  glProgramUniform1d(prog, glGetUniformLocation(prog, "stab"), beta * dt * dt * mass * mass);
  glProgramUniform1d(prog, glGetUniformLocation(prog, "to_p"), density ? 1.0 / (dt * dt) : 1.0 / dt);
  glProgramUniform1d(prog, glGetUniformLocation(prog, "bias"), density ? density_bias_ : 0.0);
  glProgramUniform1d(prog, glGetUniformLocation(prog, "error_scale"),
                     (density ? 1.0 : dt) / this->prm_.rho0);
  residual_.dispatch(this->fluid_.size());
  solve_.bind(RTSPH_B_DFSPH_SOLVE);
  this->reduce_solve_error();
}

template <int D>
void GpuDfsph<D>::gate(int mode, int least, int most, double threshold) {
  this->run_gate(gate_, mode, least, most, threshold);
}

// The CPU's Dfsph::solve: the warm start (a share of the last step's total, stored independent
// of Δt), then relaxed Jacobi sweeps, Chebyshev-accelerated in clamped density solves, until the
// mean error reaches the tolerance (at least two sweeps for density, one for divergence). The
// stopping test runs on the device; the sweeps queued after it stops return at once.
template <int D>
int GpuDfsph<D>::solve(bool density, double dt, double tolerance, const char* name) {
  const auto timer = this->stage_timer(density ? this->times_.density_s : this->times_.forces_s);
  const SimSpec& s = this->spec_;
  const std::size_t n = this->fluid_.size();
  const double to_p = density ? 1.0 / (dt * dt) : 1.0 / dt;
  const GLuint totals = totals_.id();
  const int max_iterations = std::max(1, s.dfsph_max_iterations);
  const int min_iterations = density ? 2 : 1;
  // No fluid yet (an emitter's scene before its first layer): the CPU's loop sees a zero error
  // and stops after its minimum; the device would test a residual sum nothing wrote.
  if (n == 0) return std::min(min_iterations, max_iterations);
  const double threshold = sum_threshold(tolerance, n);
  gate(0);  // open
  bind_method();
  totals_.set("mode", GLint(0));
  totals_.set("component", GLint(density ? 0 : 1));
  glProgramUniform1d(totals, glGetUniformLocation(totals, "scale"), to_p * dfsph::kWarm);
  totals_.dispatch(n);
  apply_pressure(2);
  residual(density, dt);
  gate(1, min_iterations, max_iterations, threshold);
  const double rho = density && s.clamp_negative_pressure ? s.dfsph_chebyshev : 0.0;
  double omega = 1.0;
  int queued = 0;
  int batch = std::clamp(last_sweeps_[density], min_iterations, max_iterations);
  glsl::dvec4 g{};
  for (;;) {
    for (int k = 0; k < batch && queued < max_iterations; ++k, ++queued) {
      omega = dfsph::chebyshev_weight(queued, rho, omega);  // the sweep's, should it run
      bind_method();
      sweep_.set("w", Real(omega));
      sweep_.set("w1", Real(omega - 1.0));
      sweep_.set("first", GLint(queued == 0 ? 1 : 0));
      sweep_.dispatch(n);
      apply_pressure(0);
      residual(density, dt);
      gate(2, min_iterations, max_iterations, threshold);
    }
    g = this->read_stat(RTSPH_STAT_GATE);  // 32 bytes: the one wait per batch
    if (g.x == 0.0 || queued >= max_iterations) break;
    batch = 2;
  }
  int it = int(g.y);
  const double err = g.z / double(n);
  last_sweeps_[density] = it;  // the batch to queue next time: the accelerated loop's sweeps
  if (dfsph::smooths_last(it, rho)) {  // the CPU's closing plain sweep (Dfsph::solve says why)
    gate(0);                          // reopened: the sweep and the kick return at once when closed
    bind_method();
    sweep_.set("w", Real(1));
    sweep_.set("w1", Real(0));
    sweep_.set("first", GLint(1));
    sweep_.dispatch(n);
    apply_pressure(0);
    ++it;
  }
  bind_method();
  totals_.set("mode", GLint(1));
  totals_.set("component", GLint(density ? 0 : 1));
  glProgramUniform1d(totals, glGetUniformLocation(totals, "scale"), 1.0 / to_p);
  totals_.dispatch(n);
  if (err > tolerance && failure_.empty())
    failure_ = dfsph::not_converged(name, it, this->time_ + dt, err, tolerance);
  return it;
}

// A loaded state: the base uploads the particles and the device fields (the warm start); the
// factors follow from the positions, as the CPU's Dfsph::state_loaded recomputes them.
template <int D>
void GpuDfsph<D>::state_loaded() {
  GpuWorld<D>::state_loaded();
  for (Buffer* b : {&solve_, &wgrad_}) b->reserve(this->capacity() * sizeof(glsl::vec4));
  this->write_params(this->dt_, 0);
  this->sort_particles();  // the cell starts of the loaded order (already sorted: unchanged)
  factors(false);
}

template <int D>
void GpuDfsph<D>::add_method_scalars(std::vector<StateField>& f) {
  counters_.add_scalars(f);
}

template <int D>
void GpuDfsph<D>::add_method_stats(SimStats& s) const {
  counters_.add_stats(s, this->steps_);
}

template class GpuDfsph<2>;
template class GpuDfsph<3>;

}  // namespace rtsph::gpu
