#include "gpu/gpu_world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "gpu/gpu_world_detail.h"
#include "gpu/layout.h"

namespace rtsph::gpu {

static_assert(RTSPH_FACE_RADIAL == kRadialFace, "layout.h's radial face code is geometry.h's");

using namespace detail;

namespace {
using glsl::SphParams;
using glsl::vec4;

// The kernel's constants exactly as the CPU's kernel object holds them (core/kernels.h), so
// both backends evaluate the same float expressions.
template <int D>
void kernel_constants(KernelType type, double h, SphParams& p) {
  switch (type) {
    case KernelType::CubicSpline: {
      const CubicSpline<D> k(h);
      p.kernel_a = {k.h, k.inv_h, k.sigma, k.gsigma};
      p.kernel_b = {k.tiny, 0, 0, 0};
      break;
    }
    case KernelType::WendlandC2: {
      const WendlandC2<D> k(h);
      p.kernel_a = {k.h, k.inv_h, k.sigma, k.gsigma};
      p.kernel_b = {k.tiny, 0, 0, 0};
      break;
    }
    case KernelType::Poly6Spiky: {
      const Poly6Spiky<D> k(h);
      p.kernel_a = {k.R, k.R2, k.inv_R, k.poly6};
      p.kernel_b = {k.spiky, 0, 0, 0};
      break;
    }
    case KernelType::Gaussian: {
      const Gaussian<D> k(h);
      p.kernel_a = {k.h, k.inv_h2, k.sigma, k.cutoff2};
      p.kernel_b = {0, 0, 0, 0};
      break;
    }
  }
}
}  // namespace

template <int D>
GpuWorld<D>::GpuWorld(const SimSpec& spec, int threads) : FluidWorld<D>(spec, threads) {
  if (const std::string why = compute_support_problem(); !why.empty()) throw std::runtime_error(why);
  defines_ = {fmt::format("DIM {}", D), fmt::format("KERNEL {}", int(spec.kernel))};
  compile_programs();
  glCreateBuffers(1, &params_ubo_);
  glNamedBufferData(params_ubo_, sizeof(SphParams), nullptr, GL_DYNAMIC_DRAW);
  stats_.reserve(kSlots * sizeof(DVec4));
  stats_.fill_zero();
  put_back_counter_.reserve(16);
  put_back_counter_.fill_zero();
  const std::size_t n = this->fluid_.size();
  capacity_ = n + std::size_t(count_particles(spec).emitted_max);
  for (Buffer* b : {&pos_, &vel_, &acc_, &dens_, &pos_alt_, &vel_alt_}) b->reserve(capacity_ * sizeof(vec4));
  for (Buffer* b : {&id_, &id_alt_}) b->reserve(capacity_ * 4);
  write_params(0, 0);
  upload_fluid(0, n);
  upload_boundary();
  upload_obstacles();
  sort_boundary();
}

template <int D>
GpuWorld<D>::~GpuWorld() {
  if (params_ubo_) glDeleteBuffers(1, &params_ubo_);
}

template <int D>
void GpuWorld<D>::compile_programs() {
  sorter_ = std::make_unique<CellSorter>(defines_);
  density_ = ComputeProgram("density.comp", defines_);
  {
    auto d = defines_;
    d.push_back("DENSITY_ONLY 1");
    density_only_ = ComputeProgram("density.comp", d);
  }
  boundary_pressure_ = ComputeProgram("boundary_pressure.comp", defines_);
  forces_ = ComputeProgram("forces.comp", defines_);
  surface_normal_ = ComputeProgram("surface_normal.comp", defines_);
  surface_forces_ = ComputeProgram("surface_forces.comp", defines_);
  shift_ = ComputeProgram("shift.comp", defines_);
  shift_apply_ = ComputeProgram("shift_apply.comp", defines_);
  transport_ = ComputeProgram("transport.comp", defines_);
  transport_stress_ = ComputeProgram("transport_stress.comp", defines_);
  {
    auto d = defines_;
    d.push_back("TRANSPORT 1");
    kick_drift_transport_ = ComputeProgram("kick_drift.comp", d);
  }
  kick_ = ComputeProgram("kick.comp", defines_);
  kick_drift_ = ComputeProgram("kick_drift.comp", defines_);
  move_boundary_ = ComputeProgram("move_boundary.comp", defines_);
  for (int m = 0; m < kReduceModes; ++m) {
    auto d = defines_;
    d.push_back(fmt::format("MODE {}", m));
    d.push_back("FINAL 0");
    reduce_[m] = ComputeProgram("reduce.comp", d);
    d.back() = "FINAL 1";
    reduce_final_[m] = ComputeProgram("reduce.comp", d);
  }
}

template <int D>
void GpuWorld<D>::write_params(double dt, double kick_dt) {
  params_dt_ = dt;
  params_kick_dt_ = kick_dt;
  const auto& prm = this->prm_;
  const auto& s = this->spec_;
  const auto& grid = this->ctx_.fluid_grid;
  SphParams p{};
  double origin[3] = {0, 0, 0}, inv_cell[3] = {0, 0, 0};
  int dims[3] = {1, 1, 1};
  for (int k = 0; k < D; ++k) {
    origin[k] = double(grid.origin()[k]);
    inv_cell[k] = grid.inv_cell(k);
    dims[k] = grid.dim(k);
  }
  p.grid_origin = {origin[0], origin[1], origin[2], 0};
  p.grid_inv_cell = {inv_cell[0], inv_cell[1], inv_cell[2], 0};
  p.grid_dims = {dims[0], dims[1], dims[2], int(grid.cell_count())};
  const Vec3d g = this->external_acceleration();
  p.gravity = {float(g[0]), float(g[1]), D == 3 ? float(g[2]) : 0.0f, 0};
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int k = 0; k < D; ++k) { lo[k] = Real(prm.domain_min[k]); hi[k] = Real(prm.domain_max[k]); }
  p.wall_lo = {lo[0], lo[1], lo[2], 0};
  p.wall_hi = {hi[0], hi[1], hi[2], 0};
  float period[3] = {0, 0, 0};
  for (int k = 0; k < D; ++k) period[k] = grid.period(k);
  p.period = {period[0], period[1], period[2], grid.any_periodic() ? 1.0f : 0.0f};
  {
    // Akinci 2013's constants as FluidWorld::add_surface_forces computes them.
    const double H = prm.support, pi = 3.14159265358979323846;
    const double c_norm = D == 3 ? 32.0 / (pi * std::pow(H, 9)) : 25280.0 / (627.0 * pi * std::pow(H, 8));
    const double a_norm = D == 3 ? 0.007 / std::pow(H, 3.25) : (13.0 / 1200.0) / std::pow(H, 2.25);
    p.surface = {Real(s.surface_tension), Real(s.adhesion), Real(c_norm), Real(a_norm)};
    p.surface_b = {Real(H), Real(std::pow(H, 6) / 64.0), Real(2 * prm.rho0), 0};
  }
  const Brush& brush = this->brush_;
  p.brush = {float(brush.center[0]), float(brush.center[1]), float(brush.center[2]), float(brush.radius)};
  p.brush_strength = float(brush.strength);
  kernel_constants<D>(s.kernel, prm.h, p);
  p.mass = Real(prm.mass);
  p.support2 = Real(prm.support * prm.support);
  p.eps = Real(prm.eta2);
  p.ach = Real(s.artificial_viscosity * prm.c0 * prm.h);
  p.nu = Real(s.viscosity);
  p.dmin = Real(0.25 * s.spacing);  // the CPU's kMinWallDistance (fluid_sums.cpp)
  p.inv_rho0 = Real(1.0 / prm.rho0);
  p.rho0 = Real(prm.rho0);
  p.tait_b = Real(prm.tait_b);
  p.tait_gamma = Real(s.tait_gamma);
  p.stiffness = Real(prm.stiffness);
  p.dt = Real(dt);
  p.kick_dt = Real(kick_dt);
  p.put_back_margin = Real(0.25 * s.spacing);
  p.fluid_count = glsl::uint(this->fluid_.size());
  p.boundary_count = glsl::uint(this->boundary_.size());
  p.obstacle_count = glsl::uint(this->obstacles_.size());
  p.flags = (s.eos == Eos::Linear ? RTSPH_F_LINEAR_EOS : 0u) |
            (s.clamp_negative_pressure ? RTSPH_F_CLAMP_NEGATIVE : 0u) | (brush.active ? RTSPH_F_BRUSH : 0u) |
            (s.surface_tension > 0 || s.adhesion > 0 ? RTSPH_F_SURFACE : 0u);
  glNamedBufferSubData(params_ubo_, 0, sizeof p, &p);
}

