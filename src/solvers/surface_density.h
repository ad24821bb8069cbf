#pragma once
// The density a particle rests at where a free surface cuts its kernel: the rest lattice's own
// kernel sum there, for methods whose density constraint would otherwise ask ρ0 of every
// particle (solver.dfsph.surface_density = "lattice").
//
// Why: with negative pressure clamped, a particle whose support the free surface cuts sums
// below ρ0 at the fluid's spacing, so the constraint ρ ≥ ρ0 never pushes there: the surface band
// falls into itself until its cut sums reach ρ0 (docs/validation-history.md, standing wave,
// sessions 45-47). At h = s the band is one layer; at Wendland C2 with h = 1.5-2 spacings it is three or
// four, and its slow compaction drives the drops' late drift and much of a wave's loss.
#include <utility>
#include <vector>

#include "solvers/fluid_world.h"

namespace rtsph {

/// τ(|c|): the rest lattice's kernel sum Σⱼ V0 Wᵢⱼ for a particle k layers under a flat free
/// surface, V0 = m/ρ0 its particles' rest volume (so τ = 1 in the bulk), against its colour
/// gradient |c| = |Σⱼ V0 ∇Wᵢⱼ|, which is 0 in the bulk and grows toward the surface. A particle's |c| (fluid and wall samples, each at its rest volume)
/// then names the cut it sits under, whatever the surface's orientation, and ρ0 τ(|c|) is the
/// density the lattice has there.
class CutSumTable {
 public:
  CutSumTable() = default;
  template <int D>
  static CutSumTable build(const SimSpec& spec, const ResolvedParams& prm);
  /// τ at colour gradient c (1/m), interpolated linearly between layers, at most 1: beyond the
  /// top layer's gradient (corners, spray) the top layer's sum.
  double fraction(double c) const;
  /// (|c|, τ) per layer, deepest (|c| = 0) first.
  const std::vector<std::pair<double, double>>& rows() const { return rows_; }

 private:
  std::vector<std::pair<double, double>> rows_;
};

}  // namespace rtsph
