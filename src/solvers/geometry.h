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
};

/// Pose of an obstacle at time t from its prescribed motion (static, velocity, keyframed path).
Pose obstacle_pose(const ObstacleSpec& o, double t);

/// Signed distance from p to the obstacle surface at `pose` (negative inside).
double obstacle_distance(const ObstacleSpec& o, const Pose& pose, const Vec3d& p, int dim);

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
