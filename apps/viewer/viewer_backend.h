#pragma once
// Which backend the viewer runs (`rtsph view --backend cpu|gpu|auto`). With the window's OpenGL
// context current: auto picks the GPU on a hardware driver when the GPU backend runs the scene,
// else the CPU (software rasterisers such as llvmpipe are far slower than the CPU solver).
#include <string>

#include "apps/viewer/sim_runner.h"

namespace rtsph::app {

struct ViewerBackend {
  std::string name;          // "cpu" or "gpu"
  SimFactory make;           // builds the simulation for this and every reset
  bool on_caller_thread = false;  // the GPU steps on the drawing thread (its context)
};

/// Throws BackendUnavailable (one line) when --backend gpu cannot run here.
ViewerBackend choose_viewer_backend(const std::string& flag, const SimSpec& spec);

}  // namespace rtsph::app
