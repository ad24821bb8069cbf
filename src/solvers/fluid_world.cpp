#include "solvers/fluid_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/timer.h"

namespace rtsph {

template <int D>
FluidWorld<D>::FluidWorld(const SimSpec& spec, int threads) : spec_(spec), pool_(threads) {
  if (spec.dimension != D) throw std::invalid_argument("dimension mismatch");
  resolve_parameters();
  const auto fluid = sample_fluid(spec_);
  const auto counts = count_particles(spec_);
  fluid_.reserve(fluid.size() + std::size_t(counts.emitted_max));
  for (const auto& p : fluid) {
    Vec3d v{};
    for (const auto& b : spec_.fluid_blocks) {
      bool inside = true;
      for (int k = 0; k < D; ++k) inside &= p[k] >= b.min[k] && p[k] <= b.max[k];
      if (inside) { v = b.velocity; break; }
    }
    add_fluid_particle(truncate<D>(p), truncate<D>(v));
  }
  for (const auto& e : spec_.emitters) emitters_.push_back({e.start_s, 0.0});
  for (const auto& o : spec_.obstacles) {
    ObstacleState st;
    st.pose = obstacle_pose(o, 0.0);
    st.velocity = o.motion == MotionKind::Velocity ? o.velocity : Vec3d{};
    st.angular_velocity = o.motion == MotionKind::Velocity ? o.angular_velocity : Vec3d{};
    obstacles_.push_back(st);
    obstacle_skip_axes_.push_back(obstacle_seamless_axes(spec_, o));
    boundary_moving_ |= o.motion != MotionKind::Static;
  }
  build_boundary();
  sort_fluid_by_cell();
  // The transport-velocity formulation's ṽ − v travels with its particle from the step that
  // moved it to the force sum after (transport_velocity.cpp), so it is sorted and saved.
  if (spec_.transport_velocity > 0) {
    const char* axis[3] = {"x", "y", "z"};
    for (int k = 0; k < D; ++k)  // zero at the start (resize zero-fills)
      add_method_field({std::string("transport_dv.") + axis[k], &transport_dv_[k], true, true});
  }
}

// A block at rest under gravity g is in equilibrium when p(d) = ρ0 g d at depth d below its top
// (ρ0 rather than ρ(d) in the weight: the difference is the compression squared, ~1e-5). The
// lattice is sampled at ρ0, so a weakly compressible fluid would first settle, and that sets
// the whole tank sloshing (still water at c0 = 10·√(2gH): rms 0.07 m/s after 0.25 s). Instead
// each layer is moved down so the lattice's local spacing along gravity is s·ρ0/ρ(d), ρ(d) from
// inverting the equation of state: Tait ρ0 (1 + ρ0 g d / B)^(1/γ), linear ρ0 + ρ0 g d / k. The
// block's bottom stays in place; a point at height z goes to z_b + ∫_{z_b}^{z} ρ0/ρ(z_t − ζ) dζ.
template <int D>
void FluidWorld<D>::compress_hydrostatically() {
  const Vec3d accel = spec_.gravity;
  double g = 0;
  for (int k = 0; k < D; ++k) g += accel[k] * accel[k];
  g = std::sqrt(g);
  if (!spec_.hydrostatic_start || g == 0 || fluid_.size() == 0) return;
  double up[D];
  for (int k = 0; k < D; ++k) up[k] = -accel[k] / g;
  const double rho0 = prm_.rho0, B = prm_.tait_b, k_lin = prm_.stiffness, gamma = spec_.tait_gamma;
  const bool tait = spec_.eos == Eos::Tait;
  auto inv_ratio = [&](double depth) {  // ρ0 / ρ(depth)
    const double p = rho0 * g * std::max(depth, 0.0);
    return tait ? std::pow(1.0 + p / B, -1.0 / gamma) : rho0 / (rho0 + p / k_lin);
  };
  const auto& blocks = spec_.fluid_blocks;
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      double x[D], z = 0;
      for (int k = 0; k < D; ++k) { x[k] = fluid_.x[k][i]; z += x[k] * up[k]; }
      for (const auto& blk : blocks) {
        bool inside = true;
        for (int k = 0; k < D; ++k) inside &= x[k] >= blk.min[k] && x[k] <= blk.max[k];
        if (!inside) continue;
        double zb = 0, zt = 0;  // the box's lowest and highest corner along `up`
        for (int k = 0; k < D; ++k) {
          zb += std::min(blk.min[k] * up[k], blk.max[k] * up[k]);
          zt += std::max(blk.min[k] * up[k], blk.max[k] * up[k]);
        }
        constexpr int kIntervals = 64;  // Simpson's rule; the integrand is smooth and near 1
        const double hstep = (z - zb) / kIntervals;
        double sum = inv_ratio(zt - zb) + inv_ratio(zt - z);
        for (int q = 1; q < kIntervals; ++q) sum += (q % 2 ? 4.0 : 2.0) * inv_ratio(zt - (zb + q * hstep));
        const double dz = zb + sum * hstep / 3.0 - z;
        for (int k = 0; k < D; ++k) fluid_.x[k][i] = Real(x[k] + dz * up[k]);
        break;
      }
    }
  });
}

