#include "apps/run_summary.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include <stdexcept>

#include "io/errors.h"
#include "scene/scene.h"

namespace rtsph::app {

RunSummary make_summary(const Simulation& sim, long long steps, double wall_s, int threads) {
  const SimStats st = sim.stats();
  RunSummary s;
  s.scene = sim.spec().name;
  s.method = st.method;
  s.dimension = sim.dimension();
  s.fluid_particles = st.fluid_particles;
  s.boundary_particles = st.boundary_particles;
  s.steps = steps;
  s.sim_time_s = st.time_s;
  s.wall_s = wall_s;
  s.fluid_particle_steps_per_s = wall_s > 0 ? double(st.fluid_particles) * double(steps) / wall_s : 0;
  s.max_density_error = st.max_density_error;
  s.mean_density_error = st.mean_density_error;
  s.mean_pressure_iterations = st.mean_pressure_iterations;
  s.mean_divergence_iterations = st.mean_divergence_iterations;
  s.capped_steps = st.capped_steps;
  s.particles_put_back = st.particles_put_back;
  s.threads = threads > 0 ? threads : omp_get_max_threads();
  s.bytes = st.bytes;
  return s;
}

void print_summary(const RunSummary& s, std::FILE* out) {
  fmt::print(out,
             "scene                  {} ({}D, {})\n"
             "fluid particles        {}\n"
             "boundary particles     {}\n"
             "steps                  {}\n"
             "wall time              {:.2f} s\n"
             "simulated time         {:.4f} s\n"
             "throughput             {:.3g} fluid particle-steps/s ({} thread{})\n"
             "max density error      {:.2f} %\n"
             "mean density error     {:.3f} % (last step)\n"
             "put back into domain   {}\n",
             s.scene, s.dimension, s.method, s.fluid_particles, s.boundary_particles, s.steps, s.wall_s,
             s.sim_time_s, s.fluid_particle_steps_per_s, s.threads, s.threads == 1 ? "" : "s", 100 * s.max_density_error,
             100 * s.mean_density_error, s.particles_put_back);
  if (s.mean_pressure_iterations > 0 || s.mean_divergence_iterations > 0)
    fmt::print(out, "solver iterations      {:.2f} pressure, {:.2f} divergence (mean per step)\n",
               s.mean_pressure_iterations, s.mean_divergence_iterations);
  if (s.capped_steps > 0)
    fmt::print(out, "solves at their cap    {} of {} steps (the density or divergence error stayed above "
               "its tolerance; solver.dfsph.max_iterations)\n", s.capped_steps, s.steps);
  if (s.status == "unstable" && s.unstable_at_s >= 0)
    fmt::print(out, "status                 unstable at t = {:.6g} s (the time and errors above are the last good "
               "state's, the one saved)\n", s.unstable_at_s);
  else if (s.status != "completed")
    fmt::print(out, "status                 {}\n", s.status);
  if (s.retries > 0) fmt::print(out, "retries (dt halved)    {}\n", s.retries);
  if (!s.checkpoint.empty()) fmt::print(out, "checkpoint             {}\n", s.checkpoint);
  std::fflush(out);
}

std::string summary_json(const RunSummary& s) {
  nlohmann::ordered_json j;
  j["scene"] = s.scene;
  j["method"] = s.method;
  j["dimension"] = s.dimension;
  j["fluid_particles"] = s.fluid_particles;
  j["boundary_particles"] = s.boundary_particles;
  j["steps"] = s.steps;
  j["sim_time_s"] = s.sim_time_s;
  j["wall_s"] = s.wall_s;
  j["fluid_particle_steps_per_s"] = s.fluid_particle_steps_per_s;
  j["max_density_error"] = s.max_density_error;
  j["mean_density_error"] = s.mean_density_error;
  j["mean_pressure_iterations"] = s.mean_pressure_iterations;
  j["mean_divergence_iterations"] = s.mean_divergence_iterations;
  j["capped_steps"] = s.capped_steps;
  j["particles_put_back"] = s.particles_put_back;
  j["threads"] = s.threads;
  j["bytes"] = s.bytes;
  j["status"] = s.status;
  if (s.unstable_at_s >= 0) j["unstable_at_s"] = s.unstable_at_s;
  j["retries"] = s.retries;
  if (!s.checkpoint.empty()) j["checkpoint"] = s.checkpoint;
  return j.dump(2);
}

int guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const SceneError& e) {
    std::fprintf(stderr, "rtsph: %s\n", e.what());
    return 2;
  } catch (const io::CheckpointError& e) {
    std::fprintf(stderr, "rtsph: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "rtsph: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rtsph: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtsph: %s\n", e.what());
    return 1;
  }
}

}  // namespace rtsph::app
