// SPH kernels (src/core/kernels.h): normalisation, gradient = derivative of the value,
// antisymmetry of ∇W, the cubic-spline constants, the 8-lane SIMD path against the float path,
// and the Müller viscosity Laplacian. Every check is against an independent computation
// (quadrature, finite differences, closed forms written out here) with a stated tolerance.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <type_traits>
#include <vector>

#include "core/kernels.h"
#include "core/simd.h"

namespace rtsph {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHs[] = {0.01, 0.7};

template <class K>
struct Traits;
template <template <int> class K, int D_>
struct Traits<K<D_>> {
  static constexpr int D = D_;
  // MullerViscosity is double-only; the production kernels are evaluated in float.
  static constexpr bool is_double = std::is_same_v<K<D_>, MullerViscosity<D_>>;
  static constexpr bool is_poly6spiky = std::is_same_v<K<D_>, Poly6Spiky<D_>>;
  static constexpr bool is_gaussian = std::is_same_v<K<D_>, Gaussian<D_>>;
};

template <class K>
double W(const K& k, double r) {
  if constexpr (Traits<K>::is_double) return k.value(r * r);
  else return double(k.value(float(r * r)));
}
template <class K>
double G(const K& k, double r) {
  if constexpr (Traits<K>::is_double) return k.grad_factor(r * r);
  else return double(k.grad_factor(float(r * r)));
}

template <class K>
double support(double h) { return double(K::support_ratio) * h; }

/// ∫_0^R f(r) · (2πr or 4πr²) dr by composite 5-point Gauss-Legendre on `n` equal panels.
/// Gauss nodes never sit on panel ends, so the singular r = 0 of MullerViscosity and the kinks
/// at panel boundaries (q = 1 of the cubic spline, the support edge) are never evaluated.
template <int D, class F>
double radial_integral(F&& f, double R, int n = 4000) {
  static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                              0.9061798459386640};
  static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                              0.2369268850561891, 0.2369268850561891};
  const double dr = R / n;
  double sum = 0;
  for (int p = 0; p < n; ++p) {
    const double c = (p + 0.5) * dr;
    double s = 0;
    for (int g = 0; g < 5; ++g) {
      const double r = c + 0.5 * dr * x[g];
      const double shell = D == 2 ? 2 * kPi * r : 4 * kPi * r * r;
      s += w[g] * f(r) * shell;
    }
    sum += 0.5 * dr * s;
  }
  return sum;
}

template <class K>
class KernelTest : public ::testing::Test {};
using AllKernels =
    ::testing::Types<CubicSpline<2>, CubicSpline<3>, WendlandC2<2>, WendlandC2<3>, Poly6Spiky<2>,
                     Poly6Spiky<3>, Gaussian<2>, Gaussian<3>, MullerViscosity<2>, MullerViscosity<3>>;
TYPED_TEST_SUITE(KernelTest, AllKernels);

// ∫W dV = 1 (W evaluated through the float template for the production kernels).
TYPED_TEST(KernelTest, IntegratesToOne) {
  using K = TypeParam;
  constexpr int D = Traits<K>::D;
  for (double h : kHs) {
    const K k(h);
    const double I = radial_integral<D>([&](double r) { return W(k, r); }, support<K>(h));
    EXPECT_NEAR(I, 1.0, 1e-4) << "h=" << h;
  }
}

// W and ∇W vanish at and beyond the support radius (and the value there is never NaN).
TYPED_TEST(KernelTest, ZeroOutsideSupport) {
  using K = TypeParam;
  for (double h : kHs) {
    const K k(h);
    const double R = support<K>(h);
    for (double f : {1.0 + 1e-5, 1.01, 1.5, 3.0, 100.0}) {
      EXPECT_EQ(W(k, f * R), 0.0) << "h=" << h << " r/R=" << f;
      EXPECT_EQ(G(k, f * R), 0.0) << "h=" << h << " r/R=" << f;
    }
  }
}