template <int D>
void FluidWorld<D>::resolve_parameters() {
  const SimSpec& s = spec_;
  prm_.h = s.smoothing_ratio * s.spacing;
  prm_.support = support_ratio(s.kernel) * prm_.h;
  // η² keeps Morris's and Monaghan's 1/(r² + η²) finite as a pair closes. Both papers write
  // 0.01h², for h of about a spacing; what it guards is the nearest pairs, a spacing apart
  // whatever h, so it is 0.01 s² here (the same at the default h = s). Scaled with h it took 1.5%
  // off the viscous term's lattice sum at Wendland C2, h = 1.5 s (0.985 of the Laplacian of a
  // shear profile, 0.997 without η), and Poiseuille flow ran 2.1-2.5% fast (docs/validation.md).
  prm_.eta2 = 0.01 * s.spacing * s.spacing;
  prm_.rho0 = s.rest_density;
  prm_.domain_min = s.domain_min;
  prm_.domain_max = s.domain_max;
  // Mass so that a particle inside the initial lattice sits exactly at ρ0: m = ρ0 / Σ_j W(x_ij).
  const double spacing = s.spacing;
  const int reach = int(std::ceil(prm_.support / spacing));
  double lattice_sum = 0;
  with_kernel<D>(s.kernel, prm_.h, [&](const auto& K) {
    for (int z = (D == 3 ? -reach : 0); z <= (D == 3 ? reach : 0); ++z)
      for (int y = -reach; y <= reach; ++y)
        for (int x = -reach; x <= reach; ++x) {
          const double r2 = (double(x) * x + double(y) * y + double(z) * z) * spacing * spacing;
          lattice_sum += double(K.value(float(r2)));
        }
  });
  prm_.mass = prm_.rho0 / lattice_sum;
  // Speed of sound: ten times the fastest expected flow keeps density errors near 1%
  // (Monaghan 1994); the fastest flow is a fall through the fluid height, a block's initial
  // velocity or an emitter's jet.
  double vmax = 0;
  const double g = norm(s.gravity);
  for (const auto& b : s.fluid_blocks) {
    double height = 0;
    if (g > 0) {
      const Vec3d gh = s.gravity / g;
      for (int k = 0; k < D; ++k) height += std::abs(gh[k]) * (b.max[k] - b.min[k]);
    }
    vmax = std::max({vmax, std::sqrt(2 * g * height), norm(b.velocity)});
  }
  for (const auto& e : s.emitters) vmax = std::max(vmax, e.speed + std::sqrt(2 * g * (s.domain_max[1] - s.domain_min[1])));
  for (const auto& o : s.obstacles) vmax = std::max(vmax, norm(o.velocity));
  if (vmax <= 0) vmax = 1.0;
  prm_.c0 = s.speed_of_sound > 0 ? s.speed_of_sound : 10.0 * vmax;
  if (s.eos == Eos::Linear) {
    // p = k(ρ - ρ0) has dp/dρ = k, so its sound speed is √k.
    prm_.stiffness = s.stiffness > 0 ? s.stiffness : prm_.c0 * prm_.c0;
    prm_.c0 = std::sqrt(prm_.stiffness);
  }
  prm_.tait_b = prm_.rho0 * prm_.c0 * prm_.c0 / s.tait_gamma;
}

template <int D>
void FluidWorld<D>::add_fluid_particle(const Vec<D>& x, const Vec<D>& v) {
  const std::size_t i = fluid_.size();
  fluid_.resize(i + 1);
  fluid_.set_pos(i, x);
  fluid_.set_vel(i, v);
  const Vec3d g = external_acceleration();
  for (int k = 0; k < D; ++k) fluid_.a[k][i] = Real(g[k]);
  fluid_.rho[i] = Real(prm_.rho0);
  fluid_.p[i] = 0;
  fluid_.id[i] = next_id_++;
  for (auto& f : method_fields_) f.array->resize(i + 1);
}

