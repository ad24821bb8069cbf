#pragma once
// The viewer's real-time profile (issue 9 §5): scenes with viewer.realtime set run with PBF, at
// a spacing coarse enough that the viewer's solver threads keep up with real time. The budget
// is measured, not derived: see docs/performance.md ("The viewer in real time").
#include <string>

#include "solvers/spec.h"

namespace rtsph {

/// Fluid particles one solver thread steps in real time with PBF's defaults, with the viewer
/// drawing beside it (Mesa llvmpipe on the other core), on the reference 2-core machine.
double realtime_particles_per_thread(int dimension);

struct RealtimeProfile {
  SimSpec spec;             // what the viewer runs
  bool applied = false;     // false: the scene is not marked viewer.realtime; spec as given
  double fluid_particles = 0, budget = 0;  // at the start plus what emitters may add
  std::string describe() const;  // one line for the terminal and the panel
};

/// The scene as the viewer runs it with `solver_threads` threads: unchanged unless
/// viewer.realtime is set; then method pbf, and fluid.spacing grown (never shrunk) until the
/// starting fluid plus the most its emitters may add fits the budget. Emitter caps scale with
/// the particle volume, so the scene keeps its amount of water. The result is validated like
/// any scene.
RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads);

}  // namespace rtsph
