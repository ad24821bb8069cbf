// `rtsph bench --realtime`: how large a dam break a method keeps up with in real time here.
// Each probe builds the dam break at a particle count, runs its first `window` simulated seconds
// (the collapse, the violent phase) and divides simulated by wall time, construction excluded.
// The count is doubled or halved until the real-time factor brackets 1, then bisected
// geometrically to within 10%.
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "apps/bench.h"
#include "apps/sim_backend.h"
#include "io/atomic_file.h"
#include "scene/realtime_profile.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

namespace rtsph::app {

namespace {
struct Probe {
  std::size_t fluid = 0;
  std::uint64_t steps = 0;
  double sim_s = 0, wall_s = 0;
  double iterations = -1;  // PBF's or DFSPH's mean pressure iterations per step (-1: none)
  double rtf() const { return wall_s > 0 ? sim_s / wall_s : 0; }
};

// A probe that has fallen three times behind real time stops early: its factor is known to be
// well below 1, and a large slow probe would otherwise cost minutes.
Probe probe_spec(const SimSpec& spec, double window_s, int threads, const std::string& backend) {
  auto sim = BackendSimulation::make(spec, threads, backend);
  Probe p;
  p.fluid = sim->stats().fluid_particles;
  const auto t0 = std::chrono::steady_clock::now();
  while (sim->time() < window_s) {
    sim->step();
    sim->wait_idle();
    p.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (p.wall_s > 3 * window_s) break;
  }
  p.sim_s = sim->time();
  p.steps = sim->step_count();
  const SimStats st = sim->stats();
  if (st.method == "pbf" || st.method == "dfsph") p.iterations = st.mean_pressure_iterations;
  return p;
}

Probe probe(const BenchOptions& o, double n, int threads) {
  return probe_spec(dam_break_with(o.dim, n, o.method, o.sets), o.window_s, threads, o.backend);
}
}  // namespace

int bench_realtime(const BenchOptions& o) {
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  fmt::print("rtsph bench --realtime: {}D dam break, {}, {} threads, backend {}, first {} s simulated\n",
             o.dim, o.method, threads, o.backend, o.window_s);
  fmt::print("{:>9} {:>7} {:>9} {:>9} {:>8} {:>6}\n", "fluid", "steps", "sim s", "wall s", "RTF", "iter");
  nlohmann::ordered_json rows = nlohmann::json::array();
  auto run = [&](double n) {
    const Probe p = probe(o, n, threads);
    fmt::print("{:>9} {:>7} {:>9.3f} {:>9.3f} {:>8.3f} {:>6}\n", p.fluid, p.steps, p.sim_s, p.wall_s,
               p.rtf(), p.iterations >= 0 ? fmt::format("{:.1f}", p.iterations) : std::string("-"));
    std::fflush(stdout);
    rows.push_back({{"fluid_particles", p.fluid}, {"steps", p.steps}, {"sim_s", p.sim_s},
                    {"wall_s", p.wall_s}, {"real_time_factor", p.rtf()}});
    if (p.iterations >= 0) rows.back()["mean_pressure_iterations"] = p.iterations;
    return p;
  };
  // Bracket: lo keeps up (or is the smallest size tried), hi does not.
  double n = 2000, lo = 0, hi = 0;
  std::size_t best = 0;
  for (int i = 0; i < 12 && (lo == 0 || hi == 0); ++i) {
    const Probe p = run(n);
    if (p.rtf() >= 1) {
      lo = n;
      best = p.fluid;
      n *= 2;
    } else {
      hi = n;
      n /= 2;
    }
    if (n < 50) break;
  }
  while (lo > 0 && hi > 0 && hi / lo > 1.1) {
    const double mid = std::sqrt(lo * hi);
    const Probe p = run(mid);
    if (p.rtf() >= 1) {
      lo = mid;
      best = p.fluid;
    } else {
      hi = mid;
    }
  }
  if (best > 0)
    fmt::print("real-time capacity: {} fluid particles ({}D, {}, {} threads, backend {})\n", best, o.dim,
               o.method, threads, o.backend);
  else
    fmt::print("real-time capacity: none: even the smallest dam break tried runs slower than "
               "real time\n");
  // On the GPU, what the viewer's start-up probe budgets for the same machine (docs/viewer.md,
  // "Real-time profile"), to set beside the capacity: its own probes (7 iterations, from rest,
  // realtime_device_share of a substep's real time), not this search's first simulated second.
  DeviceBudget viewer;
  if (o.backend == "gpu" && o.method == "pbf") {
    viewer = dam_break_device_budget(o.dim, [&](const SimSpec& spec) {
      return probe_substeps(*BackendSimulation::make(spec, threads, "gpu"), 0.3);
    });
    fmt::print("the viewer's budget on this GPU: {:.0f} fluid particles (probes: {})\n", viewer.particles,
               viewer.describe());
  }
  // The viewer's profile at that budget (at least a 16th of the CPU reference's rate, as the
  // viewer takes it) over the same simulated window, without the drawing: the budget holds if the
  // solver takes about the share of the wall time it was given (a real-time factor of 1/share),
  // leaving the rest for drawing.
  Probe profiled;
  if (!viewer.probes.empty()) {
    const SimSpec dam = load_scene(o.dim == 3 ? "dam_break_3d" : "dam_break_2d");
    const double rate = std::max(viewer.rate, realtime_particle_substeps_per_thread(o.dim) / 16);
    profiled = probe_spec(realtime_profile(dam, 1, rate, /*device=*/true).spec, o.window_s, threads, "gpu");
    fmt::print("the viewer's profile at that budget: {} fluid particles, {} substeps in {:.3f} s simulated, "
               "{:.3f} s wall: real-time factor {:.3f} without drawing (the budget aims at {:.2f}), {:.1f} "
               "iterations\n",
               profiled.fluid, profiled.steps, profiled.sim_s, profiled.wall_s, profiled.rtf(),
               1 / realtime_device_share(o.dim), profiled.iterations);
  }
  if (!o.json.empty()) {
    nlohmann::ordered_json j;
    j["dimension"] = o.dim;
    j["method"] = o.method;
    j["threads"] = threads;
    j["backend"] = o.backend;
    j["window_s"] = o.window_s;
    j["set"] = o.sets;
    j["capacity_fluid_particles"] = best;
    j["probes"] = rows;
    if (!viewer.probes.empty()) j["viewer_budget_fluid_particles"] = viewer.particles;
    if (profiled.fluid > 0)
      j["viewer_profile"] = {{"fluid_particles", profiled.fluid}, {"steps", profiled.steps},
                             {"sim_s", profiled.sim_s}, {"wall_s", profiled.wall_s},
                             {"real_time_factor", profiled.rtf()}, {"mean_pressure_iterations", profiled.iterations}};
    io::write_file_atomic(o.json, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
  }
  return 0;
}

}  // namespace rtsph::app
