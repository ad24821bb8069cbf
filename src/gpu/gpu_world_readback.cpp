// GpuWorld's way back to the host: the GPU reductions (statistics, the time step's extremes),
// the particle readbacks for exports, checkpoints and CPU views, and a loaded state's upload.
// Each reads back a few bytes per step, or the particle arrays only when asked.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu/gpu_world.h"
#include "gpu/gpu_world_detail.h"
#include "gpu/layout.h"

namespace rtsph::gpu {

using namespace detail;
using glsl::SphParams;
using glsl::vec4;

// Reductions run in two passes in a fixed order (reduce.comp): per-workgroup partials, then
// one workgroup over them.
template <int D>
void GpuWorld<D>::reduce(int mode, unsigned slot) const {
  auto* self = const_cast<GpuWorld*>(this);  // scratch only: the state is not touched
  const std::size_t n = this->fluid_.size();
  const GLuint blocks = blocks_of(n);
  self->partials_.reserve((1 + std::size_t(blocks)) * sizeof(DVec4));
  bind_all();
  partials_.bind(RTSPH_B_REDUCE);
  if (mode == 2 || mode == 5) {
    // The potential energy and DFSPH's head are gravity's alone, as on the CPU (not the scene's
    // body force); the head in double, so that both backends choose the same Δt.
    const Vec3d g = this->spec_.gravity;
    const GLuint prog = reduce_[mode].id();
    if (mode == 2)
      glProgramUniform3f(prog, glGetUniformLocation(prog, "g_energy"), float(g[0]), float(g[1]),
                         D == 3 ? float(g[2]) : 0.0f);
    else
      glProgramUniform3d(prog, glGetUniformLocation(prog, "g_head"), g[0], g[1], D == 3 ? g[2] : 0.0);
  }
  reduce_[mode].set("n", GLuint(n));
  reduce_[mode].dispatch_groups(blocks);
  reduce_final_[mode].set("n", blocks);
  reduce_final_[mode].set("slot", GLuint(slot));
  reduce_final_[mode].dispatch_groups(1);
}

template <int D>
typename GpuWorld<D>::Extremes GpuWorld<D>::gpu_max_speed_and_acceleration() {
  reduce(0, kExtremes);
  DVec4 r{};
  stats_.download(&r, sizeof r, kExtremes * sizeof(DVec4));
  return {r.x, r.y};
}

template <int D>
void GpuWorld<D>::measure_density_error_gpu() { reduce(1, kDensity); }

template <int D>
void GpuWorld<D>::reduce_compression() const {
  if (this->fluid_.size() > 0) reduce(1, kSolve);
}

double sum_threshold(double tolerance, std::size_t count) {
  const double n = double(count);
  double t = tolerance * n;
  while (t / n > tolerance) t = std::nextafter(t, -HUGE_VAL);
  while (std::nextafter(t, HUGE_VAL) / n <= tolerance) t = std::nextafter(t, HUGE_VAL);
  return t;
}

// The first component of reduction `mode`'s result, read back (8 bytes), divided by `divide`.
template <int D>
double GpuWorld<D>::reduce_first(int mode, unsigned slot, double divide) {
  if (this->fluid_.size() == 0) return 0.0;
  reduce(mode, slot);
  double x = 0;
  stats_.download(&x, sizeof x, slot * sizeof(DVec4));
  return x / divide;
}

template <int D>
double GpuWorld<D>::gpu_head() {
  if (this->fluid_.size() == 0) return 0.0;
  reduce(5, kHead);
  DVec4 r{};
  stats_.download(&r, sizeof r, kHead * sizeof(DVec4));
  return r.x + r.y;  // max(-g.x) - min(-g.x)
}

template <int D>
void GpuWorld<D>::reduce_solve_error() const {
  if (this->fluid_.size() > 0) reduce(6, kResidual);
}

template <int D>
void GpuWorld<D>::run_gate(const ComputeProgram& gate, int mode, int least, int most,
                           double threshold) const {
  bind_all();
  gate.set("mode", GLint(mode));
  gate.set("least", GLint(least));
  gate.set("most", GLint(most));
  glProgramUniform1d(gate.id(), glGetUniformLocation(gate.id(), "threshold"), threshold);
  gate.dispatch_groups(1);
}

template <int D>
glsl::dvec4 GpuWorld<D>::read_stat(unsigned slot) const {
  glsl::dvec4 r{};
  stats_.download(&r, sizeof r, slot * sizeof(DVec4));
  return r;
}

template <int D>
double GpuWorld<D>::gpu_mean_density() { return reduce_first(7, kResidual, double(this->fluid_.size())); }

template <int D>
void GpuWorld<D>::measure_energies(SimStats& s) const {
  reduce(2, kEnergy);
  DVec4 r{};
  stats_.download(&r, sizeof r, kEnergy * sizeof(DVec4));
  s.kinetic_energy_j = r.x;
  s.potential_energy_j = r.y;
  s.max_speed = std::sqrt(r.z);
}

template <int D>
std::optional<DeviceParticles> GpuWorld<D>::device_particles() const {
  DeviceParticles d;
  d.position = pos_.id();
  d.velocity = vel_.id();
  d.density = dens_.id();
  d.count = this->fluid_.size();
  d.dim = D;
  if (d.count > 0) {
    reduce(3, kRanges);
    reduce(4, kRanges2);
    DVec4 r[2]{};
    stats_.download(r, sizeof r, kRanges * sizeof(DVec4));
    d.max_speed = float(std::sqrt(r[0].x));
    d.density_max = float(r[0].y);
    d.density_min = float(-r[0].z);
    d.pressure_max = float(r[0].w);
    d.pressure_min = float(-r[1].x);
  }
  return d;
}

template <int D>
std::optional<HealthFacts> GpuWorld<D>::health_facts() const {
  // Nothing stepped since the host copies were made: they answer exactly.
  if (loading_ || scalars_fresh_) return std::nullopt;
  DVec4 r{};
  stats_.download(&r, sizeof r, kDensity * sizeof(DVec4));
  HealthFacts h;
  h.non_finite = r.z > 0 || !std::isfinite(r.x);
  h.max_density = this->prm_.rho0 * (1.0 + r.x);
  return h;
}

template <int D>
void GpuWorld<D>::sync_scalars() const {
  if (scalars_fresh_ || loading_) return;
  auto* self = const_cast<GpuWorld*>(this);
  DVec4 r{};
  stats_.download(&r, sizeof r, kDensity * sizeof(DVec4));
  const std::size_t n = this->fluid_.size();
  self->density_error_ = r.x;
  self->mean_density_error_ = n ? r.y / double(n) : 0.0;
  self->max_density_error_ = r.w;
  std::uint32_t count = 0;
  put_back_counter_.download(&count, 4);
  self->put_back_ = put_back_base_ + count;
  scalars_fresh_ = true;
}

template <int D>
void GpuWorld<D>::sync_host() const {
  if (host_fresh_ || loading_) return;
  auto* self = const_cast<GpuWorld*>(this);
  auto& f = self->fluid_;
  const std::size_t n = f.size();
  std::vector<vec4> x(n), v(n), a(n), d(n);
  pos_.download(x.data(), n * sizeof(vec4));
  vel_.download(v.data(), n * sizeof(vec4));
  acc_.download(a.data(), n * sizeof(vec4));
  dens_.download(d.data(), n * sizeof(vec4));
  id_.download(f.id.data(), n * 4);
  for (std::size_t i = 0; i < n; ++i) {
    const float xs[3] = {x[i].x, x[i].y, x[i].z}, vs[3] = {v[i].x, v[i].y, v[i].z},
                as[3] = {a[i].x, a[i].y, a[i].z};
    for (int k = 0; k < D; ++k) {
      f.x[k][i] = xs[k];
      f.v[k][i] = vs[k];
      f.a[k][i] = as[k];
    }
    f.rho[i] = d[i].x;
    f.p[i] = d[i].y;
  }
  if (transport()) {  // ṽ − v, a saved method field
    std::vector<vec4> t(n);
    tdv_.download(t.data(), n * sizeof(vec4));
    for (int k = 0; k < D; ++k) self->transport_dv_[k].resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const float ts[3] = {t[i].x, t[i].y, t[i].z};
      for (int k = 0; k < D; ++k) self->transport_dv_[k][i] = ts[k];
    }
  }
  download_device_fields();
  sync_boundary_host();
  host_fresh_ = true;
}

