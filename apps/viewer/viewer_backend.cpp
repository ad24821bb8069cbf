#include "apps/viewer/viewer_backend.h"

#include "apps/sim_backend.h"
#include "gpu/backend.h"
#include "gpu/gl_compute.h"

namespace rtsph::app {

ViewerBackend choose_viewer_backend(const std::string& flag, const SimSpec& spec) {
  std::string backend = choose_backend(flag, spec, "auto");
  const std::string no_compute = gpu::compute_support_problem();
  if (backend == "auto")
    backend = no_compute.empty() && !gpu::software_renderer() && gpu::gpu_cannot_run(spec).empty() ? "gpu" : "cpu";
  ViewerBackend b;
  b.name = backend;
  if (backend != "gpu") return b;  // the default factory: make_simulation
  if (!no_compute.empty()) throw BackendUnavailable("--backend gpu: " + no_compute);
  if (const std::string why = gpu::gpu_cannot_run(spec); !why.empty()) throw BackendUnavailable(why);
  // A scene picked later in the panel that the GPU cannot run (the gas method, DFSPH with the
  // transport velocity) runs on the CPU, still on this thread.
  b.make = [](const SimSpec& s, int threads) {
    return gpu::gpu_cannot_run(s).empty() ? gpu::make_gpu_simulation(s, threads) : make_simulation(s, threads);
  };
  b.on_caller_thread = true;
  return b;
}

DeviceBudget measure_gpu_budget(int dimension, double wall_s) {
  return dam_break_device_budget(dimension, [wall_s](const SimSpec& spec) {
    SimSpec s = spec;
    s.backend = "gpu";
    return probe_substeps(*gpu::make_gpu_simulation(s, 1), wall_s);
  });
}

}  // namespace rtsph::app
