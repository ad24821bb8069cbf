#pragma once
// Scenes built in code for the physics tests, so they do not depend on the JSON layer.
#include <cmath>
#include <numbers>
#include <string>

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

/// Morris, Fox & Zhu 1997's start-up Poiseuille flow: plates L = 1 mm apart (walls across y),
/// periodic along x (8 spacings), ν = 1e-6 m²/s, driven from rest by a body force F = 2e-4 m/s²,
/// so v_max = F L²/(8ν) = 2.5e-5 m/s; c0 = 100 v_max keeps the density within 1e-4 of ρ0.
struct Poiseuille {
  static constexpr double L = 1e-3, nu = 1e-6, F = 2e-4;
  static constexpr double vmax = F * L * L / (8 * nu);
  /// Their eq. 21: v(y,t) = F/(2ν) y (L − y) − Σ_n 4F L²/(ν π³ (2n+1)³) sin(π y (2n+1)/L)
  /// exp(−(2n+1)² π² ν t / L²).
  static double exact(double y, double t) {
    double v = F / (2 * nu) * y * (L - y);
    for (int n = 0; n < 200; ++n) {
      const double k = 2 * n + 1;
      v -= 4 * F * L * L / (nu * std::pow(std::numbers::pi, 3) * k * k * k) * std::sin(std::numbers::pi * y * k / L) *
           std::exp(-k * k * std::numbers::pi * std::numbers::pi * nu * t / (L * L));
    }
    return v;
  }
  /// The channel at spacing L/n for `method`, `columns` spacings long (at least three kernel
  /// supports: a wider kernel needs more).
  static SimSpec scene(const std::string& method, int n = 20, int columns = 8) {
    const double spacing = L / n;
    SimSpec s;
    s.method = method;
    s.name = "poiseuille";
    s.dimension = 2;
    s.spacing = spacing;
    s.domain_max = {{columns * spacing, L, 0}};
    s.periodic = PeriodicAxes::X;
    s.gravity = {{0, 0, 0}};
    s.body_force = {{F, 0, 0}};
    s.viscosity = nu;
    s.artificial_viscosity = 0;
    s.speed_of_sound = 100 * vmax;
    s.fluid_blocks.push_back({{{0, 0, 0}}, s.domain_max, {}});
    return s;
  }
};

}  // namespace rtsph::test
