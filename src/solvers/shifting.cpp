// Particle shifting (Lind, Xu, Stansby & Rogers 2012, "Incompressible SPH for free-surface
// flows: a generalised diffusion-based algorithm for stability and validations for impulsive
// flows and propagating waves", JCP 231), the Fickian form with the diffusion coefficient of
// Skillen, Lind, Stansby & Rogers 2013 (CMAME 265):
//
//   δrᵢ = −D ∇C̃ᵢ,   ∇C̃ᵢ = Σⱼ (mⱼ/ρⱼ) fᵢⱼ ∇Wᵢⱼ + Σ_b (Ψ_b/ρ0) fᵢ_b ∇Wᵢ_b,   D = A h |vᵢ| Δt
//
// with A = solver.shifting (0 = off, the default) and Lind's anti-clumping weight
// f = 1 + 0.2 (W/W(Δp))⁴ (Monaghan 2000's tensile term), which pushes a close pair apart far
// harder than the plain gradient does. Particles drift down the gradient of their own
// concentration, which keeps the arrangement from clumping or locking.
// Free surface (Lind et al. 2012 §3.3): a particle whose position divergence
// ∇·rᵢ = Σⱼ Vⱼ (xⱼ − xᵢ)·∇Wᵢⱼ is below Lee et al. 2008's surface threshold (1.5 in 2D, 2.4 in 3D,
// against D inside the water) keeps only the part of its shift along the surface, normal to
// the plain ∇Cᵢ; so the shift never pushes the surface out, and pairs in the surface layer,
// whose pressure is clamped at 0, are still held apart. No particle shifts more than 0.2 initial
// spacings in one step (kMaxShift). The velocity is not re-interpolated to
// the shifted position. Gathered per particle in the fixed order of the other sums (bitwise
// identical for any thread count), then applied in a second pass.
// Stability, measured (3D still water, docs/validation.md): A = 1 is steady with WCSPH and
// DFSPH; at A = 2 WCSPH's shift makes density errors whose sound feeds the speed that scales the
// next shift, and the water heats up (rms speed 0.085 m/s against 0.007 at A = 1).
#include <cmath>

#include "core/pair_loop.h"
#include "solvers/fluid_world.h"

