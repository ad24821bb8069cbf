#include "scene/realtime_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "solvers/geometry.h"
#include "solvers/simulation.h"

namespace rtsph {

double realtime_particle_substeps_per_thread(int dimension) {
  // `rtsph view dam_break_{2,3}d --frames 300 --report` under Xvfb, 1 solver thread (the
  // viewer's default on 2 cores), llvmpipe on the other, 2026-11-25: 3D, the scene's 2 PBF
  // substeps per 1/60 s frame (120 per second), 3 to 4 iterations: 10,350 particles kept up in
  // 5 runs of 5 (real-time factor 0.992-1.000, never behind). 2D, 4 substeps (240 per second):
  // 2026-11-24, 1.00 at 3,200 and 0.96 at 5,000 with the default iterations, budget 4,000
  // (docs/performance.md).
  return dimension == 3 ? 10500.0 * 120 : 4000.0 * 240;
}

double realtime_budget(const SimSpec& pbf_spec, int solver_threads, double rate_per_thread) {
  const double substeps_per_s = std::max(1, pbf_spec.pbf_substeps) / pbf_spec.pbf_time_step;
  const double rate = rate_per_thread > 0 ? rate_per_thread
                                          : realtime_particle_substeps_per_thread(pbf_spec.dimension);
  return rate * std::max(1, solver_threads) / substeps_per_s;
}

double median_substep_seconds(Simulation& sim, double wall_s) {
  using clock = std::chrono::steady_clock;
  sim.step();  // the first substep sizes the scratch; not timed
  sim.wait_idle();
  std::vector<double> times;
  const auto start = clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  // At least five substeps, then on until wall_s (at most 200).
  while (times.size() < 5 || (times.size() < 200 && elapsed() < wall_s)) {
    const auto t0 = clock::now();
    sim.step();
    sim.wait_idle();
    times.push_back(std::chrono::duration<double>(clock::now() - t0).count());
  }
  // The median: a shared machine's hiccup moves the mean of so few substeps.
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return std::max(times[times.size() / 2], 1e-9);
}

StepProbe probe_substeps(Simulation& sim, double wall_s) {
  return {double(sim.stats().fluid_particles), median_substep_seconds(sim, wall_s)};
}

namespace {

// particles_in_time without its bound: where the line through the nearest probes reaches the time
// (0 when nothing fits, or no probe is usable).
double on_the_line(std::vector<StepProbe> probes, double want) {
  std::erase_if(probes, [](const StepProbe& p) { return !(p.seconds > 0) || !(p.particles > 0); });
  if (probes.empty() || !(want > 0)) return 0;
  // The two probes whose times are nearest the one asked about: the line is local.
  std::sort(probes.begin(), probes.end(), [want](const StepProbe& a, const StepProbe& b) {
    return std::abs(a.seconds - want) < std::abs(b.seconds - want) ||
           (std::abs(a.seconds - want) == std::abs(b.seconds - want) && a.particles < b.particles);
  });
  const StepProbe& p0 = probes[0];
  double n = p0.particles * want / p0.seconds;  // t ∝ N through the nearest probe
  if (probes.size() >= 2 && probes[1].particles != p0.particles) {
    const StepProbe& p1 = probes[1];
    const double b = (p1.seconds - p0.seconds) / (p1.particles - p0.particles);
    if (b > 0) {
      const double a = p0.seconds - b * p0.particles;
      n = a >= want ? 0 : (want - a) / b;  // a ≥ want: the fixed part alone is over the time
    }
  }
  return std::max(n, 0.0);
}

}  // namespace

double particles_in_time(std::vector<StepProbe> probes, double seconds_per_substep) {
  double largest = 0;
  for (const StepProbe& p : probes)
    if (p.seconds > 0) largest = std::max(largest, p.particles);
  return std::min(on_the_line(std::move(probes), seconds_per_substep), 2 * largest);
}

DeviceBudget measure_device_budget(const SimSpec& profile, double share, double finest,
                                   const std::function<StepProbe(const SimSpec&)>& probe) {
  DeviceBudget out;
  const double substeps_per_s = std::max(1, profile.pbf_substeps) / profile.pbf_time_step;
  const double target = share / substeps_per_s;  // wall seconds a substep may take
  double spacing = profile.spacing;
  for (int round = 0; round < 4; ++round) {
    SimSpec s = profile;
    s.spacing = spacing;
    const StepProbe p = probe(s);
    if (!(p.particles > 0) || !(p.seconds > 0)) break;
    const bool again = std::any_of(out.probes.begin(), out.probes.end(),
                                   [&](const StepProbe& q) { return q.particles == p.particles; });
    out.probes.push_back(p);
    if (again) break;  // the lattice's rounding gave a size already probed: nothing new to learn
    if (std::abs(p.seconds - target) < 0.2 * target) break;  // close enough: the fit is local
    // The next size from the line itself (particles_in_time's bound would only double it).
    const double next = std::clamp(on_the_line(out.probes, target), p.particles / 8, 8 * p.particles);
    const double to = std::max(finest, spacing * std::pow(p.particles / next, 1.0 / profile.dimension));
    if (std::abs(to - spacing) < 0.02 * spacing) break;  // the next size would be this one
    spacing = to;
  }
  out.particles = particles_in_time(out.probes, target);
  out.rate = out.particles * substeps_per_s;
  return out;
}

DeviceBudget dam_break_device_budget(int dimension, const std::function<StepProbe(const SimSpec&)>& probe) {
  const SimSpec dam = load_scene(dimension == 3 ? "dam_break_3d" : "dam_break_2d");
  return measure_device_budget(realtime_profile(dam, 1).spec, realtime_calm_share(dimension),
                               kRealtimeFinest * dam.spacing, probe);
}

std::string DeviceBudget::describe() const {
  std::string s;
  for (const StepProbe& p : probes)
    s += fmt::format("{}{:.0f} particles {:.2f} ms", s.empty() ? "" : ", ", p.particles, 1e3 * p.seconds);
  return s;
}

double measure_particle_substeps_per_thread(const SimSpec& profile_spec, int threads, double wall_s) {
  SimSpec spec = profile_spec;
  spec.backend = "cpu";
  const std::unique_ptr<Simulation> sim = make_simulation(spec, threads);
  const double fluid = double(sim->stats().fluid_particles);
  if (fluid <= 0) return 0;
  return fluid / median_substep_seconds(*sim, wall_s) / std::max(1, threads);
}

double realtime_calm_share(int dimension) { return dimension == 3 ? 0.75 : 0.6; }

double calibrated_rate(double measured_per_thread, int dimension) {
  const double reference = realtime_particle_substeps_per_thread(dimension);
  if (!(measured_per_thread > 0)) return reference;
  return std::clamp(realtime_calm_share(dimension) * measured_per_thread, reference / 16, 2 * reference);
}

std::string RealtimeProfile::describe() const {
  if (!applied) return "as written";
  return fmt::format("real-time profile: pbf ({}-{} iterations), fluid.spacing {:.4g} m, {:.0f} fluid "
                     "particles at most, emitters included (budget {:.0f}, from {:.3g} particle-substeps/s "
                     "{}, {})",
                     spec.pbf_iterations, std::max(spec.pbf_iterations, spec.pbf_max_iterations),
                     spec.spacing, fluid_particles, budget, rate_per_thread, rate_per, rate_source);
}

namespace {

// The scene at spacing s, with each emitter's particle cap scaled so that it still emits the
// same volume of water (a cap is a count, and a coarser particle holds more water).
SimSpec at_spacing(const SimSpec& scene, double s) {
  SimSpec out = scene;
  out.spacing = s;
  const double volume_ratio = std::pow(scene.spacing / s, scene.dimension);
  for (auto& e : out.emitters)
    e.max_particles = std::int64_t(std::floor(double(e.max_particles) * volume_ratio));
  return out;
}

// Fluid at the start plus the most the emitters may add.
double particles(const SimSpec& s) {
  const ParticleCounts c = count_particles(s);
  return c.fluid + c.emitted_max;
}

}  // namespace

RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads, double rate_per_thread, bool finer) {
  RealtimeProfile r{scene};
  r.fluid_particles = particles(scene);
  if (!scene.viewer_realtime) return r;
  r.applied = true;
  apply_override(r.spec, "solver.method=pbf", "viewer.realtime");
  // A bounded iteration count bounds the cost of the violent steps, which are the ones that fall
  // behind real time: 3 Jacobi iterations, more while the mean compression is above
  // solver.pbf.max_density_error, at most 4 (Macklin & Müller's range). 3D dam break, 10,695
  // particles, 1 thread, 7.4 s: 4.15 iterations per substep with the defaults (4 to 20), 3.50
  // with these; worst density error 14.0% → 17.7%, mean at the end 0.72% → 0.78%.
  r.spec.pbf_iterations = std::min(r.spec.pbf_iterations, kRealtimePbfIterations);
  r.spec.pbf_max_iterations = std::min(r.spec.pbf_max_iterations, kRealtimePbfMaxIterations);
  if (rate_per_thread > 0) r.rate_source = "given";
  r.rate_per_thread = rate_per_thread > 0 ? rate_per_thread : realtime_particle_substeps_per_thread(scene.dimension);
  r.budget = realtime_budget(r.spec, solver_threads, r.rate_per_thread);
  // The count scales as spacing^-D; a few rounds absorb the lattice's rounding at block edges.
  double spacing = scene.spacing;
  for (int round = 0; round < 20 && r.fluid_particles > r.budget; ++round) {
    spacing *= std::max(1.01, std::pow(r.fluid_particles / r.budget, 1.0 / scene.dimension));
    r.fluid_particles = particles(at_spacing(r.spec, spacing));
  }
  // Finer where the budget holds more: the smallest spacing whose water still fits, by bisection
  // (the count falls as the spacing grows; lo never fits, hi always does).
  if (finer && spacing == scene.spacing && r.fluid_particles < r.budget) {
    double lo = kRealtimeFinest * scene.spacing, hi = scene.spacing;
    if (particles(at_spacing(r.spec, lo)) <= r.budget) hi = lo;
    for (int i = 0; i < 40 && hi > lo && hi - lo > 1e-4 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (particles(at_spacing(r.spec, mid)) <= r.budget ? hi : lo) = mid;
    }
    spacing = hi;
  }
  if (spacing != scene.spacing) {
    r.spec = at_spacing(r.spec, spacing);
    r.spec = parse_scene(scene_to_json(r.spec), "viewer.realtime");  // validated like any override
  }
  r.fluid_particles = particles(r.spec);
  return r;
}

}  // namespace rtsph
