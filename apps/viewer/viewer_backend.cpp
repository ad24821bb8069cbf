#include "apps/viewer/viewer_backend.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

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

GpuBudget measure_gpu_budget(const SimSpec& profile, double share, double finest, double wall_s) {
  GpuBudget out;
  const double substeps_per_s = std::max(1, profile.pbf_substeps) / profile.pbf_time_step;
  const double target = share / substeps_per_s;  // wall seconds a substep may take
  double spacing = profile.spacing;
  for (int probe = 0; probe < 4; ++probe) {
    SimSpec s = profile;
    s.spacing = spacing;
    s.backend = "gpu";
    const std::unique_ptr<Simulation> sim = gpu::make_gpu_simulation(s, 1);
    const double n = double(sim->stats().fluid_particles);
    if (n <= 0) break;
    // glFinish: the GPU backend queues a substep's passes; the clock must see them run.
    const double t = median_substep_seconds(*sim, wall_s, [] { glFinish(); });
    out.probes.push_back({n, t});
    if (std::abs(t - target) < 0.2 * target) break;  // close enough: the fit is at this size
    const double next = std::clamp(particles_in_time(out.probes, target), n / 8, 8 * n);
    const double to = std::max(finest, spacing * std::pow(n / next, 1.0 / profile.dimension));
    if (std::abs(to - spacing) < 0.02 * spacing) break;  // the next size would be this one
    spacing = to;
  }
  out.particles = particles_in_time(out.probes, target);
  out.rate = out.particles * substeps_per_s;
  return out;
}

}  // namespace rtsph::app