// Every SPH binding, again before each pass: the sort swaps buffers, and a renderer sharing the
// context may bind its own.
template <int D>
void GpuWorld<D>::bind_all() const {
  glBindBufferBase(GL_UNIFORM_BUFFER, RTSPH_U_PARAMS, params_ubo_);
  pos_.bind(RTSPH_B_POS);
  vel_.bind(RTSPH_B_VEL);
  acc_.bind(RTSPH_B_ACC);
  dens_.bind(RTSPH_B_DENS);
  id_.bind(RTSPH_B_ID);
  fluid_cells_.keys.bind(RTSPH_B_FKEY);
  fluid_cells_.start.bind(RTSPH_B_FSTART);
  bpos_.bind(RTSPH_B_BPOS);
  bvel_.bind(RTSPH_B_BVEL);
  bnormal_.bind(RTSPH_B_BNORMAL);
  blocal_.bind(RTSPH_B_BLOCAL);
  boundary_cells_.keys.bind(RTSPH_B_BKEY);
  boundary_cells_.start.bind(RTSPH_B_BSTART);
  bpress_.bind(RTSPH_B_BPRESS);
  obstacles_buf_.bind(RTSPH_B_OBSTACLES);
  stats_.bind(RTSPH_B_STATS);
}

template <int D>
void GpuWorld<D>::upload_fluid(std::size_t first, std::size_t count) {
  if (count == 0) return;
  if (first + count > capacity_) {
    // More particles than the emitters promised (a loaded checkpoint): grow, keeping the rest.
    sync_host();
    capacity_ = (first + count) * 2;
    for (Buffer* b : {&pos_, &vel_, &acc_, &dens_, &pos_alt_, &vel_alt_}) b->reserve(capacity_ * sizeof(vec4));
    for (Buffer* b : {&id_, &id_alt_}) b->reserve(capacity_ * 4);
    reserve_device_fields();
    count += first;
    first = 0;
  }
  const auto& f = this->fluid_;
  std::vector<vec4> x(count), v(count), a(count), d(count);
  for (std::size_t i = 0; i < count; ++i) {
    float xs[3] = {0, 0, 0}, vs[3] = {0, 0, 0}, as[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      xs[k] = f.x[k][first + i];
      vs[k] = f.v[k][first + i];
      as[k] = f.a[k][first + i];
    }
    x[i] = {xs[0], xs[1], xs[2], 0};
    v[i] = {vs[0], vs[1], vs[2], 0};
    a[i] = {as[0], as[1], as[2], 0};
    const float rho = f.rho[first + i];
    d[i] = {rho, f.p[first + i], 0, rho > 0 ? 1.0f / rho : 0.0f};
  }
  pos_.upload(x.data(), count * sizeof(vec4), first * sizeof(vec4));
  vel_.upload(v.data(), count * sizeof(vec4), first * sizeof(vec4));
  acc_.upload(a.data(), count * sizeof(vec4), first * sizeof(vec4));
  dens_.upload(d.data(), count * sizeof(vec4), first * sizeof(vec4));
  id_.upload(f.id.data() + first, count * 4, first * 4);
  if (transport()) {  // the host's ṽ − v: zero for new particles, a checkpoint's when loading
    tdv_.reserve(capacity_ * sizeof(vec4));
    std::vector<vec4> t(count, vec4{0, 0, 0, 0});
    for (std::size_t i = 0; i < count; ++i) {
      float ts[3] = {0, 0, 0};
      for (int k = 0; k < D; ++k)
        if (first + i < this->transport_dv_[k].size()) ts[k] = this->transport_dv_[k][first + i];
      t[i] = {ts[0], ts[1], ts[2], 0};
    }
    tdv_.upload(t.data(), count * sizeof(vec4), first * sizeof(vec4));
  }
  upload_device_fields(first, count);
}

