// Surface tension and adhesion after Akinci, Akinci & Teschner 2013 ("Versatile surface tension
// and adhesion for SPH fluids", ACM TOG 32(6)), the non-pressure force every method shares: it is
// added by accelerations() whenever that adds the external forces (WCSPH's force sum, DFSPH's
// a_nonp, PBF's f_ext), so no method carries a copy.
//
//   nᵢ = H Σⱼ (mⱼ/ρⱼ) ∇Wᵢⱼ                                  surface normal (eq. 5; H the support)
//   aᵢ += −γ Σⱼ Kᵢⱼ [ mⱼ C(rᵢⱼ) x̂ᵢⱼ + (nᵢ − nⱼ) ]           cohesion + curvature (eqs. 1, 4, 6)
//         −β Σ_b Ψ_b A(rᵢ_b) x̂ᵢ_b                          adhesion to boundary samples (eq. 7)
//   Kᵢⱼ = 2ρ0/(ρᵢ + ρⱼ)                                       symmetrised correction (eq. 6)
//
// C is Akinci's cohesion spline (attractive beyond H/2, repulsive inside), A the adhesion kernel
// (nonzero for H/2 < r ≤ H); both with the support H of the SPH kernel. In 3D their constants are
// the paper's (32/(πH⁹), 0.007/H^3.25); in 2D the constants give the same integral over the plane
// that the 3D kernels have over space (25280/(627πH⁸) and (13/1200)/H^2.25). γ is Akinci's
// coefficient, not the physical surface tension σ: `rtsph validate` calibrates σ(γ) once with
// a static droplet (docs/validation.md). Every pair term is antisymmetric, so the fluid's momentum
// is conserved by cohesion and curvature; the pairs are summed in the fixed order of the other
// sums (the half stencil's layers, or each particle's list), so results are bitwise identical
// for any thread count.
#include <cmath>

#include "core/pair_loop.h"
#include "solvers/fluid_world.h"

