#pragma once
// Sampling of the initial state: fluid lattices, container walls and obstacle shells
// (Akinci et al. 2012 boundary particles), plus rigid poses of obstacles. Setup-time only.
#include <vector>

#include "solvers/spec.h"

namespace rtsph {

/// Rigid pose: x_world = center + R(axis, angle) · x_local.
struct Pose {
  Vec3d center{};
  Vec3d axis{0, 0, 1};
  double angle = 0;  // rad
  Vec3d apply(const Vec3d& local) const;
  Vec3d rotate(const Vec3d& v) const;  // R · v: a body-frame direction (a normal) in the world
};

/// Pose of an obstacle at time t from its prescribed motion (static, velocity, keyframed path).
Pose obstacle_pose(const ObstacleSpec& o, double t);

/// Signed distance from p to the obstacle surface at `pose` (negative inside).
double obstacle_distance(const ObstacleSpec& o, const Pose& pose, const Vec3d& p, int dim);

/// Where a point inside an obstacle lies below its surface, in the body frame: the outward unit
/// normal of the nearest face and the depth below it (m, >= 0). Boxes: the face with the smallest
/// gap he_k - |q_k| (ties go to the lowest axis, so corner samples pick one face, as the
/// container's do; the depth is then at most the box's smallest half extent), skipping the body
/// axes set in `skip_axes` (bit k: a box that spans a periodic axis has no face there). Spheres
/// and circles: radial. `face` encodes the normal for the GPU, which rotates it with the pose:
/// 0 none (depth 0), ±(k+1) ±e_k, kRadialFace the normalised local position.
struct SurfacePoint {
  Vec3d normal{};
  double depth = 0;
  int face = 0;
};
inline constexpr int kRadialFace = 4;
SurfacePoint obstacle_surface_point(const ObstacleSpec& o, const Vec3d& local, int dim, unsigned skip_axes);

/// Body axes of a box obstacle that have no faces: axis k maps (at the pose at t = 0) onto a
/// periodic axis j and the box spans that period to within half a spacing, so its samples wrap
/// without a seam (the Couette case's moving plate). Bit k set for such an axis.
unsigned obstacle_seamless_axes(const SimSpec& s, const ObstacleSpec& o);

/// Lattice points (cell centres at spacing s) filling each block, minus points closer than one
/// spacing to an obstacle (their boundary particles sit on the surface).
std::vector<Vec3d> sample_fluid(const SimSpec& s);

/// Boundary particle in a body frame: owner -1 = container walls (local = world position).
struct BoundarySample {
  Vec3d local;
  int owner;
};
/// Container walls: `layers` lattice layers just outside [domain_min, domain_max], so the wall
/// plane lies half a spacing from both the first fluid and the first boundary layer.
std::vector<BoundarySample> sample_walls(const SimSpec& s);
/// Obstacle surfaces, `layers` shells inward, in each obstacle's body frame.
std::vector<BoundarySample> sample_obstacles(const SimSpec& s);

/// Number of particles the scene starts with (cheap: counts without storing), and the most the
/// emitters can add.
struct ParticleCounts {
  double fluid = 0, emitted_max = 0, boundary = 0, grid_cells = 0;
};
ParticleCounts count_particles(const SimSpec& s);

}  // namespace rtsph
