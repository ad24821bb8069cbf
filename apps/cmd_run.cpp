// `rtsph run SCENE`: headless batch run with progress, exports and a summary.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <limits>

#include "apps/commands.h"
#include "apps/progress.h"
#include "apps/run_summary.h"
#include "io/atomic_file.h"
#include "io/exporter.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

namespace rtsph::app {

namespace {
struct RunOptions {
  std::string scene;
  double until = -1;
  long long steps = -1;
  int threads = 0;
  std::vector<std::string> sets;
  std::string export_dir, format = "csv", attributes = "all", stats_json;
  double every = 0.02;
  bool quiet = false;
};

int run(const RunOptions& o) {
  SimSpec spec = load_scene(o.scene);
  for (const auto& s : o.sets) apply_override(spec, s);
  auto sim = make_simulation(spec, o.threads);
  const double until = o.until >= 0 ? o.until : (o.steps >= 0 ? std::numeric_limits<double>::infinity() : spec.end_time);
  const long long max_steps = o.steps >= 0 ? o.steps : std::numeric_limits<long long>::max();

  std::unique_ptr<io::Exporter> exporter;
  int frame = 0;
  double next_export = 0;
  if (!o.export_dir.empty()) {
    exporter = io::make_exporter(o.format, o.export_dir, io::parse_attributes(o.attributes));
    exporter->write_frame(frame++, sim->time(), sim->fluid());
    next_export = o.every;
  }

  const auto s0 = sim->stats();
  if (!o.quiet)
    std::fprintf(stderr, "rtsph run: %s (%dD, %s), %zu fluid + %zu boundary particles, c0 = %.1f m/s\n",
                 spec.name.c_str(), spec.dimension, spec.method.c_str(), s0.fluid_particles,
                 s0.boundary_particles, s0.c0);
  const double progress_total = std::isfinite(until) ? until : double(max_steps);
  Progress progress("run", progress_total, o.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  long long steps = 0;
  while (sim->time() < until && steps < max_steps) {
    sim->step();
    ++steps;
    if (exporter && sim->time() + 1e-12 >= next_export) {
      exporter->write_frame(frame++, sim->time(), sim->fluid());
      next_export += o.every;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress.update(std::isfinite(until) ? sim->time() : double(steps),
                    fmt::format("{:.0f} steps/s", wall > 0 ? steps / wall : 0.0));
  }
  progress.finish();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const RunSummary summary = make_summary(*sim, steps, wall, o.threads);
  if (!o.quiet || o.stats_json.empty()) print_summary(summary, stdout);
  if (!o.stats_json.empty()) {
    const std::string text = summary_json(summary);
    io::write_file_atomic(o.stats_json, [&](std::ostream& os) { os << text << "\n"; });
  }
  return 0;
}
}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "Run a scene headless and print a summary");
  cmd->add_option("scene", o->scene, "Scene file or built-in name (see `rtsph scenes`)")->required();
  cmd->add_option("--until", o->until, "Stop at this simulated time (s); default: the scene's end_time");
  cmd->add_option("--steps", o->steps, "Stop after this many steps");
  cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--set", o->sets, "Override a scene parameter, e.g. --set fluid.spacing=0.01");
  cmd->add_option("--export", o->export_dir, "Write frames into this directory");
  cmd->add_option("--every", o->every, "Simulated seconds between exported frames")->check(CLI::PositiveNumber);
  cmd->add_option("--format", o->format, "Export format: csv, vtk or ply");
  cmd->add_option("--attributes", o->attributes, "Exported arrays: all or a list of position,velocity,density,pressure,id");
  cmd->add_option("--stats-json", o->stats_json, "Write the summary as JSON to this file");
  cmd->add_flag("--quiet", o->quiet, "No progress and no summary on the terminal");
  cmd->callback([o, &exit_code] { exit_code = guarded([&] { return run(*o); }); });
}

}  // namespace rtsph::app
