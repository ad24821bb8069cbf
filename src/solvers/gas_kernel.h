#pragma once
// The cubic spline (Monaghan & Lattanzio 1985, support 2h) with its smoothing length per lane,
// for the gas method's adaptive h: W = σ/hᵈ w(q), q = r/h, with
//   ∇W = σ/h^(d+2) (w'(q)/q) r⃗,   ∂W/∂h = −σ/h^(d+1) (d w(q) + q w'(q))   (Price 2012, eq. 26)
// and w(q) = ¼(2−q)₊³ − (1−q)₊³, the same function as CubicSpline<D> in core/kernels.h.
// The gravitational ∂φ/∂h of Price & Monaghan 2007 (core/gravity_kernel.h, in double there) is
// here in lanes too, for the gravitational grad-h term ζ.
#include <numbers>

#include "core/simd.h"

namespace rtsph::gas {

using simd::f8;

template <int D>
inline constexpr float kSigma = D == 2 ? float(10.0 / (7.0 * std::numbers::pi))
                                       : float(1.0 / std::numbers::pi);

template <int D>
[[gnu::always_inline]] inline f8 hpow(f8 inv_h) {  // 1/hᵈ
  return D == 2 ? inv_h * inv_h : inv_h * inv_h * inv_h;
}

/// W(r, h).
template <int D>
[[gnu::always_inline]] inline f8 value(f8 q, f8 inv_h) {
  const f8 a = simd::max0(2.0f - q), b = simd::max0(1.0f - q);
  return (kSigma<D> * hpow<D>(inv_h)) * (0.25f * a * a * a - b * b * b);
}

/// G with ∇ᵢW(rᵢⱼ, h) = G (xᵢ − xⱼ). w'(q)/q = −3 + 9q/4 on [0, 1) (no division, finite at
/// q = 0) and −¾(2−q)²/q on [1, 2).
template <int D>
[[gnu::always_inline]] inline f8 grad_factor(f8 q, f8 inv_h) {
  const f8 a = simd::max0(2.0f - q);
  const f8 outer = -0.75f * a * a / simd::select(q > 1.0f, q, f8{} + 1.0f);
  const f8 wq = simd::select(q < 1.0f, -3.0f + 2.25f * q, outer);
  return (kSigma<D> * hpow<D>(inv_h) * inv_h * inv_h) * wq;
}

/// ∂W(r, h)/∂h.
template <int D>
[[gnu::always_inline]] inline f8 dw_dh(f8 q, f8 inv_h) {
  const f8 a = simd::max0(2.0f - q), b = simd::max0(1.0f - q);
  const f8 w = 0.25f * a * a * a - b * b * b;
  const f8 qdw = q * (-0.75f * a * a + 3.0f * b * b);
  return -(kSigma<D> * hpow<D>(inv_h) * inv_h) * (float(D) * w + qdw);
}

/// ∂φ(r, h)/∂h of the softened potential per unit G m (Price & Monaghan 2007, appendix A;
/// docs/self-gravity.md): zero beyond the support.
[[gnu::always_inline]] inline f8 dphi_dh(f8 q, f8 inv_h) {
  const f8 q2 = q * q, q4 = q2 * q2;
  const f8 inner = -2.0f * q2 + 1.5f * q4 - 0.6f * q4 * q + 1.4f;
  const f8 outer = -4.0f * q2 + 4.0f * q2 * q - 1.5f * q4 + 0.2f * q4 * q + 1.6f;
  const f8 f = simd::select(q < 1.0f, inner, simd::select(q < 2.0f, outer, f8{}));
  return inv_h * inv_h * f;
}

}  // namespace rtsph::gas
