// Transport-velocity formulation (Adami, Hu & Adams 2013, "A transport-velocity formulation for
// smoothed particle hydrodynamics", JCP 241): particles are advected with a transport velocity
//
//   ṽᵢ = vᵢ + Δt_k · a_bᵢ,   a_bᵢ = −(p_b/mᵢ) Σⱼ (Vᵢ² + Vⱼ²) ∇Wᵢⱼ            (their eqs. 8 and 13)
//
// instead of vᵢ, where p_b is a constant background pressure. On a uniform arrangement the sum
// vanishes; where particles bunch (the stretched stagnation points of a vortex, the
// low-pressure cores that make the arrangement clump) it pushes them back towards a uniform
// one, without touching the momentum (v, not ṽ, enters every force). With V = m/ρ and equal
// masses the sum is the symmetric pressure term of a uniform pressure p_b:
//
//   a_bᵢ = −p_b Σⱼ m (1/ρᵢ² + 1/ρⱼ²) ∇Wᵢⱼ − p_b Σ_b Ψ_b (1/ρᵢ² + 1/ρ0²) ∇Wᵢ_b,
//
// the walls' samples counted as the pressure term counts them. Here the advection by ṽ is
// applied as a displacement δxᵢ = Δt_d Δt_k a_bᵢ before the drift by v (WCSPH's kick-drift-kick:
// Δt_k = Δt/2, Δt_d = Δt, their eq. 13; DFSPH's symplectic Euler: Δt_k = Δt_d = Δt).
// p_b = solver.transport_velocity · ρ0 c0² (1, Adami's and PySPH's p_b = p0 = ρ0 c0², for
// Taylor–Green). ṽ − v is kept per particle for the momentum correction of their eq. 8, the
// divergence of A = ρ v ⊗ (ṽ − v) (add_transport_velocity_stress, at the next force sum):
// without it a particle moved by ṽ carries its momentum to where the flow has another velocity,
// which acts as a velocity diffusion. No free-surface treatment: at a free surface the truncated
// sum points outwards and the stage would push the surface off, so it is for confined or
// periodic flows, off by default. Gathered per particle in the fixed order of the other sums
// (bitwise identical for any thread count), then applied in a second pass.
#include <algorithm>
#include <cmath>

#include "core/pair_loop.h"
#include "solvers/fluid_world.h"

namespace rtsph {

using simd::f8;
using simd::i8;

template <int D>
void FluidWorld<D>::transport_velocity_shift(double dt_kick, double dt_drift, double max_signal_speed) {
  const std::size_t n = fluid_.size();
  if (n == 0 || spec_.transport_velocity <= 0 || dt_kick <= 0 || dt_drift <= 0) return;
  const Real support2 = Real(prm_.support * prm_.support), mass = Real(prm_.mass);
  const double c = std::min(prm_.c0, max_signal_speed);
  const double pb = spec_.transport_velocity * prm_.rho0 * c * c;
  const Real coeff_v = Real(pb * dt_kick);
  const Real inv_rho02 = Real(1.0 / (prm_.rho0 * prm_.rho0));
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx;
  const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  const Real* rho = fluid_.rho.data();
  for (int k = 0; k < D; ++k) ctx_.surface_normal[k].resize(n);  // scratch: δxᵢ
  Real* shift[D];
  for (int k = 0; k < D; ++k) shift[k] = ctx_.surface_normal[k].data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
        const Real inv_rhoi2 = Real(1) / (rho[i] * rho[i]);
        f8 g[D] = {};
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
            i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 rhoj = simd::at(rho, j);
              const f8 s = simd::select(m & (r2 > 0.0f),
                                        mass * (inv_rhoi2 + simd::rcp(rhoj * rhoj)) * K.grad_factor(r2), f8{});
              for (int k = 0; k < D; ++k) g[k] += s * d[k];
            });
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, cells[i], bx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 s = simd::select(m, simd::at(psi, j) * (inv_rhoi2 + inv_rho02) * K.grad_factor(r2), f8{});
              for (int k = 0; k < D; ++k) g[k] += s * d[k];
            });
        for (int k = 0; k < D; ++k) {
          const Real dv = -coeff_v * simd::hsum(g[k]);  // ṽ − v = Δt_k a_b
          transport_dv_[k][i] = dv;
          shift[k][i] = Real(dt_drift) * dv;
        }
      }
    }, ThreadPool::kPairs);
  });
  displace_fluid(shift);  // after every particle has gathered: no sum saw a half-moved neighbourhood
}

// aᵢ += Σⱼ m (1/ρᵢ² + 1/ρⱼ²) ½(Aᵢ + Aⱼ)·∇Wᵢⱼ, (A·∇W)_k = ρ v_k ((ṽ − v)·∇W)   (Adami 2013, eq. 8)
// Fluid pairs only: the wall samples are at rest (A_b = 0), and the term is second order in Δt.
template <int D>
void FluidWorld<D>::add_transport_velocity_stress() {
  const std::size_t n = fluid_.size();
  if (n == 0 || spec_.transport_velocity <= 0) return;
  const Real support2 = Real(prm_.support * prm_.support), mass = Real(prm_.mass);
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv;
  const Real* rho = fluid_.rho.data();
  const Real* dv[D];
  for (int k = 0; k < D; ++k) dv[k] = transport_dv_[k].data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D], vi[D], dvi[D];
        for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; vi[k] = fv[k][i]; dvi[k] = dv[k][i]; }
        const Real rhoi = rho[i], inv_rhoi2 = Real(1) / (rhoi * rhoi);
        f8 acc[D] = {};
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
            i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 rhoj = simd::at(rho, j);
              const f8 G = K.grad_factor(r2);
              f8 dvi_d = f8{}, dvj_d = f8{};  // (ṽ − v)·∇W / G
              for (int k = 0; k < D; ++k) {
                dvi_d += dvi[k] * d[k];
                dvj_d += simd::at(dv[k], j) * d[k];
              }
              // Lanes past the list's end read ρ = 0: masked after the product, not before.
              const f8 c = simd::select(m & (r2 > 0.0f), 0.5f * mass * (inv_rhoi2 + simd::rcp(rhoj * rhoj)) * G, f8{});
              const f8 ai = c * rhoi * dvi_d, aj = c * rhoj * dvj_d;
              for (int k = 0; k < D; ++k) acc[k] += ai * vi[k] + aj * simd::at(fv[k], j);
            });
        for (int k = 0; k < D; ++k) fluid_.a[k][i] += simd::hsum(acc[k]);
      }
    }, ThreadPool::kPairs);
  });
}

template void FluidWorld<2>::transport_velocity_shift(double, double, double);
template void FluidWorld<3>::transport_velocity_shift(double, double, double);
template void FluidWorld<2>::add_transport_velocity_stress();
template void FluidWorld<3>::add_transport_velocity_stress();

}  // namespace rtsph