template <int D>
typename FluidWorld<D>::Extremes FluidWorld<D>::max_speed_and_acceleration() const {
  struct Max {
    double v2 = 0, a2 = 0;
    Max& operator+=(const Max& o) { v2 = std::max(v2, o.v2); a2 = std::max(a2, o.a2); return *this; }
  };
  const Max m = pool_.parallel_reduce(fluid_.size(), Max{}, [&](std::size_t b, std::size_t e) {
    Max r;
    for (std::size_t i = b; i < e; ++i) {
      double v2 = 0, a2 = 0;
      for (int k = 0; k < D; ++k) {
        v2 += double(fluid_.v[k][i]) * fluid_.v[k][i];
        a2 += double(fluid_.a[k][i]) * fluid_.a[k][i];
      }
      r.v2 = std::max(r.v2, v2);
      r.a2 = std::max(r.a2, a2);
    }
    return r;
  });
  return {m.v2, m.a2};
}

template <int D>
double FluidWorld<D>::lattice_gradient_sum() const {
  const double s = spec_.spacing;
  const int reach = int(std::ceil(prm_.support / s));
  double sum = 0;
  with_kernel<D>(spec_.kernel, prm_.h, [&](const auto& K) {
    for (int z = (D == 3 ? -reach : 0); z <= (D == 3 ? reach : 0); ++z)
      for (int y = -reach; y <= reach; ++y)
        for (int x = -reach; x <= reach; ++x) {
          const double r2 = (double(x) * x + double(y) * y + double(z) * z) * s * s;
          const double G = K.grad_factor(float(r2));
          sum += G * G * r2;
        }
  });
  return sum * prm_.mass * prm_.mass;
}

template <int D>
double FluidWorld<D>::viscous_dt_limit() const {
  // Artificial viscosity acts like ν = α c0 h / (2(D+2)) (Monaghan 2005).
  const double h = prm_.h;
  const double nu = std::max(spec_.viscosity,
                             spec_.artificial_viscosity * prm_.c0 * h / (2.0 * (D + 2)));
  return nu > 0 ? 0.125 * h * h / nu : 1e30;
}

template <int D>
void FluidWorld<D>::kick(double dt) {
  const Real hdt = Real(dt);
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k) {
      Real* v = fluid_.v[k].data();
      const Real* a = fluid_.a[k].data();
      for (std::size_t i = b; i < e; ++i) v[i] += a[i] * hdt;
    }
  });
}

template <int D>
void FluidWorld<D>::drift(double dt) {
  const Real fdt = Real(dt);
  const WallPlanes walls = wall_planes();
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k) {
      Real* x = fluid_.x[k].data();
      Real* v = fluid_.v[k].data();
      const Real lo = walls.lo[k], hi = walls.hi[k];
      const Real period = ctx_.fluid_grid.period(k);
      if (period > 0) {
        // Periodic: leaving through one face is entering through the other.
        const Real start = Real(prm_.domain_min[k]), end = Real(prm_.domain_max[k]);
        for (std::size_t i = b; i < e; ++i) {
          const Real xn = x[i] + v[i] * fdt;
          x[i] = xn >= end ? xn - period : xn < start ? xn + period : xn;
        }
        continue;
      }
      for (std::size_t i = b; i < e; ++i) {
        // Contact with a wall plane (a NaN fails both tests and is left to put_back_escaped).
        const Real xn = x[i] + v[i] * fdt, vi = v[i];
        const bool below = xn < lo, above = xn > hi;
        x[i] = below ? lo : above ? hi : xn;
        v[i] = below ? std::max(vi, Real(0)) : above ? std::min(vi, Real(0)) : vi;
      }
    }
  });
}

