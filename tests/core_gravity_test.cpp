// Kernel-softened gravity (src/core/gravity_kernel.h) and direct summation
// (src/core/gravity_direct.h). The softened force and potential are checked against
// independent computations: finite differences, the enclosed mass of the project's own cubic
// spline by quadrature, and continuity at the piece boundaries. The direct sum is checked
// against the analytic field of a uniform sphere with a tolerance from the sample's own
// variance, for momentum conservation and for bitwise determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "core/gravity_direct.h"
#include "core/gravity_kernel.h"
#include "core/kernels.h"
#include "gravity_clouds.h"

namespace rtsph {
namespace {

using Grav = CubicSplineGravity;
constexpr double kPi = std::numbers::pi;
constexpr double kHs[] = {0.01, 0.7, 3.0};

// The softening's support is the cubic spline's: 2h.
TEST(GravityKernel, SupportIsTheCubicSplines) {
  EXPECT_EQ(Grav::support_ratio, double(CubicSpline<3>::support_ratio));
}

// Piece boundaries q = 1 and q = 2: force, potential and ∂φ/∂h agree from both sides to
// round-off (1e-9 of their scale 1/h², 1/h), and at q ≥ 2 they are exactly Newtonian.
TEST(GravityKernel, ContinuousAtPieceBoundariesAndNewtonianBeyond) {
  for (double h : kHs) {
    for (double q : {1.0, 2.0}) {
      const double lo = (q - 1e-12) * h, hi = (q + 1e-12) * h;
      EXPECT_NEAR(Grav::force(lo, h), Grav::force(hi, h), 1e-9 / (h * h)) << "q=" << q;
      EXPECT_NEAR(Grav::potential(lo, h), Grav::potential(hi, h), 1e-9 / h) << "q=" << q;
      EXPECT_NEAR(Grav::dphi_dh(lo, h), Grav::dphi_dh(hi, h), 1e-9 / (h * h)) << "q=" << q;
    }
    for (double q : {2.0, 2.5, 7.0, 1e3}) {
      const double r = q * h;
      EXPECT_DOUBLE_EQ(Grav::force(r, h), 1.0 / (r * r));
      EXPECT_DOUBLE_EQ(Grav::potential(r, h), -1.0 / r);
      EXPECT_EQ(Grav::dphi_dh(r, h), 0.0);
    }
  }
}

// φ' = dφ/dr and ∂φ/∂h by central differences (step 1e-5 h: truncation ~1e-10, round-off
// ~1e-11 of the scale), at points spread over both pieces and beyond.
TEST(GravityKernel, DerivativesMatchFiniteDifferences) {
  for (double h : kHs) {
    for (int k = 1; k < 60; ++k) {
      const double q = 0.043 * k, r = q * h, e = 1e-5 * h;
      const double dr = (Grav::potential(r + e, h) - Grav::potential(r - e, h)) / (2 * e);
      EXPECT_NEAR(Grav::force(r, h), dr, 1e-7 / (h * h)) << "q=" << q << " h=" << h;
      const double dh = (Grav::potential(r, h + e) - Grav::potential(r, h - e)) / (2 * e);
      EXPECT_NEAR(Grav::dphi_dh(r, h), dh, 1e-7 / (h * h)) << "q=" << q << " h=" << h;
    }
  }
}

// Gauss's law for the kernel's mass distribution: φ'(r, h) = M(<r)/r² with
// M(<r) = ∫₀ʳ 4πs² W(s, h) ds, W the project's CubicSpline<3> (evaluated in float, hence the
// 1e-6 tolerance), by 5-point Gauss-Legendre on 400 panels.
TEST(GravityKernel, ForceIsEnclosedKernelMassOverRSquared) {
  static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                              0.9061798459386640};
  static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                              0.2369268850561891, 0.2369268850561891};
  for (double h : kHs) {
    const CubicSpline<3> W(h);
    for (double q : {0.05, 0.3, 0.77, 1.0, 1.31, 1.9, 2.0, 2.6}) {
      const double r = q * h;
      const int panels = 400;
      double mass = 0;
      for (int p = 0; p < panels; ++p) {
        const double a = r * p / panels, b = r * (p + 1) / panels;
        for (int g = 0; g < 5; ++g) {
          const double s = 0.5 * (a + b) + 0.5 * (b - a) * x[g];
          mass += 0.5 * (b - a) * w[g] * 4 * kPi * s * s * double(W.value(float(s * s)));
        }
      }
      EXPECT_NEAR(Grav::force(r, h) * r * r, mass, 1e-6) << "q=" << q << " h=" << h;
    }
  }
}