template <int D>
void GpuWorld<D>::add_device_field(const DeviceField& f) {
  device_fields_.push_back(f);
  reserve_device_fields();
  upload_device_fields(0, this->fluid_.size());
}

template <int D>
void GpuWorld<D>::reserve_device_fields() {
  for (const DeviceField& f : device_fields_) {
    f.buffer->reserve(capacity_ * sizeof(vec4));
    if (f.sorted) f.alt->reserve(capacity_ * sizeof(vec4));
  }
}

template <int D>
void GpuWorld<D>::upload_device_fields(std::size_t first, std::size_t count) {
  if (count == 0) return;
  std::vector<std::array<float, 4>> t(count);
  for (const DeviceField& f : device_fields_) {
    for (std::size_t i = 0; i < count; ++i)
      for (int c = 0; c < 4; ++c) {
        const AlignedArray<Real>* h = f.host[c];
        t[i][c] = h && first + i < h->size() ? (*h)[first + i] : 0.0f;
      }
    f.buffer->upload(t.data(), count * sizeof(vec4), first * sizeof(vec4));
  }
}

template <int D>
void GpuWorld<D>::upload_boundary() {
  const auto& b = this->boundary_;
  const auto& ctx = this->ctx_;
  const std::size_t n = b.size();
  std::vector<vec4> x(n), v(n), nrm(n), loc(n);
  for (std::size_t i = 0; i < n; ++i) {
    float xs[3] = {0, 0, 0}, vs[3] = {0, 0, 0}, ns[3] = {0, 0, 0}, ls[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      xs[k] = b.x[k][i];
      vs[k] = b.v[k][i];
      ns[k] = ctx.wall_normal[k][i];
      ls[k] = b.local[k][i];
    }
    x[i] = {xs[0], xs[1], xs[2], b.psi[i]};
    v[i] = {vs[0], vs[1], vs[2], ctx.wall_depth[i]};
    nrm[i] = {ns[0], ns[1], ns[2], float(b.owner[i])};
    float face = 0;  // the body-frame normal move_boundary rotates (the CPU's choice of face)
    if (b.owner[i] >= 0) {
      const auto o = std::size_t(b.owner[i]);
      face = float(obstacle_surface_point(this->spec_.obstacles[o], Vec3d{{ls[0], ls[1], ls[2]}}, D,
                                          this->obstacle_skip_axes_[o]).face);
    }
    loc[i] = {ls[0], ls[1], ls[2], face};
  }
  for (Buffer* buf : {&bpos_, &bvel_, &bnormal_, &blocal_, &bpos_alt_, &bvel_alt_, &bnormal_alt_, &blocal_alt_})
    buf->reserve(n * sizeof(vec4));
  bpress_.reserve(n * 4);
  bpos_.upload(x.data(), n * sizeof(vec4));
  bvel_.upload(v.data(), n * sizeof(vec4));
  bnormal_.upload(nrm.data(), n * sizeof(vec4));
  blocal_.upload(loc.data(), n * sizeof(vec4));
}

