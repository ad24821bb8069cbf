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

double realtime_flow_speed(const SimSpec& spec, bool jets_only) {
  const double g = norm(spec.gravity);
  const Vec3d up = g > 0 ? spec.gravity * (-1.0 / g) : Vec3d{};
  // The extremes of a box's corners along `up`.
  auto along = [&](const Vec3d& lo, const Vec3d& hi, bool top) {
    double h = 0;
    for (int d = 0; d < 3; ++d) h += up[d] * ((up[d] > 0) == top ? hi[d] : lo[d]);
    return h;
  };
  // The floor: the container's, unless it is open or periodic along gravity; then the water's own
  // lowest point (what it falls onto is not known).
  bool walled = !spec.open;
  for (int d = 0; d < 3; ++d)
    if (up[d] != 0 && axis_is_periodic(spec.periodic, d)) walled = false;
  double floor = walled ? along(spec.domain_min, spec.domain_max, false) : 1e300;
  if (!walled)
    for (const FluidBlock& b : spec.fluid_blocks) floor = std::min(floor, along(b.min, b.max, false));
  auto fall = [&](double height) { return floor < 1e300 && height > floor ? 2 * g * (height - floor) : 0.0; };
  // A column's front (Ritter), a block's own speed after its fall, a jet's after its fall.
  double v2 = 0;
  for (const FluidBlock& b : spec.fluid_blocks) {
    if (jets_only) break;
    const double h = along(b.min, b.max, true);
    v2 = std::max({v2, 2 * fall(h), dot(b.velocity, b.velocity) + fall(h)});
  }
  for (const EmitterSpec& e : spec.emitters) v2 = std::max(v2, e.speed * e.speed + fall(dot(up, e.position)));
  return std::sqrt(v2);
}

double realtime_substeps_per_second(const SimSpec& pbf_spec, bool jets_only) {
  const double frame = std::max(1, pbf_spec.pbf_substeps) / pbf_spec.pbf_time_step;
  if (!(pbf_spec.pbf_cfl > 0) || !(pbf_spec.spacing > 0)) return frame;
  return std::max(frame, realtime_flow_speed(pbf_spec, jets_only) / (pbf_spec.pbf_cfl * pbf_spec.spacing));
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

// A substep's time at N particles from the probes: probes of one size read as their mean; the
// cost never falls with N, so each probe reads as at most the time of any larger one (a slow
// outlier at a small size is noise); then the polyline through them, the first segment's line
// below the smallest, and beyond the largest the last segment's line where it rises, t ∝ N
// where it does not (a flat end would read as all fixed cost, whatever the size). Past
// `largest` times the largest size probed: infinite (the line is not trusted far beyond what was
// measured).
double seconds_at(std::vector<StepProbe> probes, double n, double largest) {
  std::erase_if(probes, [](const StepProbe& p) { return !(p.seconds > 0) || !(p.particles > 0); });
  if (probes.empty()) return HUGE_VAL;
  std::sort(probes.begin(), probes.end(),
            [](const StepProbe& a, const StepProbe& b) { return a.particles < b.particles; });
  std::vector<StepProbe> merged;
  for (std::size_t i = 0; i < probes.size();) {
    std::size_t j = i;
    double sum = 0;
    for (; j < probes.size() && probes[j].particles == probes[i].particles; ++j) sum += probes[j].seconds;
    merged.push_back({probes[i].particles, sum / double(j - i)});
    i = j;
  }
  probes.swap(merged);
  for (std::size_t i = probes.size() - 1; i-- > 0;)
    probes[i].seconds = std::min(probes[i].seconds, probes[i + 1].seconds);
  const StepProbe& last = probes.back();
  if (n > largest * last.particles) return HUGE_VAL;
  if (probes.size() == 1) return last.seconds * n / last.particles;
  std::size_t i = 1;
  while (i + 1 < probes.size() && probes[i].particles < n) ++i;
  const StepProbe &a = probes[i - 1], &b = probes[i];
  if (n > b.particles && b.seconds <= a.seconds) return b.seconds * n / b.particles;
  return std::max(0.0, a.seconds + (b.seconds - a.seconds) * (n - a.particles) / (b.particles - a.particles));
}

}  // namespace

