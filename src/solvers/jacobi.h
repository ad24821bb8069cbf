#pragma once
// The Jacobi iterations of the density solves (DFSPH's sweeps, PBF's constraint iterations) on
// the rest lattice: how far one iteration may go before the lattice's stiffest mode grows.
#include "solvers/fluid_world.h"

namespace rtsph {

/// λmax = max over lattice modes q of |S(q)|²/Σₖ|∇Wᵢₖ|², S(q) = Σₖ sin(q·xᵢₖ)∇Wᵢₖ, for the
/// spec's kernel, h and spacing (0 if the lattice has no neighbours). A Jacobi iteration with
/// weight ω multiplies mode q by 1 − ω|S(q)|²/Σ|∇W|², so it converges only for ω < 2/λmax.
template <int D>
double jacobi_lambda_max(const SimSpec& spec, const ResolvedParams& prm);

}  // namespace rtsph
