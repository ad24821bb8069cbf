#include "solvers/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rtsph {

namespace {
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
Vec3d rodrigues(const Vec3d& v, const Vec3d& k, double angle) {  // Rodrigues
  if (angle == 0) return v;
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}
long lattice_count(double extent, double s) { return std::max(1L, std::lround(extent / s)); }
}  // namespace

Vec3d Pose::apply(const Vec3d& local) const { return center + rodrigues(local, axis, angle); }
Vec3d Pose::rotate(const Vec3d& v) const { return rodrigues(v, axis, angle); }

Pose obstacle_pose(const ObstacleSpec& o, double t) {
  Pose p;
  p.center = o.center;
  switch (o.motion) {
    case MotionKind::Static: break;
    case MotionKind::Velocity: {
      p.center = o.center + o.velocity * t;
      const double w = norm(o.angular_velocity);
      if (w > 0) { p.axis = o.angular_velocity / w; p.angle = w * t; }
      break;
    }
    case MotionKind::Path: {
      const auto& k = o.path;
      if (k.empty()) break;
      if (t <= k.front().time_s) { p.center = k.front().position; p.angle = k.front().angle_rad; break; }
      if (t >= k.back().time_s) { p.center = k.back().position; p.angle = k.back().angle_rad; break; }
      const auto hi = std::upper_bound(k.begin(), k.end(), t,
                                       [](double tt, const Keyframe& f) { return tt < f.time_s; });
      const auto lo = hi - 1;
      const double u = (t - lo->time_s) / (hi->time_s - lo->time_s);
      p.center = lo->position * (1 - u) + hi->position * u;
      p.angle = lo->angle_rad * (1 - u) + hi->angle_rad * u;
      break;
    }
  }
  return p;
}

double obstacle_distance(const ObstacleSpec& o, const Pose& pose, const Vec3d& p, int dim) {
  Vec3d q = rodrigues(p - pose.center, pose.axis, -pose.angle);
  if (dim == 2) q[2] = 0;
  if (o.shape == ObstacleShape::Sphere) return norm(q) - o.radius;
  double outside = 0, inside = -1e300;
  for (int k = 0; k < dim; ++k) {
    const double d = std::abs(q[k]) - o.half_extents[k];
    outside += std::max(d, 0.0) * std::max(d, 0.0);
    inside = std::max(inside, d);
  }
  return outside > 0 ? std::sqrt(outside) : inside;
}

SurfacePoint obstacle_surface_point(const ObstacleSpec& o, const Vec3d& local, int dim, unsigned skip_axes) {
  SurfacePoint sp;
  Vec3d q = local;
  if (dim == 2) q[2] = 0;
  if (o.shape == ObstacleShape::Sphere) {
    const double r = norm(q);
    if (!(r > 0)) return sp;  // the centre: no direction (never a sample: shells stay > s/4 out)
    sp.normal = q / r;
    sp.depth = std::max(0.0, o.radius - r);
    sp.face = kRadialFace;
    return sp;
  }
  double best = std::numeric_limits<double>::max();
  for (int k = 0; k < dim; ++k) {
    if (skip_axes & (1u << k)) continue;
    const double gap = o.half_extents[k] - std::abs(q[k]);
    if (gap < best) {
      best = gap;
      const double sign = q[k] < 0 ? -1.0 : 1.0;
      sp.normal = Vec3d{};
      sp.normal[k] = sign;
      sp.face = q[k] < 0 ? -(k + 1) : k + 1;
    }
  }
  if (sp.face != 0) sp.depth = std::max(0.0, best);
  return sp;
}

unsigned obstacle_seamless_axes(const SimSpec& s, const ObstacleSpec& o) {
  if (o.shape != ObstacleShape::Box) return 0;
  const Pose pose = obstacle_pose(o, 0.0);
  unsigned mask = 0;
  for (int k = 0; k < s.dimension; ++k) {
    Vec3d e{};
    e[k] = 1;
    const Vec3d w = pose.rotate(e);
    for (int j = 0; j < s.dimension; ++j) {
      if (!axis_is_periodic(s.periodic, j) || std::abs(w[j]) < 1 - 1e-9) continue;
      if (2 * o.half_extents[k] >= s.domain_max[j] - s.domain_min[j] - 0.5 * s.spacing) mask |= 1u << k;
    }
  }
  return mask;
}

