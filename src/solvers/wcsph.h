#pragma once
// Weakly compressible SPH (Becker & Teschner 2007; Monaghan 1994, 2005): pressure from an
// equation of state, explicit kick-drift-kick steps limited by the speed of sound.
#include "solvers/fluid_world.h"

namespace rtsph {

/// WCSPH's adaptive step (Monaghan 1992): min(cfl·h/(c0 + |v|max), 0.25·√(h/|a|max),
/// viscous_limit), at most max_dt; spec.dt in fixed-step mode. v2max and a2max are the largest
/// |v|² and |a|² over the fluid. Shared by the CPU and GPU backends.
double wcsph_time_step(const SimSpec& s, const ResolvedParams& prm, double v2max, double a2max,
                       double viscous_limit);

template <int D>
class Wcsph final : public FluidWorld<D> {
 public:
  Wcsph(const SimSpec& spec, int threads);
  void step() override;

 private:
  using W = FluidWorld<D>;
  double choose_time_step() const;
  void compute_pressure();
  void update_forces();  // density → pressure → accelerations for the current positions
};

}  // namespace rtsph
