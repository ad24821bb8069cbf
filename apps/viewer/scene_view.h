#pragma once
// Shared by `rtsph view` and `rtsph render`: how a scene is shown (domain, particle size,
// obstacle solids, initial camera) and the option spellings.
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/renderer.h"
#include "solvers/simulation.h"
#include "solvers/spec.h"

namespace rtsph::app {

/// Domain box of the spec in renderer coordinates (2D: z = 0).
inline void scene_bounds(const SimSpec& spec, render::Vec3f* lo, render::Vec3f* hi) {
  *lo = {float(spec.domain_min[0]), float(spec.domain_min[1]),
         spec.dimension == 3 ? float(spec.domain_min[2]) : 0.0f};
  *hi = {float(spec.domain_max[0]), float(spec.domain_max[1]),
         spec.dimension == 3 ? float(spec.domain_max[2]) : 0.0f};
}

/// Sets the renderer's domain and the particle radius (half the spacing: touching spheres).
inline void setup_scene_view(const SimSpec& spec, render::Renderer& r, render::RenderSettings& s) {
  render::Vec3f lo, hi;
  scene_bounds(spec, &lo, &hi);
  r.set_domain(spec.dimension, lo, hi);
  s.particle_radius = float(0.5 * spec.spacing);
}

/// The simulation's obstacles as render solids: the scene geometry at the current pose.
inline std::vector<render::SolidShape> obstacle_solids(const Simulation& sim) {
  const auto& obs = sim.spec().obstacles;
  std::vector<render::SolidShape> out(obs.size());
  for (int i = 0; i < int(obs.size()); ++i) {
    const Pose pose = sim.obstacle_transform(i);
    render::SolidShape& s = out[i];
    s.kind = obs[i].shape == ObstacleShape::Sphere ? render::SolidShape::Kind::Sphere
                                                   : render::SolidShape::Kind::Box;
    s.center = {float(pose.center[0]), float(pose.center[1]), float(pose.center[2])};
    for (int k = 0; k < 3; ++k) {
      Vec3d axis{};
      axis[k] = 1;
      const Vec3d col = pose.apply(axis) - pose.center;
      for (int j = 0; j < 3; ++j) s.rotation[3 * k + j] = float(col[j]);
    }
    s.half_extents = {float(obs[i].half_extents[0]), float(obs[i].half_extents[1]),
                      float(obs[i].half_extents[2])};
    s.radius = float(obs[i].radius);
  }
  return out;
}

/// Camera framing the scene's domain.
inline void frame_scene(const SimSpec& spec, render::Camera& cam, float aspect) {
  render::Vec3f lo, hi;
  scene_bounds(spec, &lo, &hi);
  cam = render::Camera{};
  cam.dim = spec.dimension;
  cam.frame(lo, hi, aspect);
}

/// "1280x720" → 1280, 720; false if malformed or out of [16, 8192].
bool parse_size(const std::string& text, int* w, int* h);
/// parse_size, or std::invalid_argument naming --size and its range.
void require_size(const std::string& text, int* w, int* h);

}  // namespace rtsph::app