namespace {
// Calls fn(index) for every integer index in [lo, hi] per axis (first `dim` axes).
template <class Fn>
void for_each_index(int dim, const long lo[3], const long hi[3], Fn&& fn) {
  long i[3] = {lo[0], lo[1], dim == 3 ? lo[2] : 0};
  const long zhi = dim == 3 ? hi[2] : 0;
  for (i[2] = dim == 3 ? lo[2] : 0; i[2] <= zhi; ++i[2])
    for (i[1] = lo[1]; i[1] <= hi[1]; ++i[1])
      for (i[0] = lo[0]; i[0] <= hi[0]; ++i[0]) fn(i);
}
}  // namespace

namespace {
// The ball (disc) inscribed in the block: centred, radius half its smallest side.
bool inside_ball(const FluidBlock& b, const Vec3d& p, int dim) {
  double r = 1e300, d2 = 0;
  for (int k = 0; k < dim; ++k) {
    r = std::min(r, 0.5 * (b.max[k] - b.min[k]));
    const double d = p[k] - 0.5 * (b.min[k] + b.max[k]);
    d2 += d * d;
  }
  return d2 <= r * r;
}
}  // namespace

std::vector<Vec3d> sample_fluid(const SimSpec& s) {
  std::vector<Vec3d> out;
  std::vector<Pose> poses;
  for (const auto& o : s.obstacles) poses.push_back(obstacle_pose(o, 0.0));
  for (const auto& b : s.fluid_blocks) {
    long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < s.dimension; ++k) hi[k] = lattice_count(b.max[k] - b.min[k], s.spacing) - 1;
    for_each_index(s.dimension, lo, hi, [&](const long* i) {
      Vec3d p{};
      for (int k = 0; k < s.dimension; ++k) p[k] = b.min[k] + (double(i[k]) + 0.5) * s.spacing;
      if (b.shape == BlockShape::Ball && !inside_ball(b, p, s.dimension)) return;
      for (std::size_t o = 0; o < s.obstacles.size(); ++o)
        if (obstacle_distance(s.obstacles[o], poses[o], p, s.dimension) < 0.5 * s.spacing) return;
      out.push_back(p);
    });
  }
  return out;
}

std::vector<BoundarySample> sample_walls(const SimSpec& s) {
  std::vector<BoundarySample> out;
  if (s.open) return out;  // open space: no container
  const long L = std::max(1, s.boundary_layers);
  long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, n[3] = {1, 1, 1};
  double step[3] = {0, 0, 0};
  bool wraps[3] = {false, false, false};
  for (int k = 0; k < s.dimension; ++k) {
    n[k] = lattice_count(s.domain_max[k] - s.domain_min[k], s.spacing);
    step[k] = (s.domain_max[k] - s.domain_min[k]) / double(n[k]);
    // A periodic axis has no walls of its own, and the others' walls span exactly one period.
    wraps[k] = axis_is_periodic(s.periodic, k);
    lo[k] = wraps[k] ? 0 : -L;
    hi[k] = wraps[k] ? n[k] - 1 : n[k] - 1 + L;
  }
  for_each_index(s.dimension, lo, hi, [&](const long* i) {
    bool outside = false;
    for (int k = 0; k < s.dimension; ++k) outside |= !wraps[k] && (i[k] < 0 || i[k] >= n[k]);
    if (!outside) return;
    Vec3d p{};
    for (int k = 0; k < s.dimension; ++k) p[k] = s.domain_min[k] + (double(i[k]) + 0.5) * step[k];
    out.push_back({p, -1});
  });
  return out;
}

