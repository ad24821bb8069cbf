#pragma once
// The viewer's real-time profile (issue 9 §5): scenes with viewer.realtime set run with PBF, at
// a spacing coarse enough that the viewer's solver threads keep up with real time. The budget
// is measured, not derived: see docs/performance.md ("The viewer in real time").
#include <string>

#include "solvers/spec.h"

namespace rtsph {

/// Fluid particle-substeps per second one solver thread keeps up with in PBF, with the viewer
/// drawing beside it (Mesa llvmpipe on the other core), on the reference 2-core machine.
double realtime_particle_substeps_per_thread(int dimension);
/// The fluid particles (emitters' caps included) `solver_threads` keep in real time for this
/// PBF set-up: the rate above over its substeps per second (solver.pbf.substeps over
/// solver.pbf.time_step), so a scene with twice the substeps gets half the particles.
double realtime_budget(const SimSpec& pbf_spec, int solver_threads);

/// PBF's Jacobi iterations per substep in the profile: at least, and at most (realtime_profile).
inline constexpr int kRealtimePbfIterations = 3, kRealtimePbfMaxIterations = 4;

struct RealtimeProfile {
  SimSpec spec;             // what the viewer runs
  bool applied = false;     // false: the scene is not marked viewer.realtime; spec as given
  double fluid_particles = 0, budget = 0;  // at the start plus what emitters may add
  std::string describe() const;  // one line for the terminal and the panel
};

/// The scene as the viewer runs it with `solver_threads` threads: unchanged unless
/// viewer.realtime is set; then method pbf with 3 to 4 iterations, and fluid.spacing grown (never shrunk) until the
/// starting fluid plus the most its emitters may add fits the budget. Emitter caps scale with
/// the particle volume, so the scene keeps its amount of water. The result is validated like
/// any scene.
RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads);

}  // namespace rtsph