template <int D>
void FluidWorld<D>::put_back_escaped() {
  // A particle that crossed a container wall is returned a quarter spacing inside and loses
  // its outward velocity. NaN positions fail both comparisons and are put back too. The walls
  // hold by themselves (drift's contact, PBF's collision response), so this is a diagnostic:
  // any count here is a particle the boundary handling let through.
  if (spec_.open) return;  // open space: nothing to escape from
  const Real margin = Real(0.25 * spec_.spacing);
  Real lo[D], hi[D];
  for (int k = 0; k < D; ++k) {
    lo[k] = Real(prm_.domain_min[k]);
    hi[k] = Real(prm_.domain_max[k]);
  }
  put_back_ += pool_.parallel_reduce(fluid_.size(), std::uint64_t(0), [&](std::size_t b, std::size_t e) {
    // Almost always nothing has escaped: one read-only pass that vectorises finds out, and
    // only a chunk with a particle to fix runs the per-particle loop below.
    bool any = false;
    for (int k = 0; k < D; ++k) {
      const Real* x = fluid_.x[k].data();
      const Real* v = fluid_.v[k].data();
      // A periodic axis keeps [lo, hi): its last float inside is the one below hi.
      const Real l = lo[k], vmax = std::numeric_limits<Real>::max(),
                 h = ctx_.fluid_grid.period(k) > 0 ? std::nextafter(hi[k], lo[k]) : hi[k];
      int bad = 0;
      for (std::size_t i = b; i < e; ++i)  // comparisons are false for NaN: "not inside"
        bad |= int(!((x[i] >= l) & (x[i] <= h))) | int(!(std::abs(v[i]) <= vmax));
      any = any || bad != 0;
    }
    if (!any) return std::uint64_t(0);
    std::uint64_t count = 0;
    for (std::size_t i = b; i < e; ++i) {
      bool moved = false;
      for (int k = 0; k < D; ++k) {
        Real& x = fluid_.x[k][i];
        Real& v = fluid_.v[k][i];
        const Real period = ctx_.fluid_grid.period(k);
        if (period > 0 && std::isfinite(x)) {  // a correction's overshoot past the seam wraps
          x = x >= hi[k] ? x - period : x < lo[k] ? x + period : x;
          if (!std::isfinite(v)) { v = 0; moved = true; }
          continue;
        }
        if (!(x >= lo[k])) { x = lo[k] + margin; v = std::max(v, Real(0)); moved = true; }
        else if (!(x <= hi[k])) { x = hi[k] - margin; v = std::min(v, Real(0)); moved = true; }
        if (!std::isfinite(v)) v = 0;
      }
      count += moved;
    }
    return count;
  });
}

template <int D>
void FluidWorld<D>::update_neighbours() {
  ScopedTimer timer(times_.neighbours_s);
  sort_fluid_by_cell();  // counting sort, arrays reordered by cell (Ihmsen et al. 2011)
  if (boundary_moving_) sort_boundary_by_cell();
  if (keep_lists_) build_neighbour_lists();
}

template <int D>
Real FluidWorld<D>::follow_fluid(Real cell) {
  struct Box {
    Real lo[D], hi[D];
    Box() {
      for (int k = 0; k < D; ++k) { lo[k] = std::numeric_limits<Real>::max(); hi[k] = -lo[k]; }
    }
    Box& operator+=(const Box& o) {
      for (int k = 0; k < D; ++k) { lo[k] = std::min(lo[k], o.lo[k]); hi[k] = std::max(hi[k], o.hi[k]); }
      return *this;
    }
  };
  const Box box = pool_.parallel_reduce(fluid_.size(), Box{}, [&](std::size_t b, std::size_t e) {
    Box r;
    for (std::size_t i = b; i < e; ++i)
      for (int k = 0; k < D; ++k) {
        const Real x = fluid_.x[k][i];
        if (!std::isfinite(x)) continue;  // the instability guard reports it
        r.lo[k] = std::min(r.lo[k], x);
        r.hi[k] = std::max(r.hi[k], x);
      }
    return r;
  });
  Vec<D> lo, hi;
  double cells = 1;
  for (int k = 0; k < D; ++k) {
    if (!(box.lo[k] <= box.hi[k])) { lo[k] = 0; hi[k] = cell; continue; }
    lo[k] = box.lo[k] - cell;
    hi[k] = box.hi[k] + cell;
    cells *= std::max(1.0, double(hi[k] - lo[k]) / double(cell));
  }
  // A few particles far from the rest (a tidal tail) would make a grid of fine cells huge:
  // coarsen until there are at most ~4 cells per particle (cells grow, candidates with them,
  // but every pair within `cell` is still found).
  const double limit = 4.0 * double(std::max<std::size_t>(fluid_.size(), 64));
  if (cells > limit) cell = Real(double(cell) * std::pow(cells / limit, 1.0 / D));
  ctx_.fluid_grid.configure(lo, hi, cell);
  return cell;
}