template <int D>
void GpuWorld<D>::upload_obstacles() {
  std::vector<glsl::Obstacle> obs;
  for (const auto& st : this->obstacles_) {
    glsl::Obstacle o{};
    const Vec3d c = st.pose.center;
    Vec3d col[3];
    for (int k = 0; k < 3; ++k) {
      Vec3d e{};
      e[k] = 1;
      col[k] = st.pose.apply(e) - c;  // R e_k
    }
    o.r0 = {float(col[0][0]), float(col[1][0]), float(col[2][0]), 0};
    o.r1 = {float(col[0][1]), float(col[1][1]), float(col[2][1]), 0};
    o.r2 = {float(col[0][2]), float(col[1][2]), float(col[2][2]), 0};
    o.center = {float(c[0]), float(c[1]), float(c[2]), 0};
    o.velocity = {float(st.velocity[0]), float(st.velocity[1]), float(st.velocity[2]), 0};
    o.omega = {float(st.angular_velocity[0]), float(st.angular_velocity[1]), float(st.angular_velocity[2]), 0};
    obs.push_back(o);
  }
  obstacles_buf_.reserve(std::max<std::size_t>(1, obs.size()) * sizeof(glsl::Obstacle));
  obstacles_buf_.upload(obs.data(), obs.size() * sizeof(glsl::Obstacle));
}