// G(r)·r = dW/dr. For Poly6Spiky the gradient is Müller's spiky gradient, so the reference is
// d/dr of s·(R−r)³ with s written out here (15/(πR⁶) in 3D, 10/(πR⁵) in 2D).
TYPED_TEST(KernelTest, GradientIsDerivativeOfValue) {
  using K = TypeParam;
  constexpr int D = Traits<K>::D;
  for (double h : kHs) {
    const K k(h);
    const double R = support<K>(h);
    const double s = D == 3 ? 15.0 / (kPi * std::pow(R, 6)) : 10.0 / (kPi * std::pow(R, 5));
    auto ref = [&](double r) {
      if constexpr (Traits<K>::is_poly6spiky) return s * std::pow(R - r, 3);
      else return W(k, r);
    };
    // Float values carry ~1e-7 relative rounding, so a step of 1% of h keeps the rounding part
    // of the difference quotient at ~1e-5 of W' while the truncation part is O(δ²) ~ 1e-5.
    const double delta = Traits<K>::is_double ? 1e-5 * h : 1e-2 * h;
    // Scale for the absolute floor: the largest |W'| on a coarse scan.
    double wmax = 0;
    for (int i = 1; i < 1000; ++i) {
      const double r = R * i / 1000.0;
      wmax = std::max(wmax, std::abs(G(k, r) * r));
    }
    ASSERT_GT(wmax, 0.0);
    int checked = 0;
    for (int i = 0; i <= 200; ++i) {
      const double r = R * (0.03 + 0.94 * i / 200.0);  // away from r = 0 and the support edge
      const double fd = (ref(r + delta) - ref(r - delta)) / (2 * delta);
      const double an = G(k, r) * r;
      EXPECT_NEAR(an, fd, 1e-3 * std::abs(fd) + 1e-4 * wmax)
          << "h=" << h << " r/R=" << r / R << " (q=" << r / h << ")";
      ++checked;
    }
    EXPECT_EQ(checked, 201);
  }
}

// ∇W(x_i − x_j) = −∇W(x_j − x_i) bitwise for random pairs: G depends on r² only.
TYPED_TEST(KernelTest, GradientAntisymmetricBitwise) {
  using K = TypeParam;
  constexpr int D = Traits<K>::D;
  using T = std::conditional_t<Traits<K>::is_double, double, float>;
  std::mt19937 rng(1234);
  for (double h : kHs) {
    const K k(h);
    std::uniform_real_distribution<T> u(T(-1.2 * support<K>(h)), T(1.2 * support<K>(h)));
    for (int t = 0; t < 20000; ++t) {
      T xi[D], xj[D], dij[D], dji[D];
      for (int a = 0; a < D; ++a) {
        xi[a] = u(rng);
        xj[a] = u(rng);
        dij[a] = xi[a] - xj[a];
        dji[a] = xj[a] - xi[a];
      }
      T r2ij = 0, r2ji = 0;
      for (int a = 0; a < D; ++a) { r2ij += dij[a] * dij[a]; r2ji += dji[a] * dji[a]; }
      const T gij = k.grad_factor(r2ij), gji = k.grad_factor(r2ji);
      for (int a = 0; a < D; ++a) {
        const T lhs = gij * dij[a], rhs = -(gji * dji[a]);
        ASSERT_EQ(std::memcmp(&lhs, &rhs, sizeof(T)), 0)
            << "h=" << h << " axis " << a << ": " << lhs << " vs " << rhs;
        ASSERT_TRUE(std::isfinite(lhs));
      }
    }
  }
}

