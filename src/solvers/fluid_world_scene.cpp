// Scene-driven parts of the shared fluid world: boundary construction, obstacle motion, emitters, interaction.
#include <algorithm>
#include <cmath>

#include "solvers/fluid_world.h"

namespace rtsph {

template <int D>
void FluidWorld<D>::build_boundary() {
  auto samples = sample_walls(spec_);
  const auto obs = sample_obstacles(spec_);
  samples.insert(samples.end(), obs.begin(), obs.end());
  boundary_.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& s = samples[i];
    const Vec3d world = s.owner < 0 ? s.local : obstacles_[s.owner].pose.apply(s.local);
    for (int k = 0; k < D; ++k) {
      boundary_.local[k][i] = Real(s.local[k]);
      boundary_.x[k][i] = Real(world[k]);
      boundary_.v[k][i] = 0;
    }
    boundary_.owner[i] = s.owner;
  }
  // Both grids share one geometry, so a fluid particle's cell key indexes either.
  // A periodic axis spans exactly one period (no walls there to leave room for).
  const double margin = (std::max(1, spec_.boundary_layers) + 1) * spec_.spacing;
  Vec<D> lo, hi;
  bool periodic[D];
  for (int k = 0; k < D; ++k) {
    periodic[k] = axis_is_periodic(spec_.periodic, k);
    lo[k] = Real(spec_.domain_min[k] - (periodic[k] ? 0 : margin));
    hi[k] = Real(spec_.domain_max[k] + (periodic[k] ? 0 : margin));
  }
  ctx_.fluid_grid.configure(lo, hi, Real(prm_.support), periodic);
  ctx_.boundary_grid.configure(lo, hi, Real(prm_.support), periodic);
  sort_boundary_by_cell();
  compute_boundary_psi();
  if (!obstacles_.empty()) move_obstacles(0.0, 0.0);
}

template <int D>
void FluidWorld<D>::move_obstacles(double t_new, double dt) {
  if (!update_obstacle_states(t_new, dt)) return;
  pool_.parallel_for(boundary_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const int o = boundary_.owner[i];
      if (o < 0) continue;
      const auto& st = obstacles_[o];
      Vec3d local{};
      for (int k = 0; k < D; ++k) local[k] = boundary_.local[k][i];
      const Vec3d x = st.pose.apply(local), r = x - st.pose.center, w = st.angular_velocity;
      // v = v_c + ω × r; in 2D only ω_z acts.
      const Vec3d v = st.velocity + Vec3d{{w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2],
                                           w[0] * r[1] - w[1] * r[0]}};
      for (int k = 0; k < D; ++k) {
        boundary_.x[k][i] = Real(x[k]);
        boundary_.v[k][i] = Real(v[k]);
      }
      // The normal turns with the body (the depth does not): the viscous sum reads the current
      // pose's even where no boundary sort follows this move.
      obstacle_wall_geometry(i);
    }
  });
  stop_user_driven_obstacles();
}

template <int D>
bool FluidWorld<D>::update_obstacle_states(double t_new, double dt) {
  if (obstacles_.empty()) return false;
  bool any_moved = false;
  for (std::size_t o = 0; o < obstacles_.size(); ++o) {
    auto& st = obstacles_[o];
    const auto& sp = spec_.obstacles[o];
    const Pose old = st.pose;
    if (st.user_driven) {
      st.pose.center = st.user_target;
      st.velocity = dt > 0 ? (st.user_target - old.center) / dt : Vec3d{};
      st.angular_velocity = {};
    } else if (sp.motion != MotionKind::Static) {
      st.pose = obstacle_pose(sp, t_new);
      if (sp.motion == MotionKind::Velocity) {
        st.velocity = sp.velocity;
        st.angular_velocity = sp.angular_velocity;
      } else if (dt > 0) {  // keyframed: finite difference over the step
        st.velocity = (st.pose.center - old.center) / dt;
        st.angular_velocity = Vec3d{{0, 0, (st.pose.angle - old.angle) / dt}};
      }
    }
    any_moved |= st.user_driven || sp.motion != MotionKind::Static;
  }
  return any_moved || dt <= 0;
}

