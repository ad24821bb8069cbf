// PBF's non-pressure velocity terms (Macklin & Müller 2013, section 5):
//   XSPH viscosity        Δvᵢ = c Σⱼ (m/ρⱼ)(vⱼ − vᵢ)Wᵢⱼ + c Σ_b (Ψ_b/ρ0)(v_b − vᵢ)W_ib    (eq. 17)
//     (the wall term lets moving obstacles drag the fluid, as viscosity does in WCSPH);
//   vorticity confinement ωᵢ = Σⱼ (m/ρⱼ) ∇ᵢWᵢⱼ × (vⱼ − vᵢ)                               (eq. 15)
//                         ηᵢ = Σⱼ (m/ρⱼ)(|ωⱼ| − |ωᵢ|)∇ᵢWᵢⱼ,  N = η/|η|,
//                         vᵢ += Δt ε (N × ωᵢ)                                              (eq. 16)
// In 2D ω has only a z component. Both read the same velocities (Jacobi), then all update.
// The XSPH loop also sums the density the position corrections reached (ρᵢ = Σⱼ mWᵢⱼ +
// Σ_b Ψ_bW_ib at the final positions), saving a pair loop per substep; its volumes m/ρⱼ use the
// density of the last λ pass, one correction earlier.
#include <cmath>

#include "core/pair_loop.h"
#include "core/timer.h"
#include "solvers/pbf.h"

