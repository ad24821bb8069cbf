#pragma once
// Self-gravity by direct summation: the O(N²) reference for accuracy (and the method of choice
// up to ~20k particles). Every particle pulls every other through the kernel-softened potential
// of Price & Monaghan 2007 with symmetric softening (src/core/gravity_kernel.h):
//   aᵢ = G Σ_{j≠i} mⱼ ½[φ'(rᵢⱼ, hᵢ) + φ'(rᵢⱼ, hⱼ)] (xⱼ - xᵢ)/rᵢⱼ
//   Φᵢ = G Σ_{j≠i} mⱼ ½[φ(rᵢⱼ, hᵢ) + φ(rᵢⱼ, hⱼ)]          (no self term)
// Pair terms are float (8 lanes), each row is summed in double in a fixed order, so the result
// is bitwise identical for any thread count. 2D uses the same 3D potential.
#include <cstddef>

#include "core/parallel.h"

namespace rtsph {

/// Borrowed SoA views of the particles that attract each other (and feel the field).
template <int D>
struct GravitySources {
  const float* x[D] = {};  // positions, m
  const float* m = nullptr;  // masses, kg (0 makes a massless test particle)
  const float* h = nullptr;  // smoothing lengths, m (> 0: the softening is 2h)
  std::size_t n = 0;
};

/// Writes acc[a][i] (m/s²) and, when pot is not null, pot[i] (J/kg) for every particle.
/// G is the gravitational constant in the scene's units.
template <int D>
void gravity_direct(const GravitySources<D>& src, double G, float* const acc[D], float* pot,
                    const ThreadPool& pool);

}  // namespace rtsph
