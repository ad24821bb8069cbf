#pragma once
// Scenes built in code for the physics tests, so they do not depend on the JSON layer.
#include "solvers/simulation.h"

namespace rtsph::test {

/// Martin & Moyce 1952 (n² = 2): a column a wide and 2a high at the left wall of a 2D tank.
inline SimSpec dam_break_2d(double a, double spacing) {
  SimSpec s;
  s.name = "dam_break_2d_test";
  s.dimension = 2;
  s.domain_min = {{0, 0, 0}};
  s.domain_max = {{6 * a, 3 * a, 0}};
  s.spacing = spacing;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{a, 2 * a, 0}}, {}});
  return s;
}

/// A column of water of depth H at rest in a closed tank of width W.
inline SimSpec tank(int dim, double W, double H, double spacing) {
  SimSpec s;
  s.name = "tank_test";
  s.dimension = dim;
  s.domain_min = {{0, 0, 0}};
  s.domain_max = {{W, 1.5 * H, dim == 3 ? W : 0}};
  s.spacing = spacing;
  s.fluid_blocks.push_back({{{0, 0, 0}}, {{W, H, dim == 3 ? W : 0}}, {}});
  return s;
}

}  // namespace rtsph::test