template <int D>
void FluidWorld<D>::stop_user_driven_obstacles() {
  // A user-driven obstacle stops once it reaches the target.
  for (auto& st : obstacles_)
    if (st.user_driven) st.velocity = {};
}

template <int D>
void FluidWorld<D>::emit_particles(double t_new) {
  for (std::size_t e = 0; e < spec_.emitters.size(); ++e) {
    const auto& sp = spec_.emitters[e];
    auto& st = emitters_[e];
    const double len = norm(sp.direction);
    if (len <= 0 || sp.speed <= 0) continue;
    const Vec3d dir = sp.direction / len;
    // Lateral lattice across the nozzle: a line in 2D, a disc in 3D.
    Vec3d u{{-dir[1], dir[0], 0}};
    if (norm(u) < 1e-9) u = Vec3d{{1, 0, 0}};
    u = u / norm(u);
    const Vec3d w{{dir[1] * u[2] - dir[2] * u[1], dir[2] * u[0] - dir[0] * u[2], dir[0] * u[1] - dir[1] * u[0]}};
    const int m = std::max(1, int(std::lround(sp.width / spec_.spacing)));
    std::vector<Vec3d> offsets;
    for (int a = 0; a < m; ++a) {
      const double oa = (a - (m - 1) * 0.5) * spec_.spacing;
      if (D == 2) { offsets.push_back(u * oa); continue; }
      for (int c = 0; c < m; ++c) {
        const double oc = (c - (m - 1) * 0.5) * spec_.spacing;
        if (oa * oa + oc * oc <= 0.25 * sp.width * sp.width + 1e-12) offsets.push_back(u * oa + w * oc);
      }
    }
    if (offsets.empty()) offsets.push_back({});
    const double interval = sp.rate > 0 ? double(offsets.size()) / sp.rate : spec_.spacing / sp.speed;
    while (st.next_layer_s <= t_new && st.next_layer_s < sp.stop_s &&
           st.emitted + double(offsets.size()) <= double(sp.max_particles)) {
      // The layer left the nozzle at next_layer_s and has travelled since.
      const double travelled = sp.speed * (t_new - st.next_layer_s);
      for (const auto& off : offsets)
        add_fluid_particle(truncate<D>(sp.position + off + dir * travelled), truncate<D>(dir * sp.speed));
      st.emitted += double(offsets.size());
      st.next_layer_s += interval;
    }
  }
}

template <int D>
void FluidWorld<D>::move_obstacle(int index, const Vec3d& center) {
  if (index < 0 || index >= int(obstacles_.size())) return;
  obstacles_[index].user_driven = true;
  obstacles_[index].user_target = center;
  boundary_moving_ = true;
}

template <int D>
Vec3d FluidWorld<D>::obstacle_center(int index) const {
  if (index < 0 || index >= int(obstacles_.size())) return {};
  return obstacles_[index].pose.center;
}

template <int D>
void FluidWorld<D>::set_live_parameters(const SimSpec& s) { copy_live_parameters(s, spec_); }

#define RTSPH_INSTANTIATE(D)                                   \
  template void FluidWorld<D>::build_boundary();                    \
  template void FluidWorld<D>::move_obstacles(double, double);      \
  template bool FluidWorld<D>::update_obstacle_states(double, double); \
  template void FluidWorld<D>::stop_user_driven_obstacles();        \
  template void FluidWorld<D>::emit_particles(double);              \
  template void FluidWorld<D>::move_obstacle(int, const Vec3d&);    \
  template Vec3d FluidWorld<D>::obstacle_center(int) const;         \
  template void FluidWorld<D>::set_live_parameters(const SimSpec&);
RTSPH_INSTANTIATE(2)
RTSPH_INSTANTIATE(3)
#undef RTSPH_INSTANTIATE

}  // namespace rtsph
