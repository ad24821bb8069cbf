#pragma once
// Shared by `rtsph view` and `rtsph render`: how a scene is shown (domain, particle size,
// initial camera) and the option spellings.
#include <string>

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
  // Overlapping boundary spheres read as one shaded solid surface rather than a bead shell.
  s.boundary_radius = float(0.85 * spec.spacing);
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

}  // namespace rtsph::app
