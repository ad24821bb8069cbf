#pragma once
// SPH smoothing kernels W(r, h) with value and gradient, 2D and 3D, written once for float and
// for 8-lane batches. Each kernel gives:
//   value(r2)      W(r)
//   grad_factor(r2) G with ∇W(r) = G · r_vec (so G = W'(r)/r; zero at r = 0)
// Support radius = support_ratio · h. The gradient is the analytic derivative of the value:
// no ∂W/∂h term (the 2014 reference's mistake).
#include <cmath>
#include <numbers>

#include "core/simd.h"

namespace rtsph {

enum class KernelType { CubicSpline, WendlandC2, Poly6Spiky, Gaussian };

namespace detail {
template <int D>
constexpr double hpow(double h) { return D == 2 ? h * h : h * h * h; }
}  // namespace detail

/// Monaghan & Lattanzio 1985 cubic B-spline, support 2h.
/// σ = 2/(3h), 10/(7πh²), 1/(πh³) in 1D/2D/3D.
template <int D>
struct CubicSpline {
  static constexpr float support_ratio = 2.0f;
  float h, inv_h, sigma, gsigma, tiny;
  explicit CubicSpline(double h_) : h(float(h_)), inv_h(float(1.0 / h_)), tiny(float(1e-20 * h_ * h_)) {
    const double s = (D == 2 ? 10.0 / (7.0 * std::numbers::pi) : 1.0 / std::numbers::pi);
    sigma = float(s / detail::hpow<D>(h_));
    gsigma = float(s / (detail::hpow<D>(h_) * h_ * h_));
  }
  // Branch-free: w(q) = (2-q)_+^3/4 - (1-q)_+^3 equals the piecewise cubic on [0,1) and [1,2).
  template <class T>
  T value(T r2) const {
    const T q = r2 * simd::rsqrt(r2 + tiny) * inv_h;  // r = r²/√r², exact 0 at r = 0
    const T a = simd::max0(2.0f - q), b = simd::max0(1.0f - q);
    return sigma * (0.25f * a * a * a - b * b * b);
  }
  // w'(q)/q = (-0.75 a^2 + 3 b^2)/q. The bracket vanishes like -3q as q→0, so the offset
  // `tiny` under the root only keeps r = 0 finite (G(0) = 0; ∇W = G·r is 0 there anyway).
  template <class T>
  T grad_factor(T r2) const {
    const T inv_r = simd::rsqrt(r2 + tiny);
    const T q = r2 * inv_r * inv_h;
    const T a = simd::max0(2.0f - q), b = simd::max0(1.0f - q);
    const T num = -0.75f * a * a + 3.0f * b * b;
    return (gsigma * h) * num * inv_r;
  }
};

/// Wendland 1995 C2, support 2h: w(q) = (1 - q/2)^4 (2q + 1); σ = 7/(4πh²), 21/(16πh³).
template <int D>
struct WendlandC2 {
  static constexpr float support_ratio = 2.0f;
  float h, inv_h, sigma, gsigma, tiny;
  explicit WendlandC2(double h_) : h(float(h_)), inv_h(float(1.0 / h_)), tiny(float(1e-20 * h_ * h_)) {
    const double s = (D == 2 ? 7.0 / (4.0 * std::numbers::pi) : 21.0 / (16.0 * std::numbers::pi));
    sigma = float(s / detail::hpow<D>(h_));
    gsigma = float(s / (detail::hpow<D>(h_) * h_ * h_));
  }
  template <class T>
  T value(T r2) const {
    const T q = r2 * simd::rsqrt(r2 + tiny) * inv_h;
    const T a = simd::max0(1.0f - 0.5f * q);
    const T a2 = a * a;
    return sigma * (a2 * a2 * (2.0f * q + 1.0f));
  }
  // w'(q) = -5 q (1 - q/2)^3, so w'(q)/q = -5 (1 - q/2)^3: smooth, no division.
  template <class T>
  T grad_factor(T r2) const {
    const T q = r2 * simd::rsqrt(r2 + tiny) * inv_h;
    const T a = simd::max0(1.0f - 0.5f * q);
    return gsigma * (-5.0f * a * a * a);
  }
};

/// Müller, Charypar & Gross 2003: poly6 for the value, spiky for the gradient (poly6's
/// gradient vanishes at r = 0 and lets particles clump). Support R = 2h.
template <int D>
struct Poly6Spiky {
  static constexpr float support_ratio = 2.0f;
  float R, R2, inv_R, poly6, spiky;
  explicit Poly6Spiky(double h_) : R(float(2 * h_)), R2(float(4 * h_ * h_)), inv_R(float(0.5 / h_)) {
    const double r = 2 * h_, pi = std::numbers::pi;
    poly6 = float(D == 2 ? 4.0 / (pi * std::pow(r, 8)) : 315.0 / (64.0 * pi * std::pow(r, 9)));
    // spiky W = s (R - r)^3, ∇W = -3 s (R - r)^2 r̂
    spiky = float(D == 2 ? 10.0 / (pi * std::pow(r, 5)) : 15.0 / (pi * std::pow(r, 6)));
  }
  template <class T>
  T value(T r2) const {
    const T d = simd::max0(R2 - r2);
    return poly6 * d * d * d;
  }
  template <class T>
  T grad_factor(T r2) const {
    const T r = simd::sqrt(r2);
    const T d = simd::max0(R - r);
    return (-3.0f * spiky) * d * d / (r + 1e-12f * R);
  }
};

/// Gingold & Monaghan 1977 Gaussian, truncated at 3h and renormalised so it still integrates
/// to 1: the truncated mass is 1 - e^-9 in 2D and erf(3) - 6/√π e^-9 in 3D.
template <int D>
struct Gaussian {
  static constexpr float support_ratio = 3.0f;
  float h, inv_h2, sigma, cutoff2;
  explicit Gaussian(double h_) : h(float(h_)), inv_h2(float(1.0 / (h_ * h_))), cutoff2(float(9 * h_ * h_)) {
    const double pi = std::numbers::pi;
    const double mass = D == 2 ? 1.0 - std::exp(-9.0)
                               : std::erf(3.0) - 6.0 / std::sqrt(pi) * std::exp(-9.0);
    sigma = float(1.0 / (std::pow(pi, D / 2.0) * detail::hpow<D>(h_) * mass));
  }
  template <class T>
  T value(T r2) const {
    const T w = sigma * simd::exp(-r2 * inv_h2);
    return r2 < cutoff2 ? w : T{} * 0.0f;
  }
  template <class T>
  T grad_factor(T r2) const {
    return (-2.0f * inv_h2) * value(r2);
  }
};

/// Müller et al. 2003 viscosity kernel, support R = 2h. Its Laplacian is positive everywhere,
/// which is why Müller used it for viscosity; rtsph's Morris viscosity uses ∇W of the chosen
/// kernel instead, so this kernel is offered for study and tested like the others.
template <int D>
struct MullerViscosity {
  static constexpr float support_ratio = 2.0f;
  double R, sigma;
  explicit MullerViscosity(double h_) : R(2 * h_) {
    const double pi = std::numbers::pi;
    sigma = D == 2 ? 10.0 / (3.0 * pi * R * R) : 15.0 / (2.0 * pi * R * R * R);
  }
  double value(double r2) const {
    const double r = std::sqrt(r2), q = r / R;
    if (q >= 1.0 || r == 0.0) return 0.0;
    return sigma * (-0.5 * q * q * q + q * q + 0.5 / q - 1.0);
  }
  double grad_factor(double r2) const {
    const double r = std::sqrt(r2), q = r / R;
    if (q >= 1.0 || r == 0.0) return 0.0;
    return sigma * (-1.5 * q * q + 2.0 * q - 0.5 / (q * q)) / (R * r);
  }
  /// ∇²W = W'' + (D-1) W'/r; in 3D this is 45/(πR^6)(R - r), Müller's formula.
  double laplacian(double r2) const {
    const double r = std::sqrt(r2), q = r / R;
    if (q >= 1.0 || r == 0.0) return 0.0;
    const double f1 = -1.5 * q * q + 2.0 * q - 0.5 / (q * q), f2 = -3.0 * q + 2.0 + 1.0 / (q * q * q);
    return sigma / (R * R) * (f2 + (D - 1) * f1 / q);
  }
};

/// Calls fn with the kernel object for `type`, so hot loops are compiled per kernel and never
/// branch on the kernel type inside.
template <int D, class Fn>
decltype(auto) with_kernel(KernelType type, double h, Fn&& fn) {
  switch (type) {
    case KernelType::WendlandC2: return fn(WendlandC2<D>(h));
    case KernelType::Poly6Spiky: return fn(Poly6Spiky<D>(h));
    case KernelType::Gaussian: return fn(Gaussian<D>(h));
    case KernelType::CubicSpline: break;
  }
  return fn(CubicSpline<D>(h));
}

inline float support_ratio(KernelType t) { return t == KernelType::Gaussian ? 3.0f : 2.0f; }

}  // namespace rtsph