template <int D>
void FluidWorld<D>::build_neighbour_lists() {
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = fluid_.x[k].data();
  ctx_.fluid_list.build(ctx_.fluid_grid, xs, fluid_.size(), Real(prm_.support * prm_.support), pool_);
}

template <int D>
void FluidWorld<D>::sort_fluid_by_cell() {
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = fluid_.x[k].data();
  ctx_.fluid_grid.build(xs, fluid_.size(), pool_);
  const uint32_t* order = ctx_.fluid_grid.order();
  fluid_.permute_kinematics(order, ctx_.spare, pool_);
  const std::size_t n = fluid_.size();
  // Particle shifting (shift_particles) and PBF's surface forces read the neighbours' ρ between
  // the sort and the next density sum: carry the last step's along. (Unsorted, each particle
  // read another's.)
  if (density_read_after_sort()) {
    ctx_.tmp.resize(n);
    const Real* src = fluid_.rho.data();
    Real* dst = ctx_.tmp.data();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) dst[i] = src[order[i]];
    });
    fluid_.rho.swap(ctx_.tmp);
  }
  for (auto& f : method_fields_) {
    if (!f.sorted) continue;
    ctx_.tmp.resize(n);
    const Real* src = f.array->data();
    Real* dst = ctx_.tmp.data();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) dst[i] = src[order[i]];
    });
    f.array->swap(ctx_.tmp);
  }
}

template <int D>
void FluidWorld<D>::sort_boundary_by_cell() {
  const Real* xs[D];
  for (int k = 0; k < D; ++k) xs[k] = boundary_.x[k].data();
  ctx_.boundary_grid.build(xs, boundary_.size(), pool_);
  ctx_.boundary_grid.mark_occupied_stencils();
  boundary_.permute(ctx_.boundary_grid.order(), ctx_.tmp, pool_);
  compute_wall_geometry();
}

// A container-wall sample lies outside the domain box; the face it lies furthest beyond is its
// wall plane (corner samples pick one face). An obstacle sample lies inside its body; the face
// it lies nearest below is its wall plane (obstacle_wall_geometry). Per sample, so any thread
// count gives the same bits.
template <int D>
void FluidWorld<D>::compute_wall_geometry() {
  const std::size_t n = boundary_.size();
  for (int k = 0; k < D; ++k) ctx_.wall_normal[k].resize(n);
  ctx_.wall_depth.resize(n);
  pool_.parallel_for(n, [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      if (boundary_.owner[b] >= 0) {
        obstacle_wall_geometry(b);
        continue;
      }
      int axis = -1;
      Real depth = 0, sign = 0;
      for (int k = 0; k < D; ++k) {
        if (ctx_.boundary_grid.periodic(k)) continue;
        const Real below = Real(prm_.domain_min[k]) - boundary_.x[k][b];
        const Real above = boundary_.x[k][b] - Real(prm_.domain_max[k]);
        if (below > depth) { depth = below; axis = k; sign = 1; }
        if (above > depth) { depth = above; axis = k; sign = -1; }
      }
      for (int k = 0; k < D; ++k) ctx_.wall_normal[k][b] = k == axis ? sign : Real(0);
      ctx_.wall_depth[b] = axis >= 0 ? depth : Real(0);
    }
  });
}

template <int D>
void FluidWorld<D>::measure_density_error() {
  struct Err {
    double max = 0, sum = 0;
    Err& operator+=(const Err& o) { max = std::max(max, o.max); sum += o.sum; return *this; }
  };
  const double inv_rho0 = 1.0 / prm_.rho0;
  const Err e = pool_.parallel_reduce(fluid_.size(), Err{}, [&](std::size_t b, std::size_t end) {
    Err r;
    for (std::size_t i = b; i < end; ++i) {
      const double err = std::max(0.0, double(fluid_.rho[i]) * inv_rho0 - 1.0);
      r.max = std::max(r.max, err);
      r.sum += err;
    }
    return r;
  });
  density_error_ = e.max;
  mean_density_error_ = fluid_.size() ? e.sum / double(fluid_.size()) : 0.0;
  max_density_error_ = std::max(max_density_error_, density_error_);
}

template <int D>
void FluidWorld<D>::compute_inverse_density() {
  const std::size_t n = fluid_.size();
  ctx_.inv_rho.resize(n);
  const Real* rho = fluid_.rho.data();
  Real* out = ctx_.inv_rho.data();
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) out[i] = Real(1) / rho[i];
  });
}

template class FluidWorld<2>;
template class FluidWorld<3>;

}  // namespace rtsph
