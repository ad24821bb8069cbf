// The gas method's accelerations: the hydrodynamic pair sum with grad-h terms, and
// self-gravity. Each particle gathers from its candidates in a fixed order, so results are
// bitwise identical for any thread count.
#include <algorithm>
#include <cmath>

#include "core/gravity_direct.h"
#include "core/pair_loop.h"
#include "solvers/gas.h"
#include "solvers/gas_kernel.h"

namespace rtsph {

using simd::f8;
using simd::i8;

// aᵢ = −Σⱼ mⱼ [Aᵢ ∇ᵢWᵢⱼ(hᵢ) + Aⱼ ∇ᵢWᵢⱼ(hⱼ)] − Σⱼ mⱼ Πᵢⱼ ½[∇ᵢWᵢⱼ(hᵢ) + ∇ᵢWᵢⱼ(hⱼ)]
//   Aᵢ = pᵢ/(Ωᵢρᵢ²) + G ζᵢ/(2Ωᵢ)      (Price 2012, eq. 34; Price & Monaghan 2007, eq. 31)
//   Πᵢⱼ = (−α c̄ μ + 2α μ²)/ρ̄ for vᵢⱼ·rᵢⱼ < 0, μ = h̄ vᵢⱼ·rᵢⱼ/(r² + 0.01 h̄²)   (Monaghan 1992)
// duᵢ/dt = pᵢ/(Ωᵢρᵢ²) Σⱼ mⱼ vᵢⱼ·∇ᵢWᵢⱼ(hᵢ) + ½ Σⱼ mⱼ Πᵢⱼ vᵢⱼ·∇̄Wᵢⱼ   (Price 2012, eq. 35)
// A pair is in range when r < 2 max(hᵢ, hⱼ); the terms of the smaller support vanish by
// themselves beyond it. The grid's cells are at least 2 max(h), so the stencil holds them all.
template <int D>
void Gas<D>::hydro_accelerations() {
  if (this->spec_.gas_smoothing == GasSmoothing::Global) {
    // One h for all: the Gaussian of Gingold & Monaghan 1977 (both gradients are the same).
    const Gaussian<D> K(this->fluid_.size() ? double(h_[0]) : 1.0);
    hydro_sum([&](f8, f8 r2, f8) { return K.grad_factor(r2); });
  } else {
    hydro_sum([](f8 r, f8, f8 inv_h) { return gas::grad_factor<D>(r * inv_h, inv_h); });
  }
}

template <int D>
template <class Grad>
void Gas<D>::hydro_sum(const Grad& grad) {
  const std::size_t n = this->fluid_.size();
  const auto& grid = this->ctx_.fluid_grid;
  const uint32_t* cells = grid.sorted_cells();
  const Real m = Real(this->prm_.mass), alpha = Real(this->spec_.artificial_viscosity);
  const Real beta = 2 * alpha;
  const Real cell = grid.cell_size(0);
  const Real* xs[D];
  const Real* vs[D];
  for (int k = 0; k < D; ++k) { xs[k] = this->fluid_.x[k].data(); vs[k] = this->fluid_.v[k].data(); }
  const Real* rho = this->fluid_.rho.data();
  const Real* h = h_.data();
  const Real* cs = cs_.data();
  const Real* A = a_coef_.data();
  auto& f = this->fluid_;
  this->pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Real xi[D];
      f8 vi[D];
      for (int k = 0; k < D; ++k) { xi[k] = xs[k][i]; vi[k] = f8{} + vs[k][i]; }
      const f8 hi = f8{} + h[i], inv_hi = f8{} + Real(1) / h[i];
      const f8 Pti = f8{} + p_term_[i];
      const f8 Ai = f8{} + A[i], ci = f8{} + cs[i], rhoi = f8{} + rho[i];
      f8 acc[D] = {}, du{}, mu_max{};
      for_each_candidate_batch<D, false>(grid, cells[i], xs, xi, cell * cell,
                                         [&](auto j, const f8* d, f8 r2, i8 mask) {
        const f8 hj_raw = simd::at(h, j);  // lanes past the end read the zero padding
        const f8 hj = simd::select(hj_raw > 0.0f, hj_raw, f8{} + 1.0f);
        const f8 r = simd::sqrt(r2);
        const f8 Gi = grad(r, r2, inv_hi);
        const f8 Gj = grad(r, r2, 1.0f / hj);
        f8 vr{};
        f8 vij[D];
        for (int k = 0; k < D; ++k) {
          vij[k] = vi[k] - simd::at(vs[k], j);
          vr += vij[k] * d[k];
        }
        const f8 hbar = 0.5f * (hi + hj);
        const f8 mu = hbar * vr / (r2 + 0.01f * hbar * hbar);
        const f8 cbar = 0.5f * (ci + simd::at(cs, j)), rhobar = 0.5f * (rhoi + simd::at(rho, j));
        const f8 Pi = simd::select(vr < 0.0f, (-alpha * cbar * mu + beta * mu * mu) / rhobar, f8{});
        const f8 Gbar = 0.5f * (Gi + Gj);
        const f8 coef = simd::select(mask, m * (Ai * Gi + simd::at(A, j) * Gj + Pi * Gbar), f8{});
        for (int k = 0; k < D; ++k) acc[k] -= coef * d[k];
        du += simd::select(mask, m * vr * (Pti * Gi + 0.5f * Pi * Gbar), f8{});
        mu_max = simd::select(mask & (vr < 0.0f) & (-mu > mu_max), -mu, mu_max);
      });
      for (int k = 0; k < D; ++k) f.a[k][i] = simd::hsum(acc[k]);
      dudt_[i] = simd::hsum(du);
      float mmax = 0;
      for (int l = 0; l < simd::kWidth; ++l) mmax = std::max(mmax, mu_max[l]);
      signal_[i] = cs[i] + Real(0.6) * (alpha * cs[i] + beta * mmax);
    }
  }, ThreadPool::kPairs);
}

// Kernel-softened gravity with symmetric softening (core/gravity_direct.h, gravity_tree.h):
// direct summation, or the Barnes–Hut octree in 3D (2D always sums directly).
template <int D>
void Gas<D>::add_self_gravity() {
  const std::size_t n = this->fluid_.size();
  const double G = this->spec_.gravitational_constant;
  float* acc[D];
  for (int k = 0; k < D; ++k) acc[k] = gacc_[k].data();
  if constexpr (D == 3) {
    if (this->spec_.gravity_solver == GravitySolver::Tree) {
      GravitySources<3> src;
      for (int k = 0; k < 3; ++k) src.x[k] = this->fluid_.x[k].data();
      src.m = mass_.data();
      src.h = h_.data();
      src.n = n;
      tree_.build(src, this->pool_);
      tree_.accelerations(G, this->spec_.gravity_theta, acc, phi_.data(), this->pool_);
    }
  }
  if (D != 3 || this->spec_.gravity_solver == GravitySolver::Direct) {
    GravitySources<D> src;
    for (int k = 0; k < D; ++k) src.x[k] = this->fluid_.x[k].data();
    src.m = mass_.data();
    src.h = h_.data();
    src.n = n;
    gravity_direct<D>(src, G, acc, phi_.data(), this->pool_);
  }
  auto& f = this->fluid_;
  this->pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k)
      for (std::size_t i = b; i < e; ++i) f.a[k][i] += gacc_[k][i];
  });
}

template void Gas<2>::hydro_accelerations();
template void Gas<3>::hydro_accelerations();
template void Gas<2>::add_self_gravity();
template void Gas<3>::add_self_gravity();

}  // namespace rtsph
