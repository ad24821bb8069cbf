#include "scene/realtime_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {

double realtime_particles_per_thread(int dimension) {
  // `rtsph view dam_break_{2,3}d --report` under Xvfb, PBF defaults, 1 solver thread (the
  // viewer's default on 2 cores), 2026-11-23: real-time factor ~1 at these counts.
  return dimension == 3 ? 1100 : 2500;
}

std::string RealtimeProfile::describe() const {
  if (!applied) return "as written";
  return fmt::format("real-time profile: pbf, fluid.spacing {:.4g} m, {:.0f} fluid particles "
                     "(budget {:.0f})",
                     spec.spacing, fluid_particles, budget);
}

RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads) {
  RealtimeProfile r{scene};
  r.fluid_particles = count_particles(scene).fluid;
  if (!scene.viewer_realtime) return r;
  r.applied = true;
  r.budget = realtime_particles_per_thread(scene.dimension) * std::max(1, solver_threads);
  apply_override(r.spec, "solver.method=pbf", "viewer.realtime");
  // The count scales as spacing^-D; a few rounds absorb the lattice's rounding at block edges.
  double spacing = scene.spacing;
  for (int round = 0; round < 20 && r.fluid_particles > r.budget; ++round) {
    spacing *= std::max(1.01, std::pow(r.fluid_particles / r.budget, 1.0 / scene.dimension));
    SimSpec trial = r.spec;
    trial.spacing = spacing;
    r.fluid_particles = count_particles(trial).fluid;
  }
  if (spacing != scene.spacing)
    apply_override(r.spec, fmt::format("fluid.spacing={:.6g}", spacing), "viewer.realtime");
  r.fluid_particles = count_particles(r.spec).fluid;
  return r;
}

}  // namespace rtsph
