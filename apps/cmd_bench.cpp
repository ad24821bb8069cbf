// `rtsph bench`: the dam break at several sizes; ms/step by stage and throughput.
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "apps/bench.h"
#include "apps/commands.h"
#include "apps/run_summary.h"
#include "apps/sim_backend.h"
#include "io/atomic_file.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

namespace rtsph::app {

SimSpec dam_break_with(int dim, double n, const std::string& method, const std::vector<std::string>& sets) {
  SimSpec s = load_scene(dim == 2 ? "dam_break_2d" : "dam_break_3d");
  double volume = 0;
  for (const auto& b : s.fluid_blocks) {
    double v = 1;
    for (int k = 0; k < dim; ++k) v *= b.max[k] - b.min[k];
    volume += v;
  }
  s.spacing = std::pow(volume / n, 1.0 / dim);
  s.smoothing_ratio = 1.0;
  s.kernel = KernelType::CubicSpline;
  s.method = method;
  for (const auto& a : sets) {
    const std::string key = a.substr(0, a.find('='));
    if (key == "fluid.spacing" || key == "solver.method")
      throw std::invalid_argument(fmt::format("--set {}: rtsph bench sets {} itself (use {})", a, key,
                                              key == "fluid.spacing" ? "--particles" : "--method"));
    apply_override(s, a);
  }
  return s;
}

SimSpec star_with(double n, const std::string& gravity) {
  SimSpec s = load_scene("polytrope_star_3d");
  const double radius = 1.0;  // the scene's sphere, inscribed in [-1, 1]³
  s.spacing = std::cbrt(4.0 / 3.0 * std::numbers::pi * radius * radius * radius / n);
  s.gravity_solver = gravity == "tree" ? GravitySolver::Tree : GravitySolver::Direct;
  return s;
}

namespace {
// PBF's constraint iterations or DFSPH's density-solve iterations over the run so far.
double total_pressure_iterations(const Simulation& sim) {
  const SimStats st = sim.stats();
  return st.mean_pressure_iterations * double(sim.step_count());
}

int bench(const BenchOptions& o) {
  std::vector<double> sizes;
  std::stringstream ss(o.particles);
  for (std::string item; std::getline(ss, item, ',');) {
    try {
      sizes.push_back(std::stod(item));
    } catch (const std::exception&) {
      throw std::invalid_argument(fmt::format("--particles: '{}': expected a comma-separated list of counts", item));
    }
    if (!(sizes.back() >= 1 && sizes.back() <= 1e9))
      throw std::invalid_argument(fmt::format("--particles: '{}': expected counts in [1, 1e9]", item));
  }
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  if (!o.gravity.empty())
    fmt::print("rtsph bench: 3D n = 1 polytrope, gas, self-gravity by {} (in 'forces'), {} threads, "
               "{} steps, backend {}\n", o.gravity, threads, o.steps, o.backend);
  else
    fmt::print("rtsph bench: {}D dam break, {}, cubic spline, h = spacing, {} threads, {} steps, backend {}\n",
               o.dim, o.method, threads, o.steps, o.backend);
  if (o.backend == "gpu")
    fmt::print("(stage columns: a second run of as many steps, waiting for the GPU at each stage's start "
               "and end; 'other' is what that run spent outside them: reductions, read-backs)\n");
  fmt::print("{:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>6} {:>12} {:>8}\n", "fluid", "boundary",
             "ms/step", "neigh", "density", "forces", "integr", "other", "iter", "particle-st/s", "B/part");
  nlohmann::ordered_json rows = nlohmann::json::array();
  for (double n : sizes) {
    const SimSpec spec = o.gravity.empty() ? dam_break_with(o.dim, n, o.method, o.sets) : star_with(n, o.gravity);
    auto sim = BackendSimulation::make(spec, threads, o.backend);
    for (int i = 0; i < 3; ++i) sim->step();  // warm caches and allocations
    sim->wait_idle();
    sim->reset_stage_times();
    const double iterations_before = total_pressure_iterations(*sim);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < o.steps; ++i) sim->step();
    sim->wait_idle();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double iterations = (total_pressure_iterations(*sim) - iterations_before) / o.steps;
    const auto st = sim->stats();
    // The GPU queues each stage and returns: its stage times come from a second run that waits
    // for the device around each stage (slower in all; the throughput is the first run's).
    double staged_wall = wall;
    if (sim.backend() == "gpu") {
      sim->reset_stage_times();
      sim->set_stage_sync(true);
      const auto t1 = std::chrono::steady_clock::now();
      for (int i = 0; i < o.steps; ++i) sim->step();
      sim->wait_idle();
      staged_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      sim->set_stage_sync(false);
    }
    const auto& tm = sim->stage_times();
    const double per = 1e3 / o.steps;
    const double other = std::max(0.0, staged_wall - tm.total()) * per;
    const double rate = double(st.fluid_particles) * o.steps / wall;
    const double bpp = double(st.bytes) / double(st.fluid_particles);
    const bool iterative = st.method == "pbf" || st.method == "dfsph";
    fmt::print("{:>9} {:>9} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>6} {:>12.3g} {:>8.0f}\n",
               st.fluid_particles, st.boundary_particles, wall * per, tm.neighbours_s * per,
               tm.density_s * per, tm.forces_s * per, tm.integrate_s * per, other,
               iterative ? fmt::format("{:.1f}", iterations) : std::string("-"), rate, bpp);
    std::fflush(stdout);
    nlohmann::ordered_json row = {{"fluid_particles", st.fluid_particles},
                                  {"boundary_particles", st.boundary_particles},
                                  {"ms_per_step", wall * per},
                                  {"neighbours_ms", tm.neighbours_s * per},
                                  {"density_ms", tm.density_s * per},
                                  {"forces_ms", tm.forces_s * per},
                                  {"integrate_ms", tm.integrate_s * per},
                                  {"other_ms", other},
                                  {"fluid_particle_steps_per_s", rate},
                                  {"bytes_per_particle", bpp}};
    if (iterative) row["mean_pressure_iterations"] = iterations;
    rows.push_back(row);
  }
  if (!o.json.empty()) {
    nlohmann::ordered_json j;
    j["dimension"] = o.gravity.empty() ? o.dim : 3;
    j["method"] = o.gravity.empty() ? o.method : "gas";
    if (!o.gravity.empty()) j["gravity"] = o.gravity;
    j["threads"] = threads;
    j["backend"] = o.backend;
    j["steps"] = o.steps;
    j["set"] = o.sets;
    j["rows"] = rows;
    io::write_file_atomic(o.json, [&](std::ostream& os) { os << j.dump(2) << "\n"; });
  }
  return 0;
}
}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench", "Benchmark the dam break at several particle counts");
  cmd->add_option("--dim", o->dim, "Dimension (2 or 3)")->check(CLI::IsMember({2, 3}));
  cmd->add_option("--particles", o->particles, "Comma-separated fluid particle counts");
  cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--steps", o->steps, "Timed steps per size")->check(CLI::Range(1, 1000000));
  cmd->add_option("--method", o->method, "Solver method")->check(CLI::IsMember(solver_methods()));
  cmd->add_option("--backend", o->backend, "Where the solver runs: cpu or gpu (OpenGL compute through EGL)")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  cmd->add_option("--json", o->json, "Write the table as JSON to this file");
  cmd->add_option("--gravity", o->gravity,
                  "Benchmark self-gravity instead: the n = 1 polytrope (gas method) with gravity "
                  "by direct summation or the Barnes-Hut tree")
      ->check(CLI::IsMember({"direct", "tree"}));
  cmd->add_option("--set", o->sets, "Override a parameter of the benched dam break, e.g. --set solver.pbf.substeps=2");
  cmd->add_flag("--realtime", o->realtime,
                "Search for the largest dam break this method runs in real time");
  cmd->add_option("--window", o->window_s, "Simulated seconds each --realtime probe measures")
      ->check(CLI::Range(0.05, 100.0));
  cmd->callback([o, &exit_code] {
    exit_code = guarded([&] {
      if (!o->sets.empty() && !o->gravity.empty())
        throw std::invalid_argument("--set applies to the dam break, not to --gravity");
      if (!o->sets.empty()) (void)dam_break_with(o->dim, 1000, o->method, o->sets);  // bad --set: one line, before any output
      if (!o->json.empty()) io::check_file_target(o->json);  // before the runs (minutes with --realtime), not after
      return o->realtime ? bench_realtime(*o) : bench(*o);
    });
  });
}

}  // namespace rtsph::app