// At r = 0 every kernel gives a finite value and a finite G, so ∇W(0) = G·0 = 0 (no 0/0 NaN).
TYPED_TEST(KernelTest, FiniteAtOrigin) {
  using K = TypeParam;
  using T = std::conditional_t<Traits<K>::is_double, double, float>;
  for (double h : kHs) {
    const K k(h);
    const T g = k.grad_factor(T(0));
    EXPECT_TRUE(std::isfinite(g)) << "h=" << h;
    EXPECT_EQ(g * T(0), T(0)) << "h=" << h;
    EXPECT_TRUE(std::isfinite(k.value(T(0)))) << "h=" << h;
    // Tiny but nonzero r² must not blow up either (coincident particles after float rounding).
    // MullerViscosity is singular at r = 0 by design (G ~ 1/r³), so only the production kernels.
    if constexpr (!Traits<K>::is_double)
    for (T r2 : {T(1e-30), T(1e-20), std::numeric_limits<T>::denorm_min()}) {
      EXPECT_TRUE(std::isfinite(k.grad_factor(r2))) << "h=" << h << " r2=" << r2;
      EXPECT_TRUE(std::isfinite(k.value(r2))) << "h=" << h << " r2=" << r2;
    }
  }
}

// ---- Poly6Spiky: the spiky kernel that supplies the gradient integrates to 1 itself. ----------

template <int D>
void check_spiky_normalised() {
  for (double h : kHs) {
    const Poly6Spiky<D> k(h);
    const double R = 2 * h;
    const double s = D == 3 ? 15.0 / (kPi * std::pow(R, 6)) : 10.0 / (kPi * std::pow(R, 5));
    // With the constant written out here...
    EXPECT_NEAR(radial_integral<D>([&](double r) { return s * std::pow(R - r, 3); }, R), 1.0, 1e-6)
        << "h=" << h;
    // ...and with the float constant the kernel actually uses.
    EXPECT_NEAR(radial_integral<D>([&](double r) { return double(k.spiky) * std::pow(R - r, 3); }, R),
                1.0, 1e-6)
        << "h=" << h;
    EXPECT_NEAR(double(k.spiky), s, 1e-6 * s) << "h=" << h;
    // grad_factor is exactly -3 s (R-r)² / r inside the support.
    for (int i = 1; i < 100; ++i) {
      const double r = R * i / 100.0;
      const double expect = -3 * s * (R - r) * (R - r) / r;
      EXPECT_NEAR(double(k.grad_factor(float(r * r))), expect, 2e-5 * std::abs(expect))
          << "h=" << h << " r/R=" << r / R;
    }
  }
}
TEST(Poly6Spiky, SpikyIntegratesToOne2D) { check_spiky_normalised<2>(); }
TEST(Poly6Spiky, SpikyIntegratesToOne3D) { check_spiky_normalised<3>(); }

// ---- Cubic spline constants ---------------------------------------------------------------

template <int D>
void check_cubic_constants() {
  for (double h : kHs) {
    const CubicSpline<D> k(h);
    const double sigma = D == 2 ? 10.0 / (7.0 * kPi * h * h) : 1.0 / (kPi * h * h * h);
    const float hf = float(h);
    EXPECT_NEAR(double(k.value(0.0f)), sigma, 1e-6 * sigma) << "W(0) = σ, h=" << h;
    EXPECT_NEAR(double(k.value(hf * hf)), sigma / 4, 1e-5 * sigma) << "W(h) = σ/4, h=" << h;
    // W(2h) = 0 up to the rounding of q = sqrt(4h²)/h ≈ 2 (a residual (2-q)³ ~ 1e-21).
    EXPECT_NEAR(double(k.value(4 * hf * hf)), 0.0, 1e-12 * sigma) << "W(2h) = 0, h=" << h;
    EXPECT_EQ(k.value(4 * hf * hf * 1.0001f), 0.0f) << "W beyond 2h, h=" << h;
    // The piecewise cubic of Monaghan & Lattanzio at a few q.
    for (double q : {0.1, 0.5, 0.9, 1.1, 1.5, 1.9}) {
      const double w = q < 1 ? 1 - 1.5 * q * q + 0.75 * q * q * q : 0.25 * std::pow(2 - q, 3);
      const float r = float(q * h);
      EXPECT_NEAR(double(k.value(r * r)), sigma * w, 1e-5 * sigma) << "q=" << q << " h=" << h;
    }
    // ∇W(0) = 0 with no NaN; G is finite at r² = 0.
    const float g0 = k.grad_factor(0.0f);
    EXPECT_TRUE(std::isfinite(g0)) << "h=" << h;
    EXPECT_EQ(g0 * 0.0f, 0.0f) << "h=" << h;
  }
}
TEST(CubicSpline, Constants2D) { check_cubic_constants<2>(); }
TEST(CubicSpline, Constants3D) { check_cubic_constants<3>(); }

