#include "solvers/health.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rtsph {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// No NaN or Inf in a[0, n): a float is non-finite exactly when its exponent bits are all ones.
/// The integer OR-reduction vectorises, so the common (healthy) case is one fast pass.
bool all_finite(const float* a, std::size_t n) {
  std::uint32_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t b;
    std::memcpy(&b, &a[i], sizeof b);
    bad |= std::uint32_t((b & 0x7f800000u) == 0x7f800000u);
  }
  return bad == 0;
}

bool any_above(const float* a, std::size_t n, float limit) {
  std::uint32_t above = 0;
  for (std::size_t i = 0; i < n; ++i) above |= std::uint32_t(a[i] > limit);
  return above != 0;
}

std::size_t first_non_finite(const float* a, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(a[i])) return i;
  return n;
}

}  // namespace

std::optional<HealthIssue> check_health(const Simulation& sim, double max_density_error) {
  // A backend that knows all is well without handing over its particles says so; only a
  // problem is worth the read-back that finds which particle it is.
  if (const auto facts = sim.health_facts();
      facts && !facts->non_finite && facts->max_density <= float(sim.spec().rest_density * (1.0 + max_density_error)))
    return std::nullopt;
  const ParticleView f = sim.fluid();
  const std::size_t n = f.count;
  if (n == 0) return std::nullopt;
  std::optional<HealthIssue> issue;

  auto report = [&](HealthIssue::Kind kind, const char* quantity, std::size_t i, double value) {
    HealthIssue h;
    h.kind = kind;
    h.quantity = quantity;
    h.index = i;
    h.id = f.id ? f.id[i] : std::uint32_t(i);
    for (int k = 0; k < f.dim; ++k) h.position[k] = f.x[k][i];
    h.value = value;
    issue = h;
  };

  struct Array { const float* data; const char* name; };
  std::vector<Array> arrays;
  for (int k = 0; k < f.dim; ++k) arrays.push_back({f.x[k], "position"});
  for (int k = 0; k < f.dim; ++k) arrays.push_back({f.v[k], "velocity"});
  arrays.push_back({f.density, "density"});
  arrays.push_back({f.pressure, "pressure"});
  for (const auto& a : arrays) {
    if (!a.data || all_finite(a.data, n)) continue;
    const std::size_t i = first_non_finite(a.data, n);
    if (i < n) {
      report(HealthIssue::Kind::NonFinite, a.name, i, a.data[i]);
      break;
    }
  }

  // A compressible gas has no rest density to be compressed beyond: only non-finite values.
  if (!issue && f.density && sim.spec().method != "gas") {
    const double rho0 = sim.spec().rest_density;
    const float limit = float(rho0 * (1.0 + max_density_error));
    if (!any_above(f.density, n, limit)) return std::nullopt;
    float worst = f.density[0];
    std::size_t at = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (f.density[i] > worst) { worst = f.density[i]; at = i; }
    const double err = double(worst) / rho0 - 1.0;
    if (err > max_density_error) report(HealthIssue::Kind::Compression, "density", at, err);
  }
  if (!issue) return std::nullopt;

  const SimStats st = sim.stats();
  issue->time_s = st.time_s;
  issue->dt_s = st.dt_s;
  issue->step = st.steps;
  issue->cause = likely_instability_cause(sim, *issue);
  std::string what;
  if (issue->kind == HealthIssue::Kind::NonFinite) {
    what = "non-finite " + issue->quantity + " (" + num(issue->value) + ")";
  } else {
    what = "density error " + num(100 * issue->value) + " % (limit " + num(100 * max_density_error) + " %)";
  }
  std::string pos = num(issue->position[0]);
  for (int k = 1; k < f.dim; ++k) pos += ", " + num(issue->position[k]);
  issue->message = "unstable at t = " + num(issue->time_s) + " s, step " + std::to_string(issue->step) +
                   ": " + what + " at particle " + std::to_string(issue->id) + " (" + pos +
                   ") m, dt = " + num(issue->dt_s) + " s; likely cause: " + issue->cause;
  return issue;
}

std::optional<std::string> check_health_message(const Simulation& sim, double max_density_error) {
  if (auto h = check_health(sim, max_density_error)) return h->message;
  return std::nullopt;
}

