#pragma once
// Which backend the viewer runs (`rtsph view --backend cpu|gpu|auto`). With the window's OpenGL
// context current: auto picks the GPU on a hardware driver when the GPU backend runs the scene,
// else the CPU (software rasterisers such as llvmpipe are far slower than the CPU solver).
#include <string>

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
/// on a GPU is the GPU's, not the CPU reference machine's): dam_break_device_budget with probes
/// on the GPU backend in the current context (each about wall_s of substeps).
DeviceBudget measure_gpu_budget(int dimension, double wall_s);

}  // namespace rtsph::app
