#include "gpu/gpu_pbf.h"

#include <algorithm>
#include <cmath>

#include "core/timer.h"
#include "gpu/layout.h"
#include "solvers/pbf.h"

namespace rtsph::gpu {

namespace {
// The CPU's Jacobi relaxation for a two-sided constraint (solvers/pbf.cpp, kTwoSidedRelax).
constexpr double kTwoSidedRelax = 0.5;
// The neighbour lists' reach over the support: a pair may close by 15% of the support (0.3
// spacings at h = spacing) within a substep's iterations and still be summed.
constexpr double kListSkin = 1.15;
}  // namespace

template <int D>
GpuPbf<D>::GpuPbf(const SimSpec& spec, int threads) : GpuWorld<D>(spec, threads) {
  const auto& d = this->defines();
  external_ = ComputeProgram("pbf_external.comp", d);
  copy_ = ComputeProgram("copy_positions.comp", d);
  lambda_ = ComputeProgram("pbf_lambda.comp", d);
  correct_ = ComputeProgram("pbf_correct.comp", d);
  velocity_ = ComputeProgram("pbf_velocity.comp", d);
  xsph_ = ComputeProgram("pbf_xsph.comp", d);
  vorticity_ = ComputeProgram("pbf_vorticity.comp", d);
  apply_ = ComputeProgram("pbf_apply.comp", d);
  surface_ = ComputeProgram("pbf_surface.comp", d);
  list_ = ComputeProgram("pbf_list.comp", d);
  gate_ = ComputeProgram("pbf_gate.comp", d);
  // The lists reach a skin past the support (kListSkin), so that the iterations sum the pairs a
  // grid walk would even after the corrections move them. Slots for 30% more neighbours than a
  // particle has within that reach in the rest lattice, and for as many wall samples as it has
  // fluid neighbours there: a particle that needs more walks the grid instead, correct but slower.
  const double reach = kListSkin * this->prm_.support / spec.spacing;
  const double inside = D == 3 ? 4.0 / 3.0 * 3.14159265358979 * reach * reach * reach
                               : 3.14159265358979 * reach * reach;
  fluid_cap_ = GLuint(std::ceil(1.3 * inside)) + 8;
  boundary_cap_ = GLuint(std::ceil(inside)) * GLuint(std::max(1, spec.boundary_layers));
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes_);
  stable_weight_ = pbf::stable_weight<D>(this->spec_, this->prm_);
  gradient_peak_ = pbf::gradient_peak<D>(this->spec_, this->prm_);
  lattice_gradient_norm_ = this->lattice_gradient_sum() / (this->prm_.rho0 * this->prm_.rho0);
  this->sort_particles();  // the cell ranges (the fluid is already in cell order)
  this->density_only();
  this->measure_density_error_gpu();
  this->mark_stale();
  this->reset_stage_times();
}

// Algorithm 1: apply forces, predict, find neighbours, solve, update velocity, XSPH/vorticity.
template <int D>
void GpuPbf<D>::step() {
  const double dt = choose_time_step();
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    this->write_params(dt, dt);
    this->bind_all();
    external_.dispatch(this->fluid_.size());       // gravity, brush, walls' hydrostatic part (line 2)
    this->kick_drift();                            // v += Δt a; x* = x + Δt v, walls (line 3)
    this->advance_scene_gpu(this->time_ + dt, dt); // obstacles, emitters
  }
  const std::size_t n = this->fluid_.size();
  for (Buffer* b : {&pred_, &wgrad_, &delta_, &omega_}) b->reserve(this->capacity() * 16);
  lambda_buf_.reserve(this->capacity() * 8);
  const bool surface = this->spec_.surface_tension > 0 || this->spec_.adhesion > 0;
  {
    const auto timer = this->stage_timer(this->times_.neighbours_s);
    this->sort_particles(surface);                 // lines 5-7 (ρ along, for the next stage)
  }
  if (surface) {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    surface_forces_at_prediction();                // line 2's Akinci 2013, at x* (as on the CPU)
  }
  {
    const auto timer = this->stage_timer(this->times_.neighbours_s);
    list_neighbours();                             // and x*, kept for the velocity update
  }
  if (!lists_) {
    this->bind_all();
    pred_.bind(RTSPH_B_PRED);
    copy_.dispatch(n);                             // x*, kept for the velocity update
  }
  solve_density_constraint(dt);                    // lines 8-19
  {
    const auto timer = this->stage_timer(this->times_.integrate_s);
    this->bind_all();
    pred_.bind(RTSPH_B_PRED);
    lambda_buf_.bind(RTSPH_B_LAMBDA);
    wgrad_.bind(RTSPH_B_WGRAD);
    this->put_back_counter_.bind(RTSPH_B_REDUCE);
    velocity_.set("inv_dt", Real(1.0 / dt));
    velocity_.set("iterations", Real(iterations_));
    glProgramUniform1d(velocity_.id(), glGetUniformLocation(velocity_.id(), "pressure_scale"),
                       -1.0 / (this->prm_.rho0 * dt * dt));
    velocity_.dispatch(n);                         // line 21, the equivalent pressure, put-back
  }
  xsph_and_vorticity(dt);                          // line 22, and the density reached
  this->measure_density_error_gpu();
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
  this->mark_stale();
}

