#pragma once
// Weakly compressible SPH (Becker & Teschner 2007; Monaghan 1994, 2005): pressure from an
// equation of state, explicit kick-drift-kick steps limited by the speed of sound.
#include "solvers/fluid_world.h"

namespace rtsph {

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
