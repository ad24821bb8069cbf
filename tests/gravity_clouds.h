#pragma once
// Particle clouds for the self-gravity tests and benchmarks: a uniform sphere and a Plummer
// sphere, SoA floats with per-particle masses and smoothing lengths.
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "core/gravity_direct.h"

namespace rtsph::test {

struct Cloud {
  std::vector<float> x[3], m, h;
  std::size_t size() const { return m.size(); }
  void push(const double* p, double mass, double hh) {
    for (int a = 0; a < 3; ++a) x[a].push_back(float(p[a]));
    m.push_back(float(mass));
    h.push_back(float(hh));
  }
  GravitySources<3> sources() const {
    GravitySources<3> s;
    for (int a = 0; a < 3; ++a) s.x[a] = x[a].data();
    s.m = m.data();
    s.h = h.data();
    s.n = size();
    return s;
  }
};

/// Uniform random direction times radius r.
inline void on_sphere(std::mt19937_64& rng, double r, double* p) {
  std::normal_distribution<double> g;
  double n2 = 0;
  for (int a = 0; a < 3; ++a) {
    p[a] = g(rng);
    n2 += p[a] * p[a];
  }
  for (int a = 0; a < 3; ++a) p[a] *= r / std::sqrt(n2);
}

/// n particles uniform in a sphere of radius R and total mass M, h uniform in [h_lo, h_hi].
inline Cloud uniform_sphere(std::size_t n, double R, double M, double h_lo, double h_hi,
                            uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    double p[3];
    on_sphere(rng, R * std::cbrt(u(rng)), p);
    c.push(p, M / double(n), h_lo + (h_hi - h_lo) * u(rng));
  }
  return c;
}

/// Plummer sphere of scale radius a (total mass M), truncated at 20a; h follows the local
/// mean spacing, h ∝ ρ^(-1/3) = h0 (1 + r²/a²)^(5/6), as adaptive SPH would set it.
inline Cloud plummer(std::size_t n, double a, double M, double h0, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  while (c.size() < n) {
    const double r = a / std::sqrt(std::pow(u(rng), -2.0 / 3.0) - 1.0);
    if (!(r < 20 * a)) continue;
    double p[3];
    on_sphere(rng, r, p);
    c.push(p, M / double(n), h0 * std::pow(1 + r * r / (a * a), 5.0 / 6.0));
  }
  return c;
}

}  // namespace rtsph::test
