// The rest lattice's cut kernel sums under a flat free surface (surface_density.h says why).
#include "solvers/surface_density.h"

#include <algorithm>
#include <cmath>

#include "core/kernels.h"

namespace rtsph {

// Layers k = reach … 0 under the surface row y = 0 of a square (cubic) lattice of spacing s, the
// particle at (0, −k s): the sums Σⱼ W and Σⱼ ∇W over the lattice points below the surface
// within the support, in the solver's own float kernels. Each particle's mass is ρ0/Σ_lattice W
// (FluidWorld::resolve_parameters), the deepest layer's full sum, so a particle's rest volume is
// 1/Σ_lattice W: τ_k = Σⱼ W / Σ_lattice W (1 in the bulk) and c_k = Σⱼ ∇W / Σ_lattice W.
template <int D>
CutSumTable CutSumTable::build(const SimSpec& spec, const ResolvedParams& prm) {
  const double s = spec.spacing, support2 = prm.support * prm.support;
  const int reach = int(std::ceil(prm.support / s));
  std::vector<std::pair<double, double>> sums;  // (|Σ∇W|, ΣW) per layer, deepest first
  with_kernel<D>(spec.kernel, prm.h, [&](const auto& K) {
    for (int layer = reach; layer >= 0; --layer) {
      double w = 0, g = 0;
      for (int z = (D == 3 ? -reach : 0); z <= (D == 3 ? reach : 0); ++z)
        for (int row = 0; row <= layer + reach; ++row)
          for (int x = -reach; x <= reach; ++x) {
            const double dy = double(layer - row) * s, dx = x * s, dz = z * s;
            const double r2 = dx * dx + dy * dy + (D == 3 ? dz * dz : 0.0);
            if (r2 >= support2) continue;
            w += double(K.value(float(r2)));
            g += double(K.grad_factor(float(r2))) * dy;
          }
      sums.emplace_back(std::abs(g), w);
    }
  });
  CutSumTable t;
  const double full = sums.front().second;  // the deepest layer's support is whole
  sums.front().first = 0;  // whole and symmetric: its gradient is round-off (1e-16)
  for (const auto& [g, w] : sums) {
    // Rows ascend in |c|: a layer whose gradient does not exceed the one below's adds nothing
    // the interpolation could use (none does for these kernels; kept so fraction() stays a
    // function).
    if (t.rows_.empty() || g / full > t.rows_.back().first) t.rows_.emplace_back(g / full, w / full);
  }
  return t;
}

double CutSumTable::fraction(double c) const {
  if (rows_.empty()) return 1.0;
  for (std::size_t q = 1; q < rows_.size(); ++q) {
    const auto &a = rows_[q - 1], &b = rows_[q];
    if (c <= b.first) {
      const double u = b.first > a.first ? (c - a.first) / (b.first - a.first) : 1.0;
      return std::min(1.0, a.second + u * (b.second - a.second));
    }
  }
  return std::min(1.0, rows_.back().second);
}

template CutSumTable CutSumTable::build<2>(const SimSpec&, const ResolvedParams&);
template CutSumTable CutSumTable::build<3>(const SimSpec&, const ResolvedParams&);

}  // namespace rtsph