template <int D>
void GpuWorld<D>::download_device_fields() const {
  const std::size_t n = this->fluid_.size();
  std::vector<std::array<float, 4>> t(n);
  for (const DeviceField& f : device_fields_) {
    f.buffer->download(t.data(), n * sizeof(vec4));
    for (int c = 0; c < 4; ++c) {
      AlignedArray<Real>* h = f.host[c];
      if (!h) continue;
      h->resize(n);
      for (std::size_t i = 0; i < n; ++i) (*h)[i] = t[i][c];
    }
  }
}

template <int D>
void GpuWorld<D>::sync_boundary_host() const {
  if (boundary_fresh_ || loading_) return;
  auto* self = const_cast<GpuWorld*>(this);
  auto& b = self->boundary_;
  auto& ctx = self->ctx_;
  const std::size_t nb = b.size();
  std::vector<vec4> bx(nb), bv(nb), bn(nb), bl(nb);
  bpos_.download(bx.data(), nb * sizeof(vec4));
  bvel_.download(bv.data(), nb * sizeof(vec4));
  bnormal_.download(bn.data(), nb * sizeof(vec4));
  blocal_.download(bl.data(), nb * sizeof(vec4));
  for (std::size_t i = 0; i < nb; ++i) {
    const float xs[3] = {bx[i].x, bx[i].y, bx[i].z}, vs[3] = {bv[i].x, bv[i].y, bv[i].z},
                ns[3] = {bn[i].x, bn[i].y, bn[i].z}, ls[3] = {bl[i].x, bl[i].y, bl[i].z};
    for (int k = 0; k < D; ++k) {
      b.x[k][i] = xs[k];
      b.v[k][i] = vs[k];
      b.local[k][i] = ls[k];
      ctx.wall_normal[k][i] = ns[k];
    }
    b.psi[i] = bx[i].w;
    ctx.wall_depth[i] = bv[i].w;
    b.owner[i] = std::int32_t(bn[i].w);
  }
  boundary_fresh_ = true;
}