namespace rtsph {

using simd::f8;
using simd::i8;

template <int D>
void Pbf<D>::xsph_and_vorticity(double dt) {
  const double c = spec_.pbf_xsph, eps_vort = spec_.pbf_vorticity;
  if (c <= 0 && eps_vort <= 0) {
    ScopedTimer timer(times_.density_s);
    this->compute_density();
    return;
  }
  ScopedTimer timer(times_.forces_s);
  rho_next_.resize(fluid_.size());
  constexpr int kOmega = D == 2 ? 1 : 3;
  const std::size_t n = fluid_.size();
  const bool vort = eps_vort > 0;
  for (int k = 0; k < D; ++k) delta_[k].resize(n);
  if (vort)
    for (auto& o : omega_) o.resize(n);
  const Real mass = Real(prm_.mass), support2 = Real(prm_.support * prm_.support);
  const Real cx = Real(c), inv_rho0 = Real(1.0 / prm_.rho0);
  const PairArrays<D> pa = this->pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx, &bv = pa.bv;
  [[maybe_unused]] const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  const Real* rho = fluid_.rho.data();
  // 3D with current lists: the neighbours' positions and (v, ρ) as 16-byte records, read by
  // eight loads per batch instead of seven gathers (as the λ pass).
  const Real* const px = D == 3 ? this->pack_positions() : nullptr;
  const bool packed = px != nullptr;  // 2D: positions and fields gathered
  if (packed) {
    packed_v_.resize(4 * n);
    Real* pv = packed_v_.data();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        for (int k = 0; k < D; ++k) pv[4 * i + k] = fv[k][i];
        pv[4 * i + 3] = rho[i];
      }
    });
  }
  const Real* const pv = packed_v_.data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D], vi[D];
        for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; vi[k] = fv[k][i]; }
        f8 dv[D] = {}, dvb[D] = {}, om[kOmega] = {}, wf{}, wb{};
        // The pair terms, given the neighbours' ρⱼ and vⱼ.
        auto pair = [&](const f8* d, f8 r2, i8 m, f8 rhoj, const f8* vj) {
              const f8 vol = simd::select(m, mass * simd::rcp(rhoj), f8{});
              f8 vji[D];
              for (int k = 0; k < D; ++k) vji[k] = vj[k] - vi[k];
              const f8 W = simd::select(m, K.value(r2), f8{});
              wf += W;
              const f8 w = vol * W;
              for (int k = 0; k < D; ++k) dv[k] += w * vji[k];
              if (vort) {
                const f8 G = vol * K.grad_factor(r2);  // ∇ᵢWᵢⱼ = G d
                if constexpr (D == 2) {
                  om[0] += G * (d[0] * vji[1] - d[1] * vji[0]);
                } else {
                  om[0] += G * (d[1] * vji[2] - d[2] * vji[1]);
                  om[1] += G * (d[2] * vji[0] - d[0] * vji[2]);
                  om[2] += G * (d[0] * vji[1] - d[1] * vji[0]);
                }
              }
            };
        if constexpr (D == 3) {
          if (packed) {
            for_each_listed_batch_packed(ctx_.fluid_list, i, px, xi, support2,
                                         [&](i8 j, const f8* d, f8 r2, i8 m) {
                                           f8 vj[3], rhoj;
                                           simd::at_packed4(pv, j, vj[0], vj[1], vj[2], rhoj);
                                           pair(d, r2, m, rhoj, vj);
                                         });
          }
        }
        if (!packed)
          this->template for_each_fluid_batch<periodic_v<decltype(K)>>(
              i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
                f8 vj[D];
                for (int k = 0; k < D; ++k) vj[k] = simd::at(fv[k], j);
                pair(d, r2, m, simd::at(rho, j), vj);
              });
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, cells[i], bx, xi, support2, [&](auto j, const f8*, f8 r2, i8 m) {
              const f8 w = simd::select(m, simd::at(psi, j) * K.value(r2), f8{});
              wb += w;
              for (int k = 0; k < D; ++k) dvb[k] += w * (simd::at(bv[k], j) - vi[k]);
            });
        rho_next_[i] = mass * simd::hsum(wf) + simd::hsum(wb);
        for (int k = 0; k < D; ++k)
          delta_[k][i] = cx * (simd::hsum(dv[k]) + inv_rho0 * simd::hsum(dvb[k]));
        if (vort)
          for (int k = 0; k < kOmega; ++k) omega_[k][i] = simd::hsum(om[k]);
      }
    }, ThreadPool::kPairs);
    fluid_.rho.swap(rho_next_);
    rho = fluid_.rho.data();
    if (!vort) return;
    // η = ∇|ω| and the confinement acceleration ε N × ω, added to the XSPH change.
    const Real step_eps = Real(dt * eps_vort);
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
        Real wi[kOmega], wi2 = 0;
        for (int k = 0; k < kOmega; ++k) { wi[k] = omega_[k][i]; wi2 += wi[k] * wi[k]; }
        const Real wabs = std::sqrt(wi2);
        f8 eta[D] = {};
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(i, fx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              f8 wj2 = f8{};
              for (int k = 0; k < kOmega; ++k) {
                const f8 w = simd::at(omega_[k].data(), j);
                wj2 += w * w;
              }
              const f8 vol = mass * simd::rcp(simd::at(rho, j));
              const f8 G = simd::select(m, vol * (simd::sqrt(wj2) - wabs) * K.grad_factor(r2), f8{});
              for (int k = 0; k < D; ++k) eta[k] += G * d[k];
            });
        Real N[3] = {0, 0, 0}, len2 = 0;
        for (int k = 0; k < D; ++k) { N[k] = simd::hsum(eta[k]); len2 += N[k] * N[k]; }
        if (len2 <= Real(1e-20)) continue;
        const Real inv = Real(1) / std::sqrt(len2);
        for (int k = 0; k < D; ++k) N[k] *= inv;
        if constexpr (D == 2) {
          delta_[0][i] += step_eps * N[1] * wi[0];
          delta_[1][i] -= step_eps * N[0] * wi[0];
        } else {
          delta_[0][i] += step_eps * (N[1] * wi[2] - N[2] * wi[1]);
          delta_[1][i] += step_eps * (N[2] * wi[0] - N[0] * wi[2]);
          delta_[2][i] += step_eps * (N[0] * wi[1] - N[1] * wi[0]);
        }
      }
    }, ThreadPool::kPairs);
  });
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k) {
      Real* v = fluid_.v[k].data();
      const Real* dv = delta_[k].data();
      for (std::size_t i = b; i < e; ++i) v[i] += dv[i];
    }
  });
}

template void Pbf<2>::xsph_and_vorticity(double);
template void Pbf<3>::xsph_and_vorticity(double);

}  // namespace rtsph