double particles_in_real_time(const std::vector<StepProbe>& probes, double share, double largest,
                              const std::function<double(double)>& substeps_at) {
  double top = 0;
  for (const StepProbe& p : probes)
    if (p.seconds > 0) top = std::max(top, p.particles);
  auto fits = [&](double n) { return seconds_at(probes, n, largest) * substeps_at(n) <= share; };
  if (!(top > 0) || !fits(0)) return 0;
  double lo = 0, hi = largest * top;
  if (fits(hi)) return hi;
  for (int i = 0; i < 60 && hi - lo > 1e-6 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

DeviceBudget measure_device_budget(const SimSpec& profile, double share, double finest,
                                   const std::function<StepProbe(const SimSpec&)>& probe) {
  DeviceBudget out;
  // Substeps per second at N particles: the spacing from the first probe's (N ∝ spacing^-D); no
  // particles, an infinite spacing: the frame's.
  double n0 = 0;
  auto substeps_at = [&](double n) {
    SimSpec s = profile;
    if (!(n > 0) || !(n0 > 0)) s.pbf_cfl = 0;
    else s.spacing = profile.spacing * std::pow(n0 / n, 1.0 / profile.dimension);
    return realtime_substeps_per_second(s);
  };
  double spacing = profile.spacing;
  for (int round = 0; round < 4; ++round) {
    SimSpec s = profile;
    s.spacing = spacing;
    const StepProbe p = probe(s);
    if (!(p.particles > 0) || !(p.seconds > 0)) break;
    if (n0 == 0) n0 = p.particles;
    const bool again = std::any_of(out.probes.begin(), out.probes.end(),
                                   [&](const StepProbe& q) { return q.particles == p.particles; });
    out.probes.push_back(p);
    if (again) break;  // the lattice's rounding gave a size already probed: nothing new to learn
    const double target = share / realtime_substeps_per_second(s);  // wall seconds a substep may take
    if (std::abs(p.seconds - target) < 0.2 * target) break;  // close enough: the fit is local
    // The next size from the probes' line, up to 8 times this one (the answer's bound, twice the
    // largest size probed, would only double it).
    const double next = std::clamp(particles_in_real_time(out.probes, share, 8, substeps_at), p.particles / 8,
                                   8 * p.particles);
    const double to = std::max(finest, spacing * std::pow(p.particles / next, 1.0 / profile.dimension));
    if (std::abs(to - spacing) < 0.02 * spacing) break;  // the next size would be this one
    spacing = to;
  }
  out.particles = particles_in_real_time(out.probes, share, 2, substeps_at);
  out.rate = out.particles * substeps_at(out.particles);
  return out;
}

DeviceBudget dam_break_device_budget(int dimension, const std::function<StepProbe(const SimSpec&)>& probe) {
  const SimSpec dam = load_scene(dimension == 3 ? "dam_break_3d" : "dam_break_2d");
  // From the CPU reference size, with the scene's iterations (the device profile keeps them) at
  // the count they average in the flow: from rest the 1% stop runs to its cap at large sizes.
  SimSpec start = realtime_profile(dam, 1).spec;
  start.pbf_iterations = start.pbf_max_iterations = kDeviceProbeIterations;
  return measure_device_budget(start, realtime_device_share(dimension), kRealtimeFinest * dam.spacing, probe);
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

double realtime_calm_share(int dimension) { return dimension == 3 ? 0.85 : 0.6; }

double realtime_device_share(int dimension) { return dimension == 3 ? 0.4 : 0.6; }

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

RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads, double rate_per_thread, bool device) {
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
  // Not on a device, whose sizes are where the cap fails: at 395,352 particles (3 iterations) the
  // 3D dam break took 2,007 substeps in its first 0.649 s, the 2D one at 54,285 5,740 in 0.072 s,
  // as the unconverged compression sped the water up (H200, 2026-11-27; docs/performance.md).
  if (!device) {
    r.spec.pbf_iterations = std::min(r.spec.pbf_iterations, kRealtimePbfIterations);
    r.spec.pbf_max_iterations = std::min(r.spec.pbf_max_iterations, kRealtimePbfMaxIterations);
  }
  if (rate_per_thread > 0) r.rate_source = "given";
  r.rate_per_thread = rate_per_thread > 0 ? rate_per_thread : realtime_particle_substeps_per_thread(scene.dimension);
  // The particles the rate keeps at a spacing: on a device, over the substeps that spacing's flow
  // asks for (realtime_substeps_per_second); on the CPU, over the frame's, or over what its
  // emitters' jets ask where that is more. A jet runs at its speed for as long as it flows, where
  // a collapse's front is a transient that the CPU's share of the measured rate absorbs (the 3D
  // dam break took 130 substeps in its first second against the frame's 120). The nozzle scenes'
  // 2.5 m/s jet, falling 0.9 m, needs 490 a second at 0.01 m, and took 800 headless (splashes off
  // the circle): budgeted at the frame's 240 the viewer ran them at a real-time factor of
  // 0.80-0.95, once 0.34 (docs/performance.md, "Session 23").
  const bool cfl_budget = device || !r.spec.emitters.empty();
  auto budget_at = [&](double spacing) {
    if (!cfl_budget) return realtime_budget(r.spec, solver_threads, r.rate_per_thread);
    SimSpec s = r.spec;
    s.spacing = spacing;
    return r.rate_per_thread * std::max(1, solver_threads) / realtime_substeps_per_second(s, /*jets_only=*/!device);
  };
  auto fits = [&](double s) { return particles(at_spacing(r.spec, s)) <= budget_at(s); };
  // The smallest spacing in [lo, hi] whose water fits, by bisection (the count falls as the
  // spacing grows, and the budget does not; hi fits).
  auto smallest_fitting = [&](double lo, double hi) {
    if (fits(lo)) return lo;
    for (int i = 0; i < 40 && hi - lo > 1e-4 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (fits(mid) ? hi : lo) = mid;
    }
    return hi;
  };
  // The count scales as spacing^-D; a few rounds absorb the lattice's rounding at block edges.
  double spacing = scene.spacing, too_fine = 0;
  r.budget = budget_at(spacing);
  for (int round = 0; round < 20 && r.fluid_particles > r.budget; ++round) {
    too_fine = spacing;
    spacing *= std::max(1.01, std::pow(r.fluid_particles / r.budget, 1.0 / scene.dimension));
    r.fluid_particles = particles(at_spacing(r.spec, spacing));
    r.budget = budget_at(spacing);
  }
  // Where the budget counts CFL substeps it grows as the spacing coarsens, so a round above can
  // overshoot: back to the smallest spacing that fits.
  if (cfl_budget && too_fine > 0 && r.fluid_particles <= r.budget) spacing = smallest_fitting(too_fine, spacing);
  // Finer where the budget holds more: the smallest spacing whose water still fits.
  if (device && spacing == scene.spacing && r.fluid_particles < r.budget)
    spacing = smallest_fitting(kRealtimeFinest * scene.spacing, scene.spacing);
  // Validated like any override. A coarse spacing can break the scene's own checks (an emitter
  // narrower than a spacing, a block thinner than one): then the spacing steps back toward the
  // scene's until they pass, over budget (a slow device runs such a scene behind real time).
  for (int round = 0; spacing != scene.spacing; ++round) {
    try {
      r.spec = parse_scene(scene_to_json(at_spacing(r.spec, spacing)), "viewer.realtime");
      break;
    } catch (const SceneError&) {
      if (round == 30) throw;
      spacing = scene.spacing + 0.9 * (spacing - scene.spacing);
    }
  }
  r.budget = budget_at(spacing);
  r.fluid_particles = particles(r.spec);
  return r;
}

}  // namespace rtsph