namespace {
void sample_box_shell(const SimSpec& s, const Vec3d& he, int owner, std::vector<BoundarySample>& out) {
  long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  double step[3] = {0, 0, 0};
  for (int k = 0; k < s.dimension; ++k) {
    hi[k] = lattice_count(2 * he[k], s.spacing);
    step[k] = 2 * he[k] / double(hi[k]);
  }
  for_each_index(s.dimension, lo, hi, [&](const long* i) {
    bool surface = false;
    for (int k = 0; k < s.dimension; ++k) surface |= i[k] == 0 || i[k] == hi[k];
    if (!surface) return;
    Vec3d p{};
    for (int k = 0; k < s.dimension; ++k) p[k] = -he[k] + double(i[k]) * step[k];
    out.push_back({p, owner});
  });
}
void sample_round_shell(const SimSpec& s, double r, int owner, std::vector<BoundarySample>& out) {
  const double pi = std::numbers::pi;
  if (s.dimension == 2) {
    const long n = std::max(3L, std::lround(2 * pi * r / s.spacing));
    for (long i = 0; i < n; ++i) {
      const double a = 2 * pi * double(i) / double(n);
      out.push_back({{{r * std::cos(a), r * std::sin(a), 0}}, owner});
    }
    return;
  }
  // Fibonacci sphere: near-uniform area per point.
  const long n = std::max(4L, std::lround(4 * pi * r * r / (s.spacing * s.spacing)));
  const double golden = pi * (3 - std::sqrt(5.0));
  for (long i = 0; i < n; ++i) {
    const double y = 1 - 2 * (double(i) + 0.5) / double(n), rad = std::sqrt(1 - y * y);
    const double phi = golden * double(i);
    out.push_back({{{r * rad * std::cos(phi), r * y, r * rad * std::sin(phi)}}, owner});
  }
}
}  // namespace

std::vector<BoundarySample> sample_obstacles(const SimSpec& s) {
  std::vector<BoundarySample> out;
  const int L = std::max(1, s.boundary_layers);
  for (std::size_t o = 0; o < s.obstacles.size(); ++o) {
    const auto& ob = s.obstacles[o];
    // Layers sit (l + ½)·spacing inside the surface, as the wall layers sit outside the domain:
    // the fluid then stops at the obstacle's stated size, one spacing from the samples. A shape
    // too thin for that keeps one layer on its surface.
    double min_half = ob.radius;
    if (ob.shape == ObstacleShape::Box) {
      min_half = ob.half_extents[0];
      for (int k = 1; k < s.dimension; ++k) min_half = std::min(min_half, ob.half_extents[k]);
    }
    const double first = min_half - 0.5 * s.spacing > 0.25 * s.spacing ? 0.5 * s.spacing : 0.0;
    for (int l = 0; l < L; ++l) {
      const double inset = first + l * s.spacing;
      if (ob.shape == ObstacleShape::Box) {
        Vec3d he = ob.half_extents - Vec3d::splat(inset);
        bool ok = true;
        for (int k = 0; k < s.dimension; ++k) ok &= he[k] > 0.25 * s.spacing;
        if (ok) sample_box_shell(s, he, int(o), out);
      } else if (ob.radius - inset > 0.25 * s.spacing) {
        sample_round_shell(s, ob.radius - inset, int(o), out);
      }
    }
  }
  return out;
}

ParticleCounts count_particles(const SimSpec& s) {
  ParticleCounts c;
  const int D = s.dimension;
  for (const auto& b : s.fluid_blocks) {
    double n = 1;
    for (int k = 0; k < D; ++k) n *= double(std::max(1.0, std::round((b.max[k] - b.min[k]) / s.spacing)));
    c.fluid += n;
  }
  for (const auto& e : s.emitters) c.emitted_max += double(std::max<std::int64_t>(0, e.max_particles));
  const double L = std::max(1, s.boundary_layers);
  double inner = 1, outer = 1, cells = 1;
  const double support = support_ratio(s.kernel) * s.smoothing_ratio * s.spacing;
  for (int k = 0; k < D; ++k) {
    const double n = std::max(1.0, std::round((s.domain_max[k] - s.domain_min[k]) / s.spacing));
    inner *= n;
    outer *= n + 2 * L;
    cells *= std::ceil((s.domain_max[k] - s.domain_min[k] + 2 * (L + 1) * s.spacing) / support) + 2;
  }
  c.boundary = s.open ? 0.0 : outer - inner;
  const double pi = std::numbers::pi;
  for (const auto& o : s.obstacles) {
    double area = 0;  // surface measure / spacing^(D-1), per layer
    if (o.shape == ObstacleShape::Sphere)
      area = D == 2 ? 2 * pi * o.radius / s.spacing : 4 * pi * o.radius * o.radius / (s.spacing * s.spacing);
    else if (D == 2)
      area = 4 * (o.half_extents[0] + o.half_extents[1]) / s.spacing + 4;
    else
      area = 8 * (o.half_extents[0] * o.half_extents[1] + o.half_extents[1] * o.half_extents[2] +
                  o.half_extents[0] * o.half_extents[2]) / (s.spacing * s.spacing) + 8;
    c.boundary += area * L;
  }
  c.grid_cells = cells;
  return c;
}

}  // namespace rtsph