std::string likely_instability_cause(const Simulation& sim, const HealthIssue& issue) {
  // An iterative method that gave up names its own failure first.
  const std::string failure = sim.solver_failure();
  if (!failure.empty()) return failure;
  const SimSpec& s = sim.spec();
  const SimStats st = sim.stats();
  const double h = st.h, c0 = st.c0, dt = issue.dt_s > 0 ? issue.dt_s : st.dt_s;
  const int D = sim.dimension();
  // The solver's own limits (Monaghan 1992), evaluated with the fluid at rest: acoustic
  // 0.4·h/c0, body force 0.25·sqrt(h/|g|), viscous 0.125·h²/ν.
  // Only WCSPH is bound by the speed of sound; PBF and DFSPH solve for the pressure.
  const bool wcsph = s.method == "wcsph";
  const double acoustic = wcsph && c0 > 0 ? 0.4 * h / c0 : 0;
  const double g = norm(s.gravity);
  const double force = g > 0 ? 0.25 * std::sqrt(h / g) : 0;
  const double nu = std::max(s.viscosity, s.artificial_viscosity * c0 * h / (2.0 * (D + 2)));
  const double viscous = nu > 0 ? 0.125 * h * h / nu : 0;
  const bool fixed = s.time_step_mode == TimeStepMode::Fixed;
  const char* fix = fixed ? "lower solver.time_step.dt or use solver.time_step.mode=cfl"
                          : "lower solver.time_step.cfl / max_dt";
  if (acoustic > 0 && dt > acoustic * 1.0001) {
    return "dt " + num(dt) + " s is above the CFL limit " + num(acoustic) + " s for c0 = " + num(c0) +
           " m/s and h = " + num(h) + " m (" + fix + ")";
  }
  if (force > 0 && dt > force * 1.0001) {
    return "dt " + num(dt) + " s is above the body-force limit " + num(force) + " s for |g| = " + num(g) +
           " m/s² (" + fix + ")";
  }
  if (viscous > 0 && dt > viscous * 1.0001) {
    return "dt " + num(dt) + " s is above the viscous limit " + num(viscous) + " s for ν = " + num(nu) +
           " m²/s (" + fix + ")";
  }
  if (!wcsph) {
    const bool pbf = s.method == "pbf";
    return std::string("the ") + (pbf ? "PBF" : "DFSPH") + " pressure solve cannot keep up with the flow " +
           "(fastest particle " + num(st.max_speed) + " m/s, dt " + num(dt) + " s): " +
           (pbf ? "raise solver.pbf.iterations or solver.pbf.substeps"
                : "raise solver.dfsph.max_iterations or lower solver.time_step.cfl");
  }
  if (issue.kind == HealthIssue::Kind::Compression || st.max_speed > 0.3 * c0) {
    return "the speed of sound c0 = " + num(c0) + " m/s is too low for the flow (fastest particle " +
           num(st.max_speed) + " m/s; WCSPH needs about 10x the flow speed): raise solver.speed_of_sound" +
           (s.eos == Eos::Linear ? " or solver.stiffness" : "") +
           ", or slow down the obstacles/emitters that drive the fluid";
  }
  return "no time-step limit is exceeded (dt " + num(dt) + " s, acoustic limit " + num(acoustic) +
         " s); a fast obstacle, an emitter inside the fluid or too few boundary layers can push "
         "particles through walls - try a smaller dt";
}

void StateSnapshot::capture(Simulation& sim) {
  const auto fields = sim.state_fields();
  fields_.resize(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    fields_[i].name = fields[i].name;
    const auto* p = static_cast<const unsigned char*>(fields[i].data);
    fields_[i].bytes.assign(p, p + fields[i].bytes);
  }
  fluid_count_ = sim.fluid().count;
  time_ = sim.time();
  step_ = sim.step_count();
}

void StateSnapshot::restore(Simulation& sim) const {
  if (fields_.empty()) throw std::logic_error("StateSnapshot::restore: no state captured");
  // Names first, so that a snapshot of another solver or scene leaves `sim` untouched; sizes
  // are known only after prepare_state().
  const auto before = sim.state_fields();
  if (before.size() != fields_.size()) throw std::logic_error("StateSnapshot::restore: field count differs");
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (before[i].name != fields_[i].name) throw std::logic_error("StateSnapshot::restore: field '" + before[i].name + "' differs");
  }
  sim.prepare_state(fluid_count_);
  const auto fields = sim.state_fields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].name != fields_[i].name || fields[i].bytes != fields_[i].bytes.size()) {
      throw std::logic_error("StateSnapshot::restore: field '" + fields[i].name + "' differs");
    }
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].bytes) std::memcpy(fields[i].data, fields_[i].bytes.data(), fields[i].bytes);
  }
  sim.state_loaded();
}

std::size_t StateSnapshot::bytes() const {
  std::size_t b = 0;
  for (const auto& f : fields_) b += f.bytes.size();
  return b;
}

}  // namespace rtsph
