// Read access, statistics and checkpoint state of the shared fluid world.
#include <algorithm>
#include <cstring>

#include "solvers/fluid_world.h"

namespace rtsph {

template <int D>
ParticleView FluidWorld<D>::fluid() const {
  ParticleView v;
  v.dim = D;
  v.count = fluid_.size();
  for (int k = 0; k < D; ++k) { v.x[k] = fluid_.x[k].data(); v.v[k] = fluid_.v[k].data(); }
  v.density = fluid_.rho.data();
  v.pressure = fluid_.p.data();
  v.id = fluid_.id.data();
  return v;
}

template <int D>
BoundaryView FluidWorld<D>::boundary() const {
  BoundaryView v;
  v.dim = D;
  v.count = boundary_.size();
  for (int k = 0; k < D; ++k) v.x[k] = boundary_.x[k].data();
  v.owner = boundary_.owner.data();
  return v;
}

template <int D>
void FluidWorld<D>::measure_energies(SimStats& s) const {
  struct Energy {
    double ke = 0, pe = 0, v2max = 0;
    Energy& operator+=(const Energy& o) {
      ke += o.ke; pe += o.pe; v2max = std::max(v2max, o.v2max);
      return *this;
    }
  };
  const Energy e = pool_.parallel_reduce(fluid_.size(), Energy{}, [&](std::size_t b, std::size_t end) {
    Energy r;
    for (std::size_t i = b; i < end; ++i) {
      double v2 = 0, gx = 0;
      for (int k = 0; k < D; ++k) {
        v2 += double(fluid_.v[k][i]) * fluid_.v[k][i];
        gx += spec_.gravity[k] * fluid_.x[k][i];
      }
      r.ke += 0.5 * prm_.mass * v2;
      r.pe -= prm_.mass * gx;
      r.v2max = std::max(r.v2max, v2);
    }
    return r;
  });
  s.kinetic_energy_j = e.ke;
  s.potential_energy_j = e.pe;
  s.max_speed = std::sqrt(e.v2max);
}

template <int D>
SimStats FluidWorld<D>::stats() const {
  SimStats s;
  s.fluid_particles = fluid_.size();
  s.boundary_particles = boundary_.size();
  s.steps = steps_;
  s.time_s = time_;
  s.dt_s = dt_;
  s.c0 = prm_.c0;
  s.h = prm_.h;
  s.method = spec_.method;
  s.density_error = density_error_;
  s.mean_density_error = mean_density_error_;
  s.max_density_error = max_density_error_;
  s.particles_put_back = put_back_;
  measure_energies(s);
  s.bytes = fluid_.bytes() + boundary_.bytes() + ctx_.bytes();
  for (const auto& f : method_fields_) s.bytes += f.array->bytes();
  add_method_stats(s);
  return s;
}

// Checkpoint layout: every array and scalar step() reads. Boundary particles are included
// because moving obstacles change them; grids and scratch are rebuilt by state_loaded().
template <int D>
void FluidWorld<D>::prepare_state(std::size_t fluid_count) {
  fluid_.resize(fluid_count);
  for (auto& f : method_fields_) f.array->resize(fluid_count);
}

template <int D>
std::vector<StateField> FluidWorld<D>::state_fields() {
  std::vector<StateField> f;
  auto arr = [&](const std::string& name, auto& a) {
    f.push_back({name, static_cast<void*>(a.data()), a.size() * sizeof(a[0])});
  };
  auto scalar = [&](const std::string& name, auto& v) {
    f.push_back({name, static_cast<void*>(&v), sizeof(v)});
  };
  const char* axis[3] = {"x", "y", "z"};
  for (int k = 0; k < D; ++k) {
    arr(std::string("fluid.x.") + axis[k], fluid_.x[k]);
    arr(std::string("fluid.v.") + axis[k], fluid_.v[k]);
    arr(std::string("fluid.a.") + axis[k], fluid_.a[k]);
    arr(std::string("boundary.x.") + axis[k], boundary_.x[k]);
    arr(std::string("boundary.v.") + axis[k], boundary_.v[k]);
    arr(std::string("boundary.local.") + axis[k], boundary_.local[k]);
  }
  arr("fluid.rho", fluid_.rho);
  arr("fluid.p", fluid_.p);
  arr("fluid.id", fluid_.id);
  arr("boundary.psi", boundary_.psi);
  arr("boundary.owner", boundary_.owner);
  scalar("time", time_);
  scalar("dt", dt_);
  scalar("steps", steps_);
  scalar("put_back", put_back_);
  scalar("next_id", next_id_);
  scalar("density_error", density_error_);
  scalar("max_density_error", max_density_error_);
  scalar("mean_density_error", mean_density_error_);
  scalar("boundary_moving", boundary_moving_);
  f.push_back({"emitters", emitters_.data(), emitters_.size() * sizeof(EmitterState)});
  f.push_back({"obstacles", obstacles_.data(), obstacles_.size() * sizeof(ObstacleState)});
  for (auto& m : method_fields_)
    if (m.saved) arr("method." + m.name, *m.array);
  add_method_scalars(f);
  return f;
}

template <int D>
void FluidWorld<D>::state_loaded() {
  // Rebuild the grids for the loaded order without reordering: the arrays were saved sorted,
  // and resorting here could permute particles within a cell differently than a straight run.
  // The wall samples are sorted as at start (the stable sort leaves sorted samples in place).
  sort_boundary_by_cell();
  // The fluid was saved in cell order (DFSPH and WCSPH save right after a sort and only change
  // velocities after it), and the counting sort is stable, so this rebuilds the same cell
  // ranges without moving a particle; DFSPH's first pair loop of the next step reads them.
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = fluid_.x[k].data();
  ctx_.fluid_grid.build(xs, fluid_.size(), pool_);
  // The lists follow from the same positions and order, so they match the straight run's too.
  if (keep_lists_) build_neighbour_lists();
}

template <int D>
void FluidWorld<D>::overwrite_fluid(const float* const* x, const float* const* v) {
  const std::size_t n = fluid_.size();
  for (int k = 0; k < D; ++k) {
    if (x) std::copy_n(x[k], n, fluid_.x[k].data());
    if (v) std::copy_n(v[k], n, fluid_.v[k].data());
  }
  if (!x) return;
  if (!sort_after_edit()) {
    state_loaded();
    return;
  }
  // Moved particles must sit in cell order for the grid's ranges. The sort leaves a, ρ and p in
  // the old order (a step recomputes them right after sorting), but the next step's first kick
  // reads a, so those follow their particles here.
  sort_fluid_by_cell();
  const uint32_t* order = ctx_.fluid_grid.order();
  auto follow = [&](AlignedArray<Real>& arr) {
    ctx_.tmp.resize(n);
    for (std::size_t i = 0; i < n; ++i) ctx_.tmp[i] = arr[order[i]];
    arr.swap(ctx_.tmp);
  };
  for (int k = 0; k < D; ++k) follow(fluid_.a[k]);
  follow(fluid_.rho);
  follow(fluid_.p);
  state_loaded();  // the method's override too: DFSPH's factors and caches
}

template <int D>
Pose FluidWorld<D>::obstacle_transform(int index) const {
  if (index < 0 || index >= int(obstacles_.size())) return {};
  return obstacles_[index].pose;
}

#define RTSPH_INSTANTIATE(D)                                            \
  template ParticleView FluidWorld<D>::fluid() const;                        \
  template BoundaryView FluidWorld<D>::boundary() const;                     \
  template SimStats FluidWorld<D>::stats() const;                            \
  template void FluidWorld<D>::measure_energies(SimStats&) const;            \
  template void FluidWorld<D>::prepare_state(std::size_t);                   \
  template std::vector<StateField> FluidWorld<D>::state_fields();            \
  template void FluidWorld<D>::state_loaded();                               \
  template void FluidWorld<D>::overwrite_fluid(const float* const*, const float* const*); \
  template Pose FluidWorld<D>::obstacle_transform(int) const;
RTSPH_INSTANTIATE(2)
RTSPH_INSTANTIATE(3)
#undef RTSPH_INSTANTIATE

}  // namespace rtsph