namespace rtsph {

using simd::f8;
using simd::i8;

template <int D>
void FluidWorld<D>::add_surface_forces() {
  const std::size_t n = fluid_.size();
  if (n == 0) return;
  const double H = prm_.support;
  const Real support2 = Real(H * H), mass = Real(prm_.mass), Hr = Real(H);
  const Real gamma = Real(spec_.surface_tension), beta = Real(spec_.adhesion);
  const Real two_rho0 = Real(2 * prm_.rho0);
  const double pi = 3.14159265358979323846;
  const Real c_norm = Real(D == 3 ? 32.0 / (pi * std::pow(H, 9)) : 25280.0 / (627.0 * pi * std::pow(H, 8)));
  const Real c_inner = Real(std::pow(H, 6) / 64.0);
  const Real a_norm = Real(D == 3 ? 0.007 / std::pow(H, 3.25) : (13.0 / 1200.0) / std::pow(H, 2.25));
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &bx = pa.bx;
  const Real* const psi = pa.psi;
  const Real* rho = fluid_.rho.data();
  for (int k = 0; k < D; ++k) ctx_.surface_normal[k].resize(n);
  Real* nrm[D];
  const Real* cn[D];
  for (int k = 0; k < D; ++k) { nrm[k] = ctx_.surface_normal[k].data(); cn[k] = nrm[k]; }

  // Without lists or periodic axes each fluid pair is visited once (half_stencil(), as the
  // density and the force sum walk it): both passes' pair terms go to both particles, whose sums
  // then start at zero (the normals) or at the forces already summed (aᵢ). That halves the pair
  // work of WCSPH's drops (the passes were half its step); the lists' methods walk as before.
  const bool half = half_stencil();
  const uint32_t* const cells = pa.cells;
  const Real* const packed = pack_positions();  // with lists: records instead of gathers
  const Real hm = Hr * mass;
  Real* a_out[D];
  for (int k = 0; k < D; ++k) a_out[k] = fluid_.a[k].data();
  if (half && gamma > 0) clear(nrm, n);

  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    // Pass 1: nᵢ = H Σⱼ (mⱼ/ρⱼ) ∇Wᵢⱼ over fluid neighbours (the self term has ∇W = 0); the
    // pair adds −H (m/ρᵢ) ∇Wᵢⱼ to nⱼ.
    auto normal = [&](std::size_t i, auto forward) {
      Real xi[D];
      for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
      f8 acc[D] = {};
      if constexpr (decltype(forward)::value) {
        const Real to_j = -hm / rho[i];
        for_each_forward_batch<D>(ctx_.fluid_grid, cells[i], uint32_t(i), fx, xi, support2,
                                  [&](uint32_t j, const f8* d, f8 r2, i8 m, int valid) {
                                    const i8 live = m & (r2 > 0.0f);
                                    const f8 G = simd::select(live, K.grad_factor(r2), f8{});
                                    // Lanes past the range read ρ = 0 (the arrays' zero padding).
                                    const f8 s = simd::select(live, hm * G / simd::at(rho, j), f8{});
                                    for (int k = 0; k < D; ++k) {
                                      acc[k] += s * d[k];
                                      add_forward(nrm[k], j, to_j * G * d[k], valid);
                                    }
                                  });
        for (int k = 0; k < D; ++k) nrm[k][i] += simd::hsum(acc[k]);
      } else {
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
            i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 s = simd::select(m & (r2 > 0.0f), K.grad_factor(r2) / simd::at(rho, j), f8{});
              for (int k = 0; k < D; ++k) acc[k] += s * d[k];
            }, packed);
        for (int k = 0; k < D; ++k) nrm[k][i] = hm * simd::hsum(acc[k]);
      }
    };
    if (gamma > 0) for_each_pair_sum_particle<periodic_v<decltype(K)>>(half, n, normal);

    // Pass 2: cohesion, curvature (antisymmetric pair terms: j gets −c), adhesion, added to aᵢ.
    auto force = [&](std::size_t i, auto forward) {
      Real xi[D], ni[D];
      for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; ni[k] = gamma > 0 ? cn[k][i] : Real(0); }
      const Real rhoi = rho[i];
      f8 acc[D] = {};
      // The pair's acceleration of i, c (masked lanes 0).
      auto pair = [&](auto j, const f8* d, f8 r2, i8 m, f8* c) {
        const i8 live = m & (r2 > 0.0f);  // not the particle itself
        const f8 r = simd::sqrt(r2);
        const f8 q = Hr - r;
        const f8 c1 = q * q * q * r2 * r;
        const f8 C = c_norm * simd::select(r + r > Hr, c1, c1 + c1 - c_inner);
        const f8 Kij = two_rho0 / (rhoi + simd::at(rho, j));
        // x̂ᵢⱼ = d/r; lanes with r = 0 are masked off below.
        const f8 coh = simd::select(live, -gamma * Kij * mass * C / simd::select(live, r, f8{} + 1.0f), f8{});
        const f8 curv = simd::select(live, -gamma * Kij, f8{});
        for (int k = 0; k < D; ++k) c[k] = coh * d[k] + curv * (ni[k] - simd::at(cn[k], j));
      };
      if (gamma > 0) {
        this->template sum_antisymmetric_pairs<periodic_v<decltype(K)>>(i, forward, fx, xi, support2, packed, a_out, acc, pair);
      }
      if (beta > 0) {
        Vec<D> pos;
        for (int k = 0; k < D; ++k) pos[k] = xi[k];
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, ctx_.boundary_grid.cell_of(pos), bx, xi, support2,
            [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 r = simd::sqrt(r2);
              const i8 live = m & (r + r > Hr);  // A is zero inside H/2
              const f8 arg = simd::select(live, -4.0f * r2 / Hr + 6.0f * r - 2.0f * Hr, f8{});
              const f8 A = a_norm * simd::sqrt(simd::sqrt(simd::max0(arg)));
              const f8 s = simd::select(live, -beta * simd::at(psi, j) * A / simd::select(live, r, f8{} + 1.0f), f8{});
              for (int k = 0; k < D; ++k) acc[k] += s * d[k];
            });
      }
      for (int k = 0; k < D; ++k) a_out[k][i] += simd::hsum(acc[k]);
    };
    for_each_pair_sum_particle<periodic_v<decltype(K)>>(half && gamma > 0, n, force);
  });
}

template void FluidWorld<2>::add_surface_forces();
template void FluidWorld<3>::add_surface_forces();

}  // namespace rtsph