template <int D>
void GpuWorld<D>::sort_boundary() {
  bind_all();  // keys.comp reads the grid from the parameter block
  const std::size_t n = this->boundary_.size();
  sorter_->sort(bpos_, n, this->ctx_.fluid_grid.cell_count(), boundary_cells_);
  sorter_->gather(boundary_cells_.order, n, {&bpos_, &bvel_, &bnormal_, &blocal_},
                  {&bpos_alt_, &bvel_alt_, &bnormal_alt_, &blocal_alt_});
  bpos_.swap(bpos_alt_);
  bvel_.swap(bvel_alt_);
  bnormal_.swap(bnormal_alt_);
  blocal_.swap(blocal_alt_);
}

template <int D>
void GpuWorld<D>::sort_particles(bool carry_density) {
  bind_all();  // keys.comp reads the grid from the parameter block
  const std::size_t n = this->fluid_.size();
  sorter_->sort(pos_, n, this->ctx_.fluid_grid.cell_count(), fluid_cells_);
  if (this->spec_.shifting > 0 || carry_density) {
    // Shifting (and PBF's surface forces) read the neighbours' ρ before the density pass: carry
    // the last step's along, as the CPU's sort does.
    dens_alt_.reserve(capacity_ * sizeof(vec4));
    sorter_->gather(fluid_cells_.order, n, {&pos_, &vel_, &dens_}, {&pos_alt_, &vel_alt_, &dens_alt_}, &id_, &id_alt_);
    dens_.swap(dens_alt_);
  } else {
    sorter_->gather(fluid_cells_.order, n, {&pos_, &vel_}, {&pos_alt_, &vel_alt_}, &id_, &id_alt_);
  }
  pos_.swap(pos_alt_);
  vel_.swap(vel_alt_);
  id_.swap(id_alt_);
  if (transport()) {  // ṽ − v travels with its particle to the force stage (transport_stress_gpu)
    tdv_alt_.reserve(capacity_ * sizeof(vec4));
    sorter_->gather(fluid_cells_.order, n, {&tdv_}, {&tdv_alt_});
    tdv_.swap(tdv_alt_);
  }
  for (const DeviceField& f : device_fields_) {  // a method's arrays that outlive a step
    if (!f.sorted) continue;
    sorter_->gather(fluid_cells_.order, n, {f.buffer}, {f.alt});
    f.buffer->swap(*f.alt);
  }
  if (this->boundary_moving_) sort_boundary();
}

