#pragma once
// Which backend the viewer runs (`rtsph view --backend cpu|gpu|auto`). With the window's OpenGL
// context current: auto picks the GPU on a hardware driver when the GPU backend runs the scene,
// else the CPU (software rasterisers such as llvmpipe are far slower than the CPU solver).
#include <string>
#include <vector>

#include "apps/viewer/sim_runner.h"
#include "scene/realtime_profile.h"

namespace rtsph::app {

struct ViewerBackend {
  std::string name;          // "cpu" or "gpu"
  SimFactory make;           // builds the simulation for this and every reset
  bool on_caller_thread = false;  // the GPU steps on the drawing thread (its context)
};

/// Throws BackendUnavailable (one line) when --backend gpu cannot run here.
ViewerBackend choose_viewer_backend(const std::string& flag, const SimSpec& spec);

/// What the GPU keeps in real time with a real-time profile's PBF (issue 10: the viewer's budget
/// on a GPU is the GPU's, not the CPU reference machine's).
struct GpuBudget {
  double particles = 0;  // fluid particles whose median substep takes `share` of its real time
  double rate = 0;       // the same as fluid particle-substeps per second (realtime_budget's rate)
  std::vector<StepProbe> probes;  // what was measured
};
/// Steps `profile` (a real-time profile's spec, from rest) on the GPU at up to four spacings, no
/// finer than `finest` m, each for about wall_s, and fits particles_in_time to the probes. A
/// GPU's substep has a fixed cost (dispatches, barriers) that dominates small sizes, so one
/// probe at the CPU's size would say little about the size it keeps up with; each next probe is
/// sized from the line through the last ones (at most 8 times the size before). Needs the GL
/// context current.
GpuBudget measure_gpu_budget(const SimSpec& profile, double share, double finest, double wall_s);

}  // namespace rtsph::app