// A frame step split into substeps, shortened when the fastest particle would cross more than
// cfl spacings (the CPU's Pbf::choose_time_step).
template <int D>
double GpuPbf<D>::choose_time_step() {
  const SimSpec& s = this->spec_;
  double dt = s.pbf_time_step / std::max(1, s.pbf_substeps);
  if (s.pbf_cfl > 0) {
    const double vmax = std::sqrt(this->gpu_max_speed_and_acceleration().v2);
    if (vmax > 0) dt = std::min(dt, s.pbf_cfl * s.spacing / vmax);
  }
  return dt;
}

template <int D>
void GpuPbf<D>::gate(int mode, int least, int most, double threshold) {
  this->run_gate(gate_, mode, least, most, threshold);
}

template <int D>
void GpuPbf<D>::surface_forces_at_prediction() {
  const std::size_t n = this->fluid_.size();
  for (int mode : {0, 1}) {
    if (mode == 1) this->surface_forces();       // a = the surface forces alone
    this->bind_all();
    delta_.bind(RTSPH_B_DELTA);
    surface_.set("mode", GLint(mode));
    surface_.dispatch(n);
  }
}

template <int D>
void GpuPbf<D>::list_neighbours() {
  const std::size_t stride = this->capacity();
  const std::size_t fluid_bytes = stride * fluid_cap_ * sizeof(GLuint);
  const std::size_t wall_bytes = stride * boundary_cap_ * sizeof(GLuint);
  // Where a list would outgrow a storage block (llvmpipe allows 128 MB), the passes walk the
  // grid as before.
  lists_ = GLint64(std::max(fluid_bytes, wall_bytes)) <= max_block_bytes_;
  nlist_.reserve(lists_ ? fluid_bytes : 16);
  blist_.reserve(lists_ ? wall_bytes : 16);
  ncount_.reserve(stride * 2 * sizeof(GLuint));
  if (!lists_) return;
  this->bind_all();
  bind_lists(list_);
  pred_.bind(RTSPH_B_PRED);
  const double reach = kListSkin * this->prm_.support;
  list_.set("reach2", float(reach * reach));
  list_.dispatch(this->fluid_.size());
}

template <int D>
void GpuPbf<D>::bind_lists(const ComputeProgram& prog) const {
  nlist_.bind(RTSPH_B_NLIST);
  blist_.bind(RTSPH_B_BLIST);
  ncount_.bind(RTSPH_B_NCOUNT);
  prog.set("use_lists", GLint(lists_ ? 1 : 0));
  prog.set("list_stride", GLuint(this->capacity()));
  prog.set("fluid_cap", fluid_cap_);
  prog.set("boundary_cap", boundary_cap_);  // (not every pass reads the walls' list)
}

