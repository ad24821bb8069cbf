#include "scene/realtime_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {

double realtime_particles_per_thread(int dimension) {
  // `rtsph view dam_break_{2,3}d --accurate --set solver.method=pbf --set fluid.spacing=S
  // --frames 400 --report` under Xvfb, 1 solver thread (the viewer's default on 2 cores),
  // 2026-11-23: real-time factor 1.00 at 1,536 and 0.88-0.99 at 1,768-1,989 (3D), 1.00 at
  // 3,200 and 0.95 at 4,095 (2D) fluid particles (docs/performance.md).
  return dimension == 3 ? 1600 : 3200;
}

std::string RealtimeProfile::describe() const {
  if (!applied) return "as written";
  return fmt::format("real-time profile: pbf, fluid.spacing {:.4g} m, {:.0f} fluid particles "
                     "at most, emitters included (budget {:.0f})",
                     spec.spacing, fluid_particles, budget);
}

namespace {

// The scene at spacing s, with each emitter's particle cap scaled so that it still emits the
// same volume of water (a cap is a count, and a coarser particle holds more water).
SimSpec at_spacing(const SimSpec& scene, double s) {
  SimSpec out = scene;
  out.spacing = s;
  const double volume_ratio = std::pow(scene.spacing / s, scene.dimension);
  for (auto& e : out.emitters)
    e.max_particles = std::int64_t(std::floor(double(e.max_particles) * volume_ratio));
  return out;
}

// Fluid at the start plus the most the emitters may add.
double particles(const SimSpec& s) {
  const ParticleCounts c = count_particles(s);
  return c.fluid + c.emitted_max;
}

}  // namespace

RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads) {
  RealtimeProfile r{scene};
  r.fluid_particles = particles(scene);
  if (!scene.viewer_realtime) return r;
  r.applied = true;
  r.budget = realtime_particles_per_thread(scene.dimension) * std::max(1, solver_threads);
  apply_override(r.spec, "solver.method=pbf", "viewer.realtime");
  // The count scales as spacing^-D; a few rounds absorb the lattice's rounding at block edges.
  double spacing = scene.spacing;
  for (int round = 0; round < 20 && r.fluid_particles > r.budget; ++round) {
    spacing *= std::max(1.01, std::pow(r.fluid_particles / r.budget, 1.0 / scene.dimension));
    r.fluid_particles = particles(at_spacing(r.spec, spacing));
  }
  if (spacing != scene.spacing) {
    r.spec = at_spacing(r.spec, spacing);
    r.spec = parse_scene(scene_to_json(r.spec), "viewer.realtime");  // validated like any override
  }
  r.fluid_particles = particles(r.spec);
  return r;
}

}  // namespace rtsph
