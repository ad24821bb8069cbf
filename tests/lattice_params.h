#pragma once
// The constants the rest lattice's sums read, for tests of what is built from them (the Jacobi
// weights, the surface band's cut sums).
#include "core/kernels.h"
#include "solvers/fluid_world.h"

namespace rtsph::test {

/// h, the support and ρ0, as FluidWorld::resolve_parameters resolves them from the spec.
inline ResolvedParams resolve_params(const SimSpec& s) {
  ResolvedParams p;
  p.h = s.smoothing_ratio * s.spacing;
  p.support = support_ratio(s.kernel) * p.h;
  p.rho0 = s.rest_density;
  return p;
}

}  // namespace rtsph::test