// ---- SIMD path equals the float path ----------------------------------------------------------

template <class K>
class SimdKernelTest : public ::testing::Test {};
using FloatKernels = ::testing::Types<CubicSpline<2>, CubicSpline<3>, WendlandC2<2>, WendlandC2<3>,
                                      Poly6Spiky<2>, Poly6Spiky<3>, Gaussian<2>, Gaussian<3>>;
TYPED_TEST_SUITE(SimdKernelTest, FloatKernels);

TYPED_TEST(SimdKernelTest, LanesMatchScalar) {
  using K = TypeParam;
  std::mt19937 rng(99);
  for (double h : kHs) {
    const K k(h);
    const float R = float(support<K>(h));
    std::uniform_real_distribution<float> u(0.0f, 1.2f * R * 1.2f * R);
    // Scales for an absolute floor: near the support edge the value is a small difference, and
    // the cubic spline's G = σ'(-0.75a² + 3b²)/q cancels as q → 0 (condition ~2/q), so lanes
    // may differ there by a few ulps of the cancelled terms; what the solver uses is
    // ∇W = G·r_vec, so the gradient is compared as |ΔG|·r against the peak |∇W|.
    const float wscale = std::abs(k.value(0.0f));
    float gr_max = 0;
    for (int i = 1; i <= 1000; ++i) {
      const float r = R * float(i) / 1000.0f;
      gr_max = std::max(gr_max, std::abs(k.grad_factor(r * r)) * r);
    }
    ASSERT_GT(gr_max, 0.0f);
    for (int t = 0; t < 5000; ++t) {
      simd::f8 r2{};
      for (int l = 0; l < simd::kWidth; ++l) r2[l] = u(rng);
      if (t == 0) { r2[0] = 0.0f; r2[1] = R * R; r2[2] = 1e-30f; r2[3] = float(h * h); }
      const simd::f8 wv = k.value(r2), gv = k.grad_factor(r2);
      for (int l = 0; l < simd::kWidth; ++l) {
        const float ws = k.value(r2[l]), gs = k.grad_factor(r2[l]);
        const float r = std::sqrt(r2[l]);
        ASSERT_TRUE(std::isfinite(wv[l]) && std::isfinite(gv[l])) << "h=" << h << " r2=" << r2[l];
        // The 8-lane path takes 1/√r² from the hardware estimate plus one Newton step (~2^-22
        // relative), which (1 - q/2)^n and (2 - q)^n amplify a few times near the support.
        EXPECT_NEAR(wv[l], ws, 1e-5f * std::abs(ws) + 1e-7f * wscale)
            << "value h=" << h << " r2=" << r2[l] << " lane " << l;
        EXPECT_NEAR(gv[l] * r, gs * r, 1e-5f * std::abs(gs) * r + 4e-7f * gr_max)
            << "grad h=" << h << " r2=" << r2[l] << " lane " << l << " (G " << gv[l] << " vs " << gs << ")";
        // Away from the cancellations (r → 0 and R − r → 0) G itself agrees to a few 1e-6.
        if (r > 0.25f * R && r < 0.75f * R) {
          EXPECT_NEAR(gv[l], gs, 1e-5f * std::abs(gs)) << "grad h=" << h << " r2=" << r2[l];
        }
      }
    }
  }
}

