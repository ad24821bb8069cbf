// Particle shifting (Lind, Xu, Stansby & Rogers 2012, "Incompressible SPH for free-surface
// flows: a generalised diffusion-based algorithm for stability and validations for impulsive
// flows and propagating waves", JCP 231), the Fickian form with the diffusion coefficient of
// Skillen, Lind, Stansby & Rogers 2013 (CMAME 265):
//
//   δrᵢ = −D ∇Cᵢ,   ∇Cᵢ = Σⱼ (mⱼ/ρⱼ) ∇Wᵢⱼ + Σ_b (Ψ_b/ρ0) ∇Wᵢ_b,   D = A h |vᵢ| Δt
//
// with A = solver.shifting (0 = off, the default). Particles drift down the gradient of their
// own concentration, which keeps the arrangement from clumping or locking (the tensile
// instability of Taylor–Green's low-pressure cores). The velocity is not re-interpolated to the
// shifted position. There is no free-surface treatment: at a free surface ∇C points into the
// fluid and the shift would push the surface particles out, so the stage is for confined or
// periodic flows until one is added. Gathered per particle in the fixed order of the other sums
// (bitwise identical for any thread count), then applied in a second pass.
#include <cmath>

#include "core/pair_loop.h"
#include "solvers/fluid_world.h"

namespace rtsph {

using simd::f8;
using simd::i8;

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
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        Real speed2 = 0;
        for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; speed2 += fv[k][i] * fv[k][i]; }
        f8 g[D] = {};
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
            i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 s = simd::select(m & (r2 > 0.0f), mass * K.grad_factor(r2) / simd::at(rho, j), f8{});
              for (int k = 0; k < D; ++k) g[k] += s * d[k];
            });
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, cells[i], bx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 s = simd::select(m, simd::at(psi, j) * inv_rho0 * K.grad_factor(r2), f8{});
              for (int k = 0; k < D; ++k) g[k] += s * d[k];
            });
        const Real dcoef = coeff * std::sqrt(speed2);
        for (int k = 0; k < D; ++k) shift[k][i] = -dcoef * simd::hsum(g[k]);
      }
    }, ThreadPool::kPairs);
  });
  // Applied after every particle has gathered, so no sum saw a half-shifted neighbourhood; a
  // shift is far below a cell, so the sort stays valid (as after drift).
  displace_fluid(shift);
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
template void FluidWorld<2>::displace_fluid(const Real* const[2]);
template void FluidWorld<3>::displace_fluid(const Real* const[3]);

}  // namespace rtsph