namespace rtsph {

using simd::f8;
using simd::i8;

namespace {
// Lind et al. 2012's anti-clumping term (Monaghan 2000): R = 0.2 with the exponent 4.
constexpr float kAntiClumpR = 0.2f;
// The most a particle shifts in one step, in initial spacings. With DFSPH's long steps a fast
// particle travels up to 0.4 spacing per step, and D = A h |v| Δt times the anti-clumping
// weight (up to 52 for the cubic spline at r = 0) moved close pairs past each other, which the
// next step's solve turned into speed: a 2D block gliding at 0.56 m/s burst (its outline 4.8
// spacings out in 40 steps at A = 1), as did still water at A = 2 (rms 0.8 m/s). Capped at 0.2
// spacing both stay whole; shifts in flows at rest or with WCSPH's short steps are far below it.
constexpr Real kMaxShift = Real(0.2);
// ∇·r is D inside the water and about half that at a free surface; Lee et al. 2008 take a
// particle with less than 1.5 (2D) or 2.4 (3D) as a surface particle.
template <int D>
constexpr Real kSurfaceDivergence = D == 2 ? Real(1.5) : Real(2.4);
}  // namespace

template <int D>
void FluidWorld<D>::shift_particles(double dt) {
  const std::size_t n = fluid_.size();
  if (n == 0 || spec_.shifting <= 0 || dt <= 0) return;
  const Real support2 = Real(prm_.support * prm_.support), mass = Real(prm_.mass);
  const Real inv_rho0 = Real(1.0 / prm_.rho0);
  const Real coeff = Real(spec_.shifting * prm_.h * dt);
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx;
  const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  const Real* rho = fluid_.rho.data();
  for (int k = 0; k < D; ++k) ctx_.surface_normal[k].resize(n);  // scratch: δrᵢ
  Real* shift[D];
  for (int k = 0; k < D; ++k) shift[k] = ctx_.surface_normal[k].data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    const Real inv_w_dp = shifting_inv_w_dp();
    const Real most = shifting_max_shift();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        Real speed2 = 0;
        for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; speed2 += fv[k][i] * fv[k][i]; }
        f8 g[D] = {}, gc[D] = {}, div{};
        auto add = [&](f8 s, const f8* d, f8 r2) {
          const f8 q = K.value(r2) * inv_w_dp, q2 = q * q;
          const f8 sc = s * (1.0f + kAntiClumpR * q2 * q2);
          for (int k = 0; k < D; ++k) { g[k] += s * d[k]; gc[k] += sc * d[k]; }
          div -= s * r2;  // ∇·r = Σ V (x_j − x_i)·∇W_ij
        };
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
            i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              add(simd::select(m & (r2 > 0.0f), mass * K.grad_factor(r2) / simd::at(rho, j), f8{}), d, r2);
            });
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, cells[i], bx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              add(simd::select(m, simd::at(psi, j) * inv_rho0 * K.grad_factor(r2), f8{}), d, r2);
            });
        Real grad[D], shifted[D], norm2 = 0;
        for (int k = 0; k < D; ++k) {
          grad[k] = simd::hsum(g[k]);
          shifted[k] = simd::hsum(gc[k]);
          norm2 += grad[k] * grad[k];
        }
        // Free surface (Lind et al. 2012 §3.3): a particle whose position divergence is below
        // the threshold of Lee et al. 2008 shifts only along the surface, so the shift never
        // pushes it out of the water; the normal is ∇Cᵢ's direction.
        if (simd::hsum(div) < kSurfaceDivergence<D> && norm2 > 0) {
          Real along = 0;
          for (int k = 0; k < D; ++k) along += shifted[k] * grad[k];
          along /= norm2;
          for (int k = 0; k < D; ++k) shifted[k] -= along * grad[k];
        }
        Real dcoef = coeff * std::sqrt(speed2);
        Real len2 = 0;
        for (int k = 0; k < D; ++k) len2 += shifted[k] * shifted[k];
        if (dcoef * dcoef * len2 > most * most) dcoef = most / std::sqrt(len2);
        for (int k = 0; k < D; ++k) shift[k][i] = -dcoef * shifted[k];
      }
    }, ThreadPool::kPairs);
  });
  // Applied after every particle has gathered, so no sum saw a half-shifted neighbourhood; a
  // shift is far below a cell, so the sort stays valid (as after drift).
  displace_fluid(shift);
}

// Monaghan's (2000) anti-clumping weight 1 + R (W/W(Δp))^4 takes W at the initial spacing.
template <int D>
Real FluidWorld<D>::shifting_inv_w_dp() const {
  Real w = 0;
  with_kernel<D>(spec_.kernel, prm_.h, false, [&](const auto& K) { w = K.value(Real(spec_.spacing * spec_.spacing)); });
  return Real(1) / w;
}

template <int D>
Real FluidWorld<D>::shifting_max_shift() const {
  return kMaxShift * Real(spec_.spacing);
}

template <int D>
void FluidWorld<D>::displace_fluid(const Real* const shift[D]) {
  const WallPlanes w = wall_planes();
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      for (int k = 0; k < D; ++k) {
        Real x = fluid_.x[k][i] + shift[k][i];
        const Real period = ctx_.fluid_grid.period(k);
        if (period > 0) {
          const Real start = Real(prm_.domain_min[k]), end = Real(prm_.domain_max[k]);
          x = x >= end ? x - period : x < start ? x + period : x;
        } else {
          x = std::fmin(std::fmax(x, w.lo[k]), w.hi[k]);
        }
        fluid_.x[k][i] = x;
      }
  });
}

template void FluidWorld<2>::shift_particles(double);
template void FluidWorld<3>::shift_particles(double);
template Real FluidWorld<2>::shifting_inv_w_dp() const;
template Real FluidWorld<2>::shifting_max_shift() const;
template Real FluidWorld<3>::shifting_max_shift() const;
template Real FluidWorld<3>::shifting_inv_w_dp() const;
template void FluidWorld<2>::displace_fluid(const Real* const[2]);
template void FluidWorld<3>::displace_fluid(const Real* const[3]);

}  // namespace rtsph
