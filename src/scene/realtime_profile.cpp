#include "scene/realtime_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {

double realtime_particle_substeps_per_thread(int dimension) {
  // `rtsph view dam_break_{2,3}d --frames 300 --report` under Xvfb, 1 solver thread (the
  // viewer's default on 2 cores), llvmpipe on the other, 2026-11-25: 3D, the scene's 2 PBF
  // substeps per 1/60 s frame (120 per second), 3 to 4 iterations: 10,350 particles kept up in
  // 5 runs of 5 (real-time factor 0.992-1.000, never behind). 2D, 4 substeps (240 per second):
  // 2026-11-24, 1.00 at 3,200 and 0.96 at 5,000 with the default iterations, budget 4,000
  // (docs/performance.md).
  return dimension == 3 ? 10500.0 * 120 : 4000.0 * 240;
}

double realtime_budget(const SimSpec& pbf_spec, int solver_threads) {
  const double substeps_per_s = std::max(1, pbf_spec.pbf_substeps) / pbf_spec.pbf_time_step;
  return realtime_particle_substeps_per_thread(pbf_spec.dimension) * std::max(1, solver_threads) /
         substeps_per_s;
}

std::string RealtimeProfile::describe() const {
  if (!applied) return "as written";
  return fmt::format("real-time profile: pbf ({}-{} iterations), fluid.spacing {:.4g} m, {:.0f} fluid "
                     "particles at most, emitters included (budget {:.0f})",
                     spec.pbf_iterations, std::max(spec.pbf_iterations, spec.pbf_max_iterations),
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
  apply_override(r.spec, "solver.method=pbf", "viewer.realtime");
  // A bounded iteration count bounds the cost of the violent steps, which are the ones that fall
  // behind real time: 3 Jacobi iterations, more while the mean compression is above
  // solver.pbf.max_density_error, at most 4 (Macklin & Müller's range). 3D dam break, 10,695
  // particles, 1 thread, 7.4 s: 4.15 iterations per substep with the defaults (4 to 20), 3.50
  // with these; worst density error 14.0% → 17.7%, mean at the end 0.72% → 0.78%.
  r.spec.pbf_iterations = std::min(r.spec.pbf_iterations, kRealtimePbfIterations);
  r.spec.pbf_max_iterations = std::min(r.spec.pbf_max_iterations, kRealtimePbfMaxIterations);
  r.budget = realtime_budget(r.spec, solver_threads);
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
