#pragma once
// Instability guard, shared by `rtsph run` and the viewer: a cheap check after each step that
// the state is still physical (no NaN/Inf, no runaway compression), a diagnostic that names the
// particle and the likely cause, and an in-memory copy of the last good state to go back to.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "solvers/simulation.h"

namespace rtsph {

/// Default for the largest tolerated compression (ρ-ρ0)/ρ0. WCSPH targets about 1%; 50% means
/// the pressure solve has lost control of the fluid.
inline constexpr double kDefaultMaxDensityError = 0.5;

struct HealthIssue {
  enum class Kind { NonFinite, Compression };
  Kind kind = Kind::NonFinite;
  std::string quantity;        // "position", "velocity", "density", "pressure"
  std::size_t index = 0;       // in memory order (changes every step)
  std::uint32_t id = 0;        // particle id (stable)
  Vec3d position{};            // m (may itself be NaN)
  double value = 0;            // the bad value, or the density error for Compression
  double time_s = 0, dt_s = 0; // simulated time after the step, and the step's dt
  std::uint64_t step = 0;
  std::string cause;           // likely cause, e.g. "dt 0.05 s is above the CFL limit ..."
  std::string message;         // the whole diagnostic, one line
};

/// Scans the fluid after a step: every position, velocity, density and pressure must be finite
/// and (ρ-ρ0)/ρ0 must not exceed max_density_error. Returns the first problem found (NaN/Inf
/// before compression), or nothing for a healthy state. Cost: one pass over the fluid arrays.
std::optional<HealthIssue> check_health(const Simulation& sim,
                                        double max_density_error = kDefaultMaxDensityError);

/// The same check, reduced to the one-line diagnostic (for callers that only show it).
std::optional<std::string> check_health_message(const Simulation& sim,
                                                double max_density_error = kDefaultMaxDensityError);

/// A best guess at why a run became unstable, from the spec and the solver's current numbers,
/// e.g. "dt 0.05 s is above the CFL limit 0.0012 s for c0 = 44 m/s".
std::string likely_instability_cause(const Simulation& sim, const HealthIssue& issue);

/// A copy of every state field in memory: capture() after a healthy step, restore() to go back
/// to it (e.g. to retry with a smaller dt, or the viewer's reset). Restoring is exact: stepping
/// on from a restored state gives bitwise the same states as stepping on from the original.
class StateSnapshot {
 public:
  void capture(Simulation& sim);
  /// Throws std::logic_error if empty or taken from a solver with a different field layout.
  void restore(Simulation& sim) const;
  bool empty() const { return fields_.empty(); }
  double time() const { return time_; }
  std::uint64_t step() const { return step_; }
  std::size_t bytes() const;

 private:
  struct Field {
    std::string name;
    std::vector<unsigned char> bytes;
  };
  std::vector<Field> fields_;
  std::size_t fluid_count_ = 0;
  double time_ = 0;
  std::uint64_t step_ = 0;
};

}  // namespace rtsph