template <int D>
void GpuWorld<D>::density_and_pressure() {
  bind_all();
  density_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::density_only() {
  bind_all();
  density_only_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::boundary_pressure() {
  bind_all();
  boundary_pressure_.dispatch(this->boundary_.size());
}

template <int D>
void GpuWorld<D>::forces() {
  bind_all();
  forces_.dispatch(this->fluid_.size());
}

// Two passes, as the CPU's: the normals (only with cohesion on), then the pair forces.
template <int D>
void GpuWorld<D>::surface_forces() {
  const auto& s = this->spec_;
  if (!(s.surface_tension > 0 || s.adhesion > 0)) return;
  normal_.reserve(capacity_ * sizeof(vec4));
  bind_all();
  normal_.bind(RTSPH_B_NORMAL);
  if (s.surface_tension > 0) surface_normal_.dispatch(this->fluid_.size());  // dispatch() ends in a barrier
  surface_forces_.dispatch(this->fluid_.size());
}

// Two passes, as the CPU's: every particle gathers its shift, then all move.
template <int D>
void GpuWorld<D>::shift_particles_gpu(double dt) {
  const auto& s = this->spec_;
  if (s.shifting <= 0 || dt <= 0 || this->fluid_.size() == 0) return;
  shift_delta_.reserve(capacity_ * sizeof(vec4));
  bind_all();
  shift_delta_.bind(RTSPH_B_DELTA);
  shift_.set("coeff", Real(s.shifting * this->prm_.h * dt));
  shift_.set("inv_w_dp", this->shifting_inv_w_dp());
  shift_.set("most", this->shifting_max_shift());
  shift_.dispatch(this->fluid_.size());  // dispatch() ends in a barrier
  shift_apply_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::kick(double dt) {
  bind_all();
  kick_.set("dt", Real(dt));
  kick_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::kick_drift() {
  bind_all();
  put_back_counter_.bind(RTSPH_B_REDUCE);
  if (transport()) {
    tdv_.bind(RTSPH_B_TDV);
    kick_drift_transport_.dispatch(this->fluid_.size());
  } else {
    kick_drift_.dispatch(this->fluid_.size());
  }
}

// p_b = solver.transport_velocity ρ0 c² with c = min(c0, max_signal_speed)
// (FluidWorld::transport_velocity_shift; only DFSPH caps the speed).
template <int D>
void GpuWorld<D>::transport_velocity_gpu(double dt_kick, double max_signal_speed) {
  if (!transport() || dt_kick <= 0 || this->fluid_.size() == 0) return;
  tdv_.reserve(capacity_ * sizeof(vec4));
  bind_all();
  tdv_.bind(RTSPH_B_TDV);
  const double c = std::min(this->prm_.c0, max_signal_speed);
  const double pb = this->spec_.transport_velocity * this->prm_.rho0 * c * c;
  transport_.set("coeff", Real(pb * dt_kick));
  transport_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::transport_stress_gpu() {
  if (!transport() || this->fluid_.size() == 0) return;
  tdv_.reserve(capacity_ * sizeof(vec4));
  bind_all();
  tdv_.bind(RTSPH_B_TDV);
  transport_stress_.dispatch(this->fluid_.size());
}

template <int D>
void GpuWorld<D>::advance_scene_gpu(double t_new, double dt) {
  if (this->update_obstacle_states(t_new, dt)) {
    upload_obstacles();
    bind_all();
    move_boundary_.dispatch(this->boundary_.size());
    this->stop_user_driven_obstacles();
  }
  const std::size_t before = this->fluid_.size();
  this->emit_particles(t_new);
  if (this->fluid_.size() > before) upload_fluid(before, this->fluid_.size() - before);
  write_params(params_dt_, params_kick_dt_);  // the counts may have changed
}

template class GpuWorld<2>;
template class GpuWorld<3>;

}  // namespace rtsph::gpu
