#pragma once
// The end-of-run summary shared by `run` (text and --stats-json) and by `bench`.
#include <cstdio>
#include <functional>
#include <string>

#include "solvers/simulation.h"

namespace rtsph::app {

struct RunSummary {
  std::string scene;
  std::string method;
  int dimension = 3;
  std::size_t fluid_particles = 0, boundary_particles = 0;
  long long steps = 0;
  double sim_time_s = 0, wall_s = 0, fluid_particle_steps_per_s = 0;
  double max_density_error = 0;
  double mean_density_error = 0;  // last step
  double mean_pressure_iterations = 0, mean_divergence_iterations = 0;  // per step, over the run
  unsigned long long capped_steps = 0;  // DFSPH: steps whose solve stopped at its iteration cap
  unsigned long long particles_put_back = 0;
  int threads = 0;
  std::size_t bytes = 0;
  // `run` only: how the run ended ("completed", "interrupted", "unstable", "io-error"), the
  // retries --recover made, and the last checkpoint written (empty: none).
  std::string status = "completed";
  double unstable_at_s = -1;  // "unstable": the time it failed at (the summary is of the saved last good state)
  int retries = 0;
  std::string checkpoint;
};

RunSummary make_summary(const Simulation& sim, long long steps, double wall_s, int threads);
void print_summary(const RunSummary& s, std::FILE* out);
std::string summary_json(const RunSummary& s);

/// Runs body and maps failures to exit codes with a one-line message on stderr:
/// bad input (scene, arguments, checkpoint) → 2; I/O and other errors → 1.
int guarded(const std::function<int()>& body);

}  // namespace rtsph::app