// The 8-lane float evaluation used by the sums against the double reference (rsqrt with one
// Newton step and float arithmetic: 2e-6 relative).
TEST(GravityKernel, SimdLanesMatchScalar) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uq(0.0, 3.0);
  for (double h : kHs) {
    for (int rep = 0; rep < 20; ++rep) {
      simd::f8 r, inv_r3, minus_inv_r;
      for (int l = 0; l < simd::kWidth; ++l) {
        r[l] = float(uq(rng) * h + 1e-3 * h);
        inv_r3[l] = 1.0f / (r[l] * r[l] * r[l]);
        minus_inv_r[l] = -1.0f / r[l];
      }
      const simd::f8 inv_h = simd::splat(float(1.0 / h));
      const simd::f8 g = gravity_detail::softened_force_over_r(r, inv_h, inv_r3);
      const simd::f8 p = gravity_detail::softened_potential(r, inv_h, minus_inv_r);
      for (int l = 0; l < simd::kWidth; ++l) {
        const double rl = r[l], f = Grav::force(rl, h) / rl, phi = Grav::potential(rl, h);
        EXPECT_NEAR(g[l], f, 2e-6 * std::fabs(f)) << "q=" << rl / h;
        EXPECT_NEAR(p[l], phi, 2e-6 * std::fabs(phi)) << "q=" << rl / h;
      }
    }
  }
}

struct DirectResult {
  std::vector<float> a[3], pot;
};
template <int D>
DirectResult run_direct(const GravitySources<D>& s, double G, int threads) {
  DirectResult r;
  float* acc[D];
  for (int a = 0; a < D; ++a) {
    r.a[a].resize(s.n);
    acc[a] = r.a[a].data();
  }
  r.pot.resize(s.n);
  gravity_direct<D>(s, G, acc, r.pot.data(), ThreadPool(threads));
  return r;
}

// N = 3000 random particles in a uniform sphere (R = 2, M = 5, G = 0.7, h ∈ [0.16, 0.24]) plus
// 60 massless probes at 1.3R-3R. Inside r < R - 2h_max the mean softened field is exactly
// G M(<r)/r² = G M r/R³ (the kernel smooths only the surface shell, symmetric about the
// target), outside r > R + 2h_max it is G M/r². For each target the terms of its sum are
// independent draws, so the sum's standard deviation is σ = √n · sd(terms), estimated from the
// terms themselves (the double-precision pair force): z = (a - a_mean)/σ should look like a
// standard normal: RMS z < 1.3 and no |z| > 5.
TEST(GravityDirect, UniformSphereMatchesAnalyticField) {
  const double R = 2, M = 5, G = 0.7, hmax = 0.24;
  const std::size_t n = 3000, probes = 60;
  test::Cloud c = test::uniform_sphere(n, R, M, 0.16, hmax, 11);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(1.3, 3.0);
  for (std::size_t k = 0; k < probes; ++k) {
    double p[3];
    test::on_sphere(rng, u(rng) * R, p);
    c.push(p, 0.0, 0.2);
  }
  const DirectResult res = run_direct<3>(c.sources(), G, 2);
  double z2 = 0, zmax = 0;
  int count = 0, inside = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    double xi[3], r2 = 0;
    for (int a = 0; a < 3; ++a) {
      xi[a] = c.x[a][i];
      r2 += xi[a] * xi[a];
    }
    const double r = std::sqrt(r2);
    const bool probe = i >= n;
    if (!probe && (r > R - 2 * hmax || i % 10 != 0)) continue;  // 1 in 10 interior targets
    inside += !probe;
    // Mean field of the other particles: (n-1)/n of the sphere's for a particle, all of it for
    // a probe.
    const double sources = probe ? double(n) : double(n - 1);
    const double g_mean = probe ? G * M / (r * r * r) : G * M / (R * R * R) * sources / double(n);
    for (int a = 0; a < 3; ++a) {
      double s = 0, s2 = 0;
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        double d[3], dr2 = 0;
        for (int b = 0; b < 3; ++b) {
          d[b] = double(c.x[b][j]) - xi[b];
          dr2 += d[b] * d[b];
        }
        const double dr = std::sqrt(dr2);
        const double f = G * c.m[j] * 0.5 *
                         (Grav::force(dr, c.h[i]) + Grav::force(dr, c.h[j])) * d[a] / dr;
        s += f;
        s2 += f * f;
      }
      const double var = s2 / sources - (s / sources) * (s / sources);
      const double sigma = std::sqrt(sources * var);
      const double z = (res.a[a][i] - (-g_mean * xi[a])) / sigma;
      z2 += z * z;
      zmax = std::max(zmax, std::fabs(z));
      ++count;
    }
  }
  ASSERT_GT(inside, 50);
  const double zrms = std::sqrt(z2 / count);
  EXPECT_LT(zrms, 1.3) << "targets " << count / 3;
  EXPECT_LT(zmax, 5.0);
  RecordProperty("z_rms", std::to_string(zrms));
}

