#include "scene/realtime_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {

double realtime_particles_per_thread(int dimension) {
  // `rtsph view dam_break_{2,3}d --accurate --set solver.method=pbf --set fluid.spacing=S
  // --frames 300 --report` under Xvfb, 1 solver thread (the viewer's default on 2 cores), the
  // drawing paced while the solver is behind, 2026-11-24: real-time factor 0.98 at 6,175 and
  // 0.97 at 7,020 (3D, the scene's 2 PBF substeps), 1.00 at 3,200 and 0.96 at 5,000 (2D) fluid
  // particles, quiet machine (docs/performance.md). The budget keeps a margin for a busier one.
  return dimension == 3 ? 5000 : 4000;
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