// ---- MullerViscosity Laplacian ------------------------------------------------------------

template <int D>
void check_muller_laplacian() {
  for (double h : kHs) {
    const MullerViscosity<D> k(h);
    const double R = 2 * h;
    auto w = [&](double r) { return k.value(r * r); };
    for (int i = 0; i <= 200; ++i) {
      const double r = R * (0.03 + 0.94 * i / 200.0);
      const double delta = 1e-4 * r;  // relative step: W has a 1/r singularity at 0
      const double d1 = (w(r + delta) - w(r - delta)) / (2 * delta);
      const double d2 = (w(r + delta) - 2 * w(r) + w(r - delta)) / (delta * delta);
      const double num = d2 + (D - 1) * d1 / r;
      const double lap = k.laplacian(r * r);
      // In 3D W'' and 2W'/r are each ~1/q³ and cancel to the finite 6(1−q)σ/R², so the direct
      // difference quotient loses digits near r = 0; check it for q ≥ 0.2 only, and everywhere
      // through the equivalent regular form ∇²W = (rW)''/r (rW is a polynomial in 3D).
      if (D == 2 || r >= 0.2 * R) {
        EXPECT_NEAR(lap, num, 1e-5 * std::abs(num) + 1e-9 * k.sigma / (R * R))
            << "W'' + (D-1)W'/r, h=" << h << " r/R=" << r / R;
      }
      if (D == 3) {
        const double e = 1e-4 * R;
        auto rw = [&](double x) { return x * w(x); };
        const double alt = (rw(r + e) - 2 * rw(r) + rw(r - e)) / (e * e) / r;
        EXPECT_NEAR(lap, alt, 1e-6 * std::abs(alt)) << "(rW)''/r, h=" << h << " r/R=" << r / R;
      }
      EXPECT_GT(lap, 0.0) << "Laplacian must be positive, h=" << h << " r/R=" << r / R;
      if (D == 3) {
        const double mueller = 45.0 / (kPi * std::pow(R, 6)) * (R - r);
        EXPECT_NEAR(lap, mueller, 1e-10 * mueller) << "45/(πR⁶)(R−r), h=" << h;
      }
    }
    EXPECT_EQ(k.laplacian(R * R * 1.0001), 0.0);
  }
}
TEST(MullerViscosity, LaplacianMatchesFiniteDifferences2D) { check_muller_laplacian<2>(); }
TEST(MullerViscosity, LaplacianMatchesFiniteDifferences3D) { check_muller_laplacian<3>(); }

// ---- Dispatch ---------------------------------------------------------------------------

TEST(WithKernel, DispatchesToTheNamedKernel) {
  const double h = 0.1;
  const float r2 = 0.013f;
  auto v = [&](KernelType t) {
    return with_kernel<3>(t, h, [&](const auto& K) { return K.value(r2); });
  };
  EXPECT_EQ(v(KernelType::CubicSpline), CubicSpline<3>(h).value(r2));
  EXPECT_EQ(v(KernelType::WendlandC2), WendlandC2<3>(h).value(r2));
  EXPECT_EQ(v(KernelType::Poly6Spiky), Poly6Spiky<3>(h).value(r2));
  EXPECT_EQ(v(KernelType::Gaussian), Gaussian<3>(h).value(r2));
  EXPECT_EQ(support_ratio(KernelType::Gaussian), Gaussian<3>::support_ratio);
  EXPECT_EQ(support_ratio(KernelType::CubicSpline), CubicSpline<3>::support_ratio);
  EXPECT_EQ(support_ratio(KernelType::WendlandC2), WendlandC2<3>::support_ratio);
  EXPECT_EQ(support_ratio(KernelType::Poly6Spiky), Poly6Spiky<3>::support_ratio);
}

}  // namespace
}  // namespace rtsph