// Newton's third law: pair forces are antisymmetric (same float pair term, negated offset),
// so Σ mᵢaᵢ vanishes up to the float rounding of the stored accelerations: 1e-6 of Σ mᵢ|aᵢ|.
TEST(GravityDirect, ConservesMomentum) {
  const test::Cloud c = test::plummer(2000, 1.0, 3.0, 0.05, 7);
  const DirectResult res = run_direct<3>(c.sources(), 1.0, 2);
  double p[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    double a2 = 0;
    for (int a = 0; a < 3; ++a) {
      p[a] += double(c.m[i]) * res.a[a][i];
      a2 += double(res.a[a][i]) * res.a[a][i];
    }
    scale += c.m[i] * std::sqrt(a2);
  }
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::fabs(p[a]), 1e-6 * scale) << "axis " << a;
}

TEST(GravityDirect, BitwiseIdenticalForOneAndTwoThreads) {
  const test::Cloud c = test::plummer(1500, 1.0, 1.0, 0.05, 9);
  const DirectResult one = run_direct<3>(c.sources(), 1.0, 1);
  const DirectResult two = run_direct<3>(c.sources(), 1.0, 2);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(0, std::memcmp(one.a[a].data(), two.a[a].data(), c.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(one.pot.data(), two.pot.data(), c.size() * sizeof(float)));
}

// Two particles, softened (q < 2 for one of the two h) and not, in 3D and in 2D (which uses
// the 3D potential): acceleration G mⱼ ½[φ'(r,hᵢ) + φ'(r,hⱼ)] toward the other, potential
// G mⱼ ½[φ(r,hᵢ) + φ(r,hⱼ)]; float accuracy 1e-6.
template <int D>
void check_pair(double r, double hi, double hj) {
  const float x0[2] = {0.25f, float(0.25 + r)}, zero[2] = {0.0f, 0.0f};
  const float m[2] = {2.0f, 3.0f}, h[2] = {float(hi), float(hj)};
  GravitySources<D> s;
  s.x[0] = x0;
  for (int a = 1; a < D; ++a) s.x[a] = zero;
  s.m = m;
  s.h = h;
  s.n = 2;
  const DirectResult res = run_direct<D>(s, 0.5, 1);
  const double rr = double(x0[1]) - x0[0];
  const double f = 0.5 * (Grav::force(rr, h[0]) + Grav::force(rr, h[1]));
  const double phi = 0.5 * (Grav::potential(rr, h[0]) + Grav::potential(rr, h[1]));
  EXPECT_NEAR(res.a[0][0], 0.5 * 3 * f, 1e-6 * 1.5 * f);
  EXPECT_NEAR(res.a[0][1], -0.5 * 2 * f, 1e-6 * f);
  for (int a = 1; a < D; ++a) EXPECT_EQ(res.a[a][0], 0.0f);
  EXPECT_NEAR(res.pot[0], 0.5 * 3 * phi, 1e-6 * 1.5 * std::fabs(phi));
  EXPECT_NEAR(res.pot[1], 0.5 * 2 * phi, 1e-6 * std::fabs(phi));
}
TEST(GravityDirect, PairForceIsTheSymmetricSoftenedForce) {
  for (double r : {0.05, 0.3, 0.9, 4.0}) {
    check_pair<3>(r, 0.2, 0.35);
    check_pair<2>(r, 0.2, 0.35);
  }
}

}  // namespace
}  // namespace rtsph
