#pragma once
// Kernel-softened Newtonian gravity for the cubic spline (Price & Monaghan 2007, MNRAS 374,
// 1347, appendix A, for the M4 cubic spline). Each particle's mass is spread as the kernel
// W(r, h) of `CubicSpline<3>` (src/core/kernels.h): support 2h, q = r/h, σ = 1/(πh³). The pair
// potential per unit G·m is φ(r, h), with φ' = dφ/dr = M(<r)/r² where M(<r) is the kernel's
// enclosed mass fraction, so beyond the support (q ≥ 2) φ = -1/r and φ' = 1/r² exactly.
//
// Self-gravity is 3D physics: 2D scenes use the same 3D potential (particles as spheres in the
// plane), not the logarithmic 2D Green's function.
//
// Pairs use the symmetric softening of Price & Monaghan: the mean of φ'(r, hᵢ)
// and φ'(r, hⱼ), so the pair force is antisymmetric and momentum is conserved.
#include <cmath>
#include <cstddef>

#include "core/simd.h"

namespace rtsph {

struct CubicSplineGravity {
  static constexpr double support_ratio = 2.0;  // matches CubicSpline<D>::support_ratio

  /// φ'(r, h): radial derivative of the softened potential (force per unit G·m, attractive).
  static double force(double r, double h) {
    const double q = r / h;
    if (q >= 2.0) return 1.0 / (r * r);
    const double q2 = q * q, q3 = q2 * q, q4 = q2 * q2;
    if (q < 1.0) return (4.0 / 3.0 * q - 1.2 * q3 + 0.5 * q4) / (h * h);
    return (8.0 / 3.0 * q - 3.0 * q2 + 1.2 * q3 - q4 / 6.0 - 1.0 / (15.0 * q2)) / (h * h);
  }
  /// φ(r, h): softened potential per unit G·m (negative; -7/(5h) at r = 0).
  static double potential(double r, double h) {
    const double q = r / h;
    if (q >= 2.0) return -1.0 / r;
    const double q2 = q * q, q3 = q2 * q, q4 = q2 * q2, q5 = q4 * q;
    if (q < 1.0) return (2.0 / 3.0 * q2 - 0.3 * q4 + 0.1 * q5 - 1.4) / h;
    return (4.0 / 3.0 * q2 - q3 + 0.3 * q4 - q5 / 30.0 - 1.6 + 1.0 / (15.0 * q)) / h;
  }
  /// ∂φ/∂h at fixed r, for the gravitational grad-h term of Price & Monaghan 2007:
  /// with φ = f(q)/h, ∂φ/∂h = -(f + q f')/h². Zero beyond the support.
  static double dphi_dh(double r, double h) {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double q2 = q * q, q3 = q2 * q, q4 = q2 * q2, q5 = q4 * q;
    if (q < 1.0) return (-2.0 * q2 + 1.5 * q4 - 0.6 * q5 + 1.4) / (h * h);
    return (-4.0 * q2 + 4.0 * q3 - 1.5 * q4 + 0.2 * q5 + 1.6) / (h * h);
  }
};

namespace gravity_detail {

/// φ'(r, h)/r for eight pairs, given r, 1/h and the Newtonian 1/r³. The outer piece is
/// written in u = 2 - q: φ' r² = M(<r) = 1 - u⁴(1 - 4u/5 + u²/6) (the appendix's polynomial,
/// checked in the tests), because the appendix's form cancels to ~30 float ulps near q = 2.
/// Branch-free: every piece is evaluated and the lane's own one selected; callers run this only
/// when some lane is inside a support.
inline simd::f8 softened_force_over_r(simd::f8 r, simd::f8 inv_h, simd::f8 inv_r3) {
  const simd::f8 q = r * inv_h, q2 = q * q, u = 2.0f - q, u2 = u * u;
  const simd::f8 inner = inv_h * inv_h * inv_h * (4.0f / 3.0f - 1.2f * q2 + 0.5f * q2 * q);
  const simd::f8 outer = inv_r3 * (1.0f - u2 * u2 * (1.0f - 0.8f * u + u2 * (1.0f / 6.0f)));
  return q < 1.0f ? inner : (q < 2.0f ? outer : inv_r3);
}

/// φ(r, h) for eight pairs, given r, 1/h and the Newtonian -1/r. Outer piece likewise in u:
/// φ = -1/r + u⁵(1 + q)/(30 r), the appendix's polynomial factored (q·φh + 16/15 has a fifth-order
/// root at q = 2).
inline simd::f8 softened_potential(simd::f8 r, simd::f8 inv_h, simd::f8 minus_inv_r) {
  const simd::f8 q = r * inv_h, q2 = q * q, q4 = q2 * q2, u = 2.0f - q, u2 = u * u;
  const simd::f8 inner = inv_h * ((2.0f / 3.0f) * q2 - 0.3f * q4 + 0.1f * q4 * q - 1.4f);
  const simd::f8 outer = minus_inv_r * (1.0f - u2 * u2 * u * (1.0f + q) * (1.0f / 30.0f));
  return q < 1.0f ? inner : (q < 2.0f ? outer : minus_inv_r);
}

typedef double d4 __attribute__((vector_size(32)));
typedef float f4 __attribute__((vector_size(16)));

/// Eight float lanes summed into double lanes. Pair terms are float and are added up in float
/// over blocks of kBlock batches (≤ 128 terms: ~1e-7 relative), then each block's sum goes
/// into double, so a row of 10⁵-10⁶ terms keeps ~1e-7 relative accuracy at a fraction of the
/// cost of converting every term. The order is fixed, so the result depends only on the order
/// of the terms, never on the thread that computes it.
constexpr std::size_t kBlock = 16;
struct DoubleLanes {
  d4 lo{}, hi{};
  void add(simd::f8 v) {
    f4 a, b;
    __builtin_memcpy(&a, &v, sizeof a);
    __builtin_memcpy(&b, reinterpret_cast<const char*>(&v) + sizeof a, sizeof b);
    lo += __builtin_convertvector(a, d4);
    hi += __builtin_convertvector(b, d4);
  }
  double sum() const {
    const d4 s = lo + hi;
    return (s[0] + s[1]) + (s[2] + s[3]);
  }
};

/// Accumulates the softened pull of eight sources (positions xj, masses mj, inverse smoothing
/// lengths inv_hj) on one target at xi with 1/hᵢ into the float block sums acc (and pot),
/// lanes where `valid` is false contributing nothing. `Pot` adds the symmetric softened
/// potential. Newtonian lanes cost one rsqrt; the softened pieces are evaluated only when a
/// lane is inside either support (r < 2·max(hᵢ, hⱼ)).
template <int D, bool Pot>
inline void accumulate_pairs(const simd::f8* xi, const simd::f8* xj, simd::f8 mj,
                             simd::f8 inv_hi, simd::f8 inv_hj, simd::i8 valid, simd::f8* acc,
                             simd::f8* pot) {
  simd::f8 d[D];
  simd::f8 r2 = simd::f8{};
  for (int a = 0; a < D; ++a) {
    d[a] = xj[a] - xi[a];
    r2 += d[a] * d[a];
  }
  // r2 = 0 only for coincident particles (or the masked self-pair): 1/r is taken of 1 there, so
  // no lane holds inf or NaN, r stays exactly 0 and the softened inner piece (h > 0) applies.
  const simd::f8 inv_r = simd::rsqrt(r2 > 0.0f ? r2 : simd::splat(1.0f));
  const simd::f8 inv_r3 = inv_r * inv_r * inv_r, r = r2 * inv_r;
  const simd::f8 inv_hmin = inv_hi < inv_hj ? inv_hi : inv_hj;  // the larger support decides
  simd::f8 g = inv_r3, phi = -inv_r;
  if (simd::any(valid & (r * inv_hmin < 2.0f))) {
    g = 0.5f *
        (softened_force_over_r(r, inv_hi, inv_r3) + softened_force_over_r(r, inv_hj, inv_r3));
    if constexpr (Pot)
      phi = 0.5f * (softened_potential(r, inv_hi, -inv_r) + softened_potential(r, inv_hj, -inv_r));
  }
  const simd::f8 f = simd::select(valid, mj * g, simd::f8{});
  for (int a = 0; a < D; ++a) acc[a] += f * d[a];
  if constexpr (Pot) *pot += simd::select(valid, mj * phi, simd::f8{});
}

}  // namespace gravity_detail
}  // namespace rtsph