template <int D>
void GpuPbf<D>::solve_density_constraint(double) {
  const SimSpec& s = this->spec_;
  const std::size_t n = this->fluid_.size();
  lambda_buf_.fill_zero();  // Σλ starts at 0
  lambda_.set("eps", Real(s.pbf_relaxation * lattice_gradient_norm_));
  lambda_.set("omega_relax", Real(s.clamp_negative_pressure ? pbf::jacobi_weight(s, stable_weight_)
                                                            : kTwoSidedRelax));
  const double dq = s.pbf_scorr_dq * this->prm_.support;
  const float w_dq = with_kernel<D>(s.kernel, this->prm_.h, [&](const auto& K) { return float(K.value(float(dq * dq))); });
  const double q_floor = pbf::scorr_floor<D>(s, this->prm_, gradient_peak_);
  for (const ComputeProgram* prog : {&correct_, &lambda_}) {  // λ: s_corr's share of the pressure
    prog->set("inv_w_dq", Real(1.0 / double(w_dq)));
    prog->set("q_floor", Real(q_floor));
    prog->set("k_corr", Real(s.pbf_scorr_k / std::max(lattice_gradient_norm_, 1e-30)));
    prog->set("n_corr", GLint(s.pbf_scorr_n));
  }
  // The CPU's loop (solvers/pbf.cpp): past solver.pbf.iterations while the mean compression the
  // last λ pass measured is above solver.pbf.max_density_error. The test runs on the device
  // (pbf_gate.comp): the host queues as many iterations as the last substep took, then two at a
  // time, and reads the gate back once per batch (32 bytes); the iterations queued after it
  // closed return at once.
  const int least = std::max(1, s.pbf_iterations);
  const int most = std::max(least, s.pbf_max_iterations);
  const double tolerance = s.pbf_max_density_error;
  if (n == 0) {  // no fluid yet: the CPU's loop sees no compression and stops at its minimum
    iterations_ = least;
    iteration_sum_ += iterations_;
    ++solves_;
    return;
  }
  const double threshold = tolerance > 0 ? sum_threshold(tolerance, n) : -1.0;
  gate(0);
  int queued = 0;
  int batch = std::clamp(iterations_, least, most);
  glsl::dvec4 g{};
  for (;;) {
    for (int k = 0; k < batch && queued < most; ++k) {
      {
        const auto timer = this->stage_timer(this->times_.density_s);
        this->bind_all();
        lambda_buf_.bind(RTSPH_B_LAMBDA);
        wgrad_.bind(RTSPH_B_WGRAD);
        bind_lists(lambda_);
        lambda_.set("with_share", GLint(queued == 0 ? 1 : 0));  // s_corr's share: first pass
        lambda_.dispatch(n);
      }
      ++queued;
      if (threshold >= 0 && queued >= least && queued < most) this->reduce_compression();
      {
        const auto timer = this->stage_timer(this->times_.forces_s);
        this->bind_all();
        lambda_buf_.bind(RTSPH_B_LAMBDA);
        wgrad_.bind(RTSPH_B_WGRAD);
        this->pos_alt_.bind(RTSPH_B_POS_NEXT);
        bind_lists(correct_);
        correct_.dispatch(n);
        this->pos_.swap(this->pos_alt_);  // Jacobi: all move at once
      }
      gate(1, least, most, threshold);
    }
    g = this->read_stat(RTSPH_STAT_GATE);  // the one wait per batch
    if (g.x == 0.0 || queued >= most) break;
    batch = 2;
  }
  iterations_ = int(g.y);
  iteration_sum_ += iterations_;
  ++solves_;
}

template <int D>
void GpuPbf<D>::xsph_and_vorticity(double dt) {
  const SimSpec& s = this->spec_;
  const std::size_t n = this->fluid_.size();
  if (s.pbf_xsph <= 0 && s.pbf_vorticity <= 0) {
    const auto timer = this->stage_timer(this->times_.density_s);
    this->density_only();
    return;
  }
  const auto timer = this->stage_timer(this->times_.forces_s);
  const bool vort = s.pbf_vorticity > 0;
  // The new density goes to a spare buffer (the volumes read the old one), then takes its place.
  Buffer& dens_next = this->vel_alt_;  // free until the next sort's gather
  dens_next.reserve(this->capacity() * 16);
  this->bind_all();
  dens_next.bind(RTSPH_B_DENS_NEXT);
  delta_.bind(RTSPH_B_DELTA);
  omega_.bind(RTSPH_B_OMEGA);
  xsph_.set("xsph_c", Real(s.pbf_xsph));
  xsph_.set("vorticity", GLint(vort ? 1 : 0));
  bind_lists(xsph_);
  xsph_.dispatch(n);
  this->dens_.swap(dens_next);
  if (vort) {
    this->bind_all();
    delta_.bind(RTSPH_B_DELTA);
    omega_.bind(RTSPH_B_OMEGA);
    vorticity_.set("step_eps", Real(dt * s.pbf_vorticity));
    vorticity_.dispatch(n);
  }
  this->bind_all();
  delta_.bind(RTSPH_B_DELTA);
  apply_.dispatch(n);
}

template <int D>
void GpuPbf<D>::add_method_stats(SimStats& s) const {
  s.pressure_iterations = iterations_;
  s.mean_pressure_iterations = solves_ ? iteration_sum_ / double(solves_) : iterations_;
}

template class GpuPbf<2>;
template class GpuPbf<3>;

}  // namespace rtsph::gpu