template <int D>
ParticleView GpuWorld<D>::fluid() const {
  sync_host();
  return FluidWorld<D>::fluid();
}

template <int D>
BoundaryView GpuWorld<D>::boundary() const {
  sync_boundary_host();  // the walls and obstacles alone: drawing needs no fluid read-back
  return FluidWorld<D>::boundary();
}

template <int D>
SimStats GpuWorld<D>::stats() const {
  sync_scalars();
  return FluidWorld<D>::stats();
}

template <int D>
void GpuWorld<D>::prepare_state(std::size_t fluid_count) {
  loading_ = true;
  FluidWorld<D>::prepare_state(fluid_count);
}

template <int D>
std::vector<StateField> GpuWorld<D>::state_fields() {
  sync_host();
  sync_scalars();
  return FluidWorld<D>::state_fields();
}

template <int D>
void GpuWorld<D>::state_loaded() {
  FluidWorld<D>::state_loaded();  // re-sorts the boundary and rebuilds the wall geometry
  loading_ = false;
  const std::size_t n = this->fluid_.size();
  if (n > capacity_) {
    capacity_ = n + std::size_t(count_particles(this->spec_).emitted_max);
    for (Buffer* b : {&pos_, &vel_, &acc_, &dens_, &pos_alt_, &vel_alt_}) b->reserve(capacity_ * sizeof(vec4));
    for (Buffer* b : {&id_, &id_alt_}) b->reserve(capacity_ * 4);
    reserve_device_fields();
  }
  write_params(this->dt_, 0);
  upload_fluid(0, n);
  upload_boundary();
  upload_obstacles();
  sort_boundary();  // already in cell order: the stable sort keeps it, and builds the cell starts
  const DVec4 density{this->density_error_, this->mean_density_error_ * double(n), 0, this->max_density_error_};
  stats_.upload(&density, sizeof density, kDensity * sizeof(DVec4));
  put_back_base_ = this->put_back_;
  put_back_counter_.fill_zero();
  host_fresh_ = scalars_fresh_ = boundary_fresh_ = true;
}

template <int D>
void GpuWorld<D>::overwrite_fluid(const float* const* x, const float* const* v) {
  sync_host();
  sync_scalars();
  FluidWorld<D>::overwrite_fluid(x, v);  // with new positions this ends in state_loaded()
  if (!x) upload_fluid(0, this->fluid_.size());
  host_fresh_ = true;
}

#define RTSPH_INSTANTIATE(D)                                                             \
  template void GpuWorld<D>::reduce(int, unsigned) const;                                \
  template GpuWorld<D>::Extremes GpuWorld<D>::gpu_max_speed_and_acceleration();         \
  template void GpuWorld<D>::measure_density_error_gpu();                                \
  template void GpuWorld<D>::reduce_compression() const;                                   \
  template void GpuWorld<D>::run_gate(const ComputeProgram&, int, int, int, double) const;                                   \
  template double GpuWorld<D>::gpu_head();                                               \
  template double GpuWorld<D>::reduce_first(int, unsigned, double);                      \
  template void GpuWorld<D>::reduce_solve_error() const;                                 \
  template glsl::dvec4 GpuWorld<D>::read_stat(unsigned) const;                           \
  template double GpuWorld<D>::gpu_mean_density();                                       \
  template void GpuWorld<D>::measure_energies(SimStats&) const;                          \
  template std::optional<DeviceParticles> GpuWorld<D>::device_particles() const;         \
  template std::optional<HealthFacts> GpuWorld<D>::health_facts() const;                 \
  template void GpuWorld<D>::sync_scalars() const;                                       \
  template void GpuWorld<D>::sync_host() const;                                          \
  template void GpuWorld<D>::download_device_fields() const;                             \
  template void GpuWorld<D>::sync_boundary_host() const;                                 \
  template ParticleView GpuWorld<D>::fluid() const;                                      \
  template BoundaryView GpuWorld<D>::boundary() const;                                   \
  template SimStats GpuWorld<D>::stats() const;                                          \
  template void GpuWorld<D>::prepare_state(std::size_t);                                 \
  template std::vector<StateField> GpuWorld<D>::state_fields();                          \
  template void GpuWorld<D>::state_loaded();                                             \
  template void GpuWorld<D>::overwrite_fluid(const float* const*, const float* const*);
RTSPH_INSTANTIATE(2)
RTSPH_INSTANTIATE(3)
#undef RTSPH_INSTANTIATE

}  // namespace rtsph::gpu
