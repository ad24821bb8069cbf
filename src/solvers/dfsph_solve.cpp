// The two pressure solves of DFSPH (Bender & Koschier 2017), Jacobi sweeps on the velocities.
//
// With Pᵢ = κᵢ/ρᵢ the pressure acceleration is aᵢ = −Σⱼ m(Pᵢ + Pⱼ)∇Wᵢⱼ − Σ_b Ψ_b 2Pᵢ∇W_ib
// (walls mirror the particle, as in WCSPH and PBF), the shared acceleration sum. A wall sample
// stands for a ghost particle that mirrors the particle's pressure and its velocity relative to
// the wall (the mirror image moves at v_ghost = 2v_b − vᵢ), so its share of the density rate is
// Σ_b Ψ_b (vᵢ − v_ghost)·∇W_ib = 2Σ_b Ψ_b (vᵢ − v_b)·∇W_ib:
//   Dρᵢ/Dt = Σⱼ m(vᵢ − vⱼ)·∇Wᵢⱼ + 2Σ_b Ψ_b (vᵢ − v_b)·∇W_ib                             (eq. 9)
// Then the pressure force is the adjoint of the rate it corrects, and a converged solve does
// no work on the fluid. With the wall counted once in the rate (as in the density, Σ_b Ψ_b W_ib)
// the mirrored force did work −Δt Σᵢ m Pᵢ vᵢ·Σ_b Ψ_b∇W_ib each sweep: water at rest gained
// energy against the floor (2.5 J in 2 s in a 3D tank with a periodic floor at α = 0; now 0.007 J;
// docs/validation.md) and needed the artificial viscosity to hold it. The density itself keeps
// the wall once, so the water rests where it did; the density solve's prediction ρᵢ + Δt Dρᵢ/Dt
// counts a particle's approach to a wall twice, so it is held back a little early, never late.
// A velocity change Δvᵢ = Δt aᵢ changes Dρᵢ/Dt
// by −Δt Pᵢ/αᵢ when the neighbours' P is ignored, with
//   1/αᵢ = |Σⱼ m∇Wᵢⱼ + 2Σ_b Ψ_b∇W_ib|² + Σⱼ |m∇Wᵢⱼ|²                                    (eq. 8)
// so a residual r gives Pᵢ = r αᵢ / Δt² (density, r = ρ*ᵢ − ρ0) or r αᵢ / Δt (divergence,
// r = Dρᵢ/Dt): eqs. 9-12 in this notation. Each solve starts from the last step's pressure
// (warm start, section 4.3) and stops when the mean residual reaches its tolerance.
//
// Pressure stabilisation (solver.dfsph.pressure_stabilisation β, off at 0). The pressure is a
// multiplier seen only through its gradient sum, and on a lattice that sum has a null space: a
// pressure alternating from layer to layer (wavenumber π/s) exerts no force (solvers/jacobi.h),
// so no sweep corrects it and each sweep adds the residual's share of that mode to it; the warm
// start carries it on. The layer-averaged pressure of a 3D tank at rest then alternates by up to
// ±40% near the surface (docs/validation-history.md, standing wave, session 47). As for equal-order
// finite elements (Brezzi & Pitkäranta 1984), the density solve's residual gets a Laplacian of
// the pressure, r − β Δt² Σⱼ |m∇Wᵢⱼ|² (Pᵢ − Pⱼ): zero for a pressure linear across a full
// support (the hydrostatic one), largest for the alternating mode, which it thereby fixes. Walls
// mirror Pᵢ and add nothing. Its diagonal is β times the operator's (eq. 8 inside the fluid), so
// the sweep divides by 1 + β; the graph Laplacian's largest eigenvalue (2 over that diagonal) is
// below the operator's (2.15-5.67: jacobi_relaxation), so ω stays stable.
#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/pair_loop.h"
#include "core/timer.h"
#include "solvers/dfsph.h"
#include "solvers/jacobi.h"

namespace rtsph {

namespace {
// Jacobi relaxation ω. With ω = 1 the sweeps diverge once a deep column carries its load
// (measured: the error doubles every few sweeps); IISPH's ω = 0.5 (Ihmsen et al. 2014)
// converges. At most this; wide kernels need less (jacobi_relaxation below).
constexpr double kRelax = 0.5;
// The share of the Jacobi stability limit 2/λmax used by the relaxation: the stiffest mode of
// the rest lattice then changes by a factor |1 − ωλmax| ≤ 0.5 per sweep.
constexpr double kStableShare = 0.75;
// dfsph::kWarm, the share of the last step's pressure the warm start applies: at 1 it pumps
// energy into a tank at rest (measured, 2D tank: kinetic energy 5.8 J at 0.9 against 0.065 J at
// 0.5, bottom pressure 1.72 against 1.03 of ρ0gH); at 0 the first sweeps start from nothing
// (1.06 of ρ0gH).
using dfsph::kWarm;
}  // namespace

using simd::f8;
using simd::i8;

// The relaxation ω for the sweeps, from the rest lattice (jacobi_lambda_max: a sweep multiplies
// mode q by 1 − ω|S(q)|²/Σ|∇W|²). IISPH's ω = 0.5 holds for the cubic spline at h = s (λmax 2.15
// in 2D, 2.81 in 3D), but Wendland C2 at h = 2s has λmax = 5.67, where ω = 0.5 amplifies the
// stiffest mode 1.8-fold per sweep and a fluid at rest blew up within 8 steps (measured,
// periodic box, velocity noise ×4 per step). ω = min(0.5, kStableShare · 2/λmax).
template <int D>
double dfsph::jacobi_relaxation(const SimSpec& spec, const ResolvedParams& prm) {
  const double lmax = jacobi_lambda_max<D>(spec, prm);
  return lmax > 0 ? std::min(kRelax, kStableShare * 2.0 / lmax) : kRelax;
}

// With with_density, ρᵢ = Σⱼ mWᵢⱼ + Σ_b Ψ_b W_ib in the same walk: one pass over the neighbours
// after each sort instead of two (compute_density's sums, term for term, so the same bits).
template <int D>
void Dfsph<D>::compute_factors(bool with_density) {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass), support2 = Real(prm_.support * prm_.support);
  const PairArrays<D> pa = this->pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx, &bv = pa.bv;
  [[maybe_unused]] const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  const NeighbourList<D>& list = ctx_.fluid_list;  // current: every sort lists
  pair_grad_.resize(list);
  for (int k = 0; k < D; ++k) wall_grad_[k].resize(n);
  wall_rate_.resize(n);
  const bool lattice = spec_.dfsph_surface_density == SurfaceDensity::Lattice;
  const double rho0 = prm_.rho0, inv_rho0 = 1.0 / rho0;
  if (lattice) target_.resize(n);
  Real* grad_out[D];  // hoisted: the loop's stores then cannot be taken to move the arrays
  for (int k = 0; k < D; ++k) grad_out[k] = pair_grad_.at(0, k);
  const Real* const packed_x = this->pack_positions();  // records instead of gathers
  // Below this the particle has (almost) no neighbours: no pressure can act on it.
  const double tiny = 1e-6 * this->lattice_gradient_sum();
  Real* const rho = fluid_.rho.data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    auto pass = [&](auto density) {
    constexpr bool kDensity = decltype(density)::value;
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      const auto Kl = K;  // a local: the float stores below cannot then overwrite its constants
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
        f8 sq{}, cnt{}, rate{}, gf[D] = {}, gb[D] = {}, wf{}, wb{};
        std::size_t slot = list.first_slot(i);
        auto pair = [&](auto, const f8* d, f8 r2, i8 m) {
          if constexpr (kDensity) wf += simd::select(m, Kl.value(r2), f8{});
          const f8 G = simd::select(m, Kl.grad_factor(r2), f8{});
          sq += G * G * r2;
          cnt += simd::select(m, f8{} + 1.0f, f8{});
          for (int k = 0; k < D; ++k) {
            const f8 g = G * d[k];
            gf[k] += g;
            simd::store(grad_out[k] + slot, g);
          }
          slot += simd::kWidth;
        };
        if (packed_x) {
          for_each_listed_batch_packed<D>(list, i, packed_x, xi, support2, pair);
        } else {
          for_each_listed_batch<D>(list, i, fx, xi, support2, pair);
        }
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(ctx_.boundary_grid, cells[i], bx, xi, support2,
                                    [&](auto j, const f8* d, f8 r2, i8 m) {
                                      if constexpr (kDensity)
                                        wb += simd::select(m, simd::at(psi, j) * Kl.value(r2), f8{});
                                      const f8 G = simd::select(m, simd::at(psi, j) * Kl.grad_factor(r2), f8{});
                                      cnt += simd::select(m, f8{} + 1.0f, f8{});
                                      for (int k = 0; k < D; ++k) {
                                        gb[k] += G * d[k];
                                        rate += G * d[k] * simd::at(bv[k], j);
                                      }
                                    });
        double dot = 0, colour = 0;
        for (int k = 0; k < D; ++k) {
          const double f = double(mass) * simd::hsum(gf[k]), w = simd::hsum(gb[k]);
          wall_grad_[k][i] = Real(w);
          dot += (f + 2.0 * w) * (f + 2.0 * w);
          colour += (f + w) * (f + w);  // |Σⱼ m∇Wᵢⱼ + Σ_b Ψ_b∇W_ib|²: ρ0²|c|², walls once
        }
        wall_rate_[i] = simd::hsum(rate);
        const double denom = dot + double(mass) * mass * simd::hsum(sq);
        factor_[i] = denom > tiny ? Real(1.0 / denom) : Real(0);
        if (lattice) target_[i] = Real(rho0 * cut_sums_.fraction(std::sqrt(colour) * inv_rho0));
        neighbours_[i] = simd::hsum(cnt);
        if constexpr (kDensity) rho[i] = mass * simd::hsum(wf) + simd::hsum(wb);
      }
    }, ThreadPool::kPairs);
    };
    if (with_density)
      pass(std::true_type{});
    else
      pass(std::false_type{});
  });
}

// A resumed run continues from the saved positions, which the last step listed and cached:
// rebuild the caches (and the factors, to the same bits) before the next density solve.
template <int D>
void Dfsph<D>::state_loaded() {
  W::state_loaded();
  compute_factors();
}

// Computes Dρ/Dt with the current velocities and the residual r; the sweep's change of
// pressure goes to pressure_ (applied by the caller), projected so that the step's total
// pressure (warm) stays ≥ 0 when negative pressure is clamped: a sweep can take back pressure
// an earlier sweep or the warm start applied in excess, but never pull. Returns the mean
// relative residual (the complementarity error: |r| where pressure acts, compression elsewhere).
template <int D>
double Dfsph<D>::residual(bool density, double dt, const AlignedArray<Real>& total) {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass);
  const PairArrays<D> pa = this->pair_arrays();
  const auto& fv = pa.fv;
  const NeighbourList<D>& list = ctx_.fluid_list;
  const double rho0 = prm_.rho0, inv_rho0 = 1.0 / rho0;
  const bool clamp = spec_.clamp_negative_pressure;
  const double to_p = density ? 1.0 / (dt * dt) : 1.0 / dt;
  const bool lattice = clamp && spec_.dfsph_surface_density == SurfaceDensity::Lattice;
  const Real* const packed_v = packed_v_.data();  // written by the apply_pressure before
  // Particles with a thin neighbourhood (free surface, spray) get no divergence correction:
  // their missing neighbours read as expansion or compression that is not there (2017, §4.2).
  const Real min_neighbours = dfsph::kMinNeighbours<D>;
  // The stabilisation (above): β Δt² m² scales Σⱼ |∇Wᵢⱼ|² (Pᵢ − Pⱼ); the density solve only.
  const double beta = density ? spec_.dfsph_pressure_stabilisation : 0.0;
  const double stab = beta * dt * dt * double(mass) * double(mass);
  const double gain = relax_ / (1.0 + beta);  // relax_ itself at β = 0: the same bits
  const Real* const P = total.data();
  return pool_.parallel_reduce(n, 0.0, [&](std::size_t b, std::size_t e) {
    double sum = 0;
    for (std::size_t i = b; i < e; ++i) {
      Real vi[D];
      for (int k = 0; k < D; ++k) vi[k] = fv[k][i];
      double laplacian = 0;  // Σⱼ |∇Wᵢⱼ|² (Pᵢ − Pⱼ)
      if (beta > 0) {
        const Real Pi = P[i];
        f8 lf{};
        for_each_cached_batch<D>(list, i, [&](i8 j, std::size_t slot) {
          f8 g2{};
          for (int k = 0; k < D; ++k) {
            const f8 g = simd::load(pair_grad_.at(slot, k));
            g2 += g * g;
          }
          lf += (Pi - simd::at(P, j)) * g2;
        });
        laplacian = simd::hsum(lf);
      }
      f8 rf{};
      if constexpr (D == 3) {
        for_each_cached_batch<D>(list, i, [&](i8 j, std::size_t slot) {
          f8 vj[3];
          simd::at_packed3(packed_v, j, vj[0], vj[1], vj[2]);
          for (int k = 0; k < D; ++k) rf += (vi[k] - vj[k]) * simd::load(pair_grad_.at(slot, k));
        });
      } else {
        for_each_cached_batch<D>(list, i, [&](i8 j, std::size_t slot) {
          f8 vj[2];
          simd::at_packed2(packed_v, j, vj[0], vj[1]);
          for (int k = 0; k < D; ++k) rf += (vi[k] - vj[k]) * simd::load(pair_grad_.at(slot, k));
        });
      }
      double wall = -double(wall_rate_[i]);
      for (int k = 0; k < D; ++k) wall += double(vi[k]) * wall_grad_[k][i];
      const double rate = double(mass) * simd::hsum(rf) + 2.0 * wall;  // Dρᵢ/Dt, the ghosts' (eq. 9 above)
      // Density: r = ρ*ᵢ − ρ0 with ρ*ᵢ = ρᵢ + Δt Dρᵢ/Dt; divergence: r = Dρᵢ/Dt.
      // The clamped density solve keeps ρ0, or under a cut kernel the lattice's sum there.
      const double target = lattice ? double(target_[i]) : rho0;
      double r = density ? fluid_.rho[i] + dt * rate - target - density_bias_ - stab * laplacian : rate;
      const bool thin = !density && neighbours_[i] < min_neighbours;
      double p = thin ? 0.0 : total[i] + gain * r * factor_[i] * to_p;
      if (clamp) p = std::max(p, 0.0);
      pressure_[i] = Real(p - total[i]);
      // Where pressure acts, expansion is an error too (it is pressure applied in excess,
      // e.g. by the warm start); where none acts, only compression is.
      if (thin) r = 0.0;
      else if (clamp) r = p > 0 ? std::abs(r) : std::max(r, 0.0);
      else r = std::abs(r);
      sum += density ? r * inv_rho0 : r * dt * inv_rho0;
    }
    return sum;
  }, ThreadPool::kPairs) / double(std::max<std::size_t>(1, n));
}

namespace {
constexpr int kChebyshevFrom = 2;  // why: at the solve loop (Dfsph::solve)
}  // namespace

double dfsph::chebyshev_weight(int it, double rho, double omega) {
  if (rho <= 0 || it < kChebyshevFrom) return 1.0;
  return it == kChebyshevFrom ? 2.0 / (2.0 - rho * rho) : 4.0 / (4.0 - rho * rho * omega);
}

bool dfsph::smooths_last(int sweeps, double rho) { return rho > 0 && sweeps > kChebyshevFrom; }

// vᵢ += Δt aᵢ with aᵢ = −Σⱼ m(Pᵢ + Pⱼ)∇Wᵢⱼ − 2Pᵢ Σ_b Ψ_b∇W_ib: the shared pressure
// acceleration (walls mirror Pᵢ), from the cached gradients.
template <int D>
void Dfsph<D>::apply_pressure(const Real* P, double dt) {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass), fdt = Real(dt);
  const NeighbourList<D>& list = ctx_.fluid_list;
  packed_v_.resize((D == 3 ? 4 : 2) * n);
  Real* const packed_v = packed_v_.data();
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Real Pi = P[i];
      f8 acc[D] = {};
      for_each_cached_batch<D>(list, i, [&](i8 j, std::size_t slot) {
        const f8 c = -mass * (Pi + simd::at(P, j));
        for (int k = 0; k < D; ++k) acc[k] += c * simd::load(pair_grad_.at(slot, k));
      });
      for (int k = 0; k < D; ++k) {
        const Real a = simd::hsum(acc[k]) - 2.0f * Pi * wall_grad_[k][i];
        fluid_.a[k][i] = a;
        fluid_.v[k][i] += a * fdt;
        packed_v[(D == 3 ? 4 : 2) * i + k] = fluid_.v[k][i];
      }
    }
  }, ThreadPool::kPairs);
}

template <int D>
template <bool kDensity>
int Dfsph<D>::solve(double dt, AlignedArray<Real>& total, double tolerance, const char* name) {
  ScopedTimer timer(kDensity ? times_.density_s : times_.forces_s);
  const std::size_t n = fluid_.size();
  last_step_.resize(n);
  // Warm start: part of the last step's total pressure, stored independent of Δt (κ ∝ 1/Δt²,
  // 1/Δt).
  const double to_p = kDensity ? 1.0 / (dt * dt) : 1.0 / dt;
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) total[i] = Real(total[i] * to_p * kWarm);
  });
  apply_pressure(total.data(), dt);
  const int max_iterations = std::max(1, spec_.dfsph_max_iterations);
  const int min_iterations = kDensity ? 2 : 1;  // a sweep past the tolerance (2017, Alg. 2-3)
  int it = 0;
  double err = residual(kDensity, dt, total);
  const bool clamp = spec_.clamp_negative_pressure;
  const double rho = kDensity && clamp ? spec_.dfsph_chebyshev : 0.0;
  double omega = 1.0;
  while ((err > tolerance || it < min_iterations) && it < max_iterations) {
    // Chebyshev semi-iterative acceleration (Golub & Varga 1961; Wang 2015 for position-based
    // solvers): P_{k+1} = ω_k (P_k + δ_k − P_{k−1}) + P_{k−1} with δ_k the Jacobi sweep's change,
    // i.e. the applied change Δ_k = ω_k δ_k + (ω_k − 1) Δ_{k−1}, ω from the recurrence
    // ω_2 = 2/(2 − ρ²), ω_{k+1} = 4/(4 − ρ²ω_k). It shrinks the slow, deep-column modes Jacobi
    // leaves (DFSPH 3D dam break at 60k, 0.5 s: 8.92 → 4.18 sweeps per density solve). The first
    // two sweeps stay plain: a short Chebyshev polynomial brings back modes one Jacobi sweep
    // removes (at two sweeps by 1 − ω₂ = −0.82 at ρ = 0.95), and solves that stop after the
    // minimum two (a fluid at rest, a periodic stream, Poiseuille flow) then gained noise that
    // the warm start carried over from step to step (rest: |v| 0.018 m/s against < 1e-3).
    // Divergence solves take about one sweep: left plain. So are two-sided (unclamped) solves:
    // with no free surface to pin it, a near-uniform pressure is a slow mode whose residual
    // force the acceleration amplifies (Taylor–Green without the transport velocity, 80²: decay
    // rate 111% off against 74% plain).
    omega = dfsph::chebyshev_weight(it, rho, omega);
    const Real w = Real(omega), w1 = Real(omega - 1.0);
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real d = w * pressure_[i] + (it > 0 ? w1 * last_step_[i] : Real(0));
        if (clamp && total[i] + d < 0) d = -total[i];
        pressure_[i] = d;
        last_step_[i] = d;
        total[i] += d;
      }
    });
    apply_pressure(pressure_.data(), dt);
    err = residual(kDensity, dt, total);
    ++it;
  }
  // A solve the acceleration acted in ends with one plain sweep: the change the last residual
  // left, at the relaxation alone. Chebyshev damps every mode within ±ρ alike, about 0.72 per
  // sweep at ρ = 0.95, so the lattice's stiffest modes, which a plain sweep takes down to 0.4
  // (3D: |1 − ωλmax|), stay near their size through a short solve, and the warm start carries
  // them into the next step: water at rest jittered at 14 mm/s rms (the quick still-water box,
  // 4-8 s; 5.1 with this sweep; docs/validation.md, session 28). Its residual is not measured:
  // the error reported is the last accelerated sweep's.
  if (kDensity && dfsph::smooths_last(it, rho)) {  // the loop's change at w = 1, no momentum
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real d = pressure_[i];
        if (clamp && total[i] + d < 0) d = -total[i];
        pressure_[i] = d;
        total[i] += d;
      }
    });
    apply_pressure(pressure_.data(), dt);
    ++it;
  }
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) total[i] = Real(total[i] / to_p);
  });
  if (err > tolerance && failure_.empty())
    failure_ = dfsph::not_converged(name, it, this->time_ + dt, err, tolerance);
  return it;
}

// In a periodic domain the fluid fills (every axis periodic, so no walls and no free surface),
// with two-sided pressure, the fluid's volume is fixed: its mean density is ρ0 whatever the
// flow. What the kernel sums read above or below that on average comes from the particles'
// arrangement (a strained or disordered lattice sums higher than a square one), and no velocity
// field can remove it; the solve then cannot converge, and the impulses it applies trying to
// destroy the flow (Taylor–Green, 80², with the transport velocity: 100 sweeps in most steps and
// the decay rate 36% off). So there the target is the mean: r = ρ*ᵢ − ρ0 − (ρ̄ − ρ0).
template <int D>
bool dfsph::targets_mean_density(const SimSpec& s, std::size_t fluid_count) {
  const int all = (1 << D) - 1;
  double volume = 1;
  for (int k = 0; k < D; ++k) volume *= s.domain_max[k] - s.domain_min[k];
  const bool filled = double(fluid_count) * std::pow(s.spacing, D) >= 0.98 * volume;  // each holds s^D
  return !s.clamp_negative_pressure && (int(s.periodic) & all) == all && filled;
}

template <int D>
double Dfsph<D>::correct_density_error(double dt) {
  density_bias_ = 0;
  const std::size_t n = fluid_.size();
  if (dfsph::targets_mean_density<D>(spec_, n)) {
    const double sum = pool_.parallel_reduce(n, 0.0, [&](std::size_t b, std::size_t e) {
      double acc = 0;
      for (std::size_t i = b; i < e; ++i) acc += fluid_.rho[i];
      return acc;
    });
    density_bias_ = sum / double(n) - prm_.rho0;
  }
  counters_.density_iterations = solve<true>(dt, warm_density_, spec_.dfsph_max_density_error, "density");
  return counters_.density_iterations;
}

template <int D>
double Dfsph<D>::correct_divergence_error(double dt) {
  counters_.divergence_iterations =
      solve<false>(dt, warm_divergence_, spec_.dfsph_max_divergence_error, "divergence");
  // Pressure for output: both solves act as Δv = Δt·(−Σ m(Pᵢ + Pⱼ)∇W), so the step's pressure is
  // p = ρ²(P_density + P_divergence) (κ = Pρ), from the totals stored as P·Δt² and P·Δt.
  const double inv_dt = 1.0 / dt;
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const double P = (warm_density_[i] * inv_dt + warm_divergence_[i]) * inv_dt;
      fluid_.p[i] = Real(P * double(fluid_.rho[i]) * fluid_.rho[i]);
    }
  });
  return counters_.divergence_iterations;
}

#define RTSPH_INSTANTIATE(D)                                  \
  template double dfsph::jacobi_relaxation<D>(const SimSpec&, const ResolvedParams&); \
  template bool dfsph::targets_mean_density<D>(const SimSpec&, std::size_t);          \
  template void Dfsph<D>::compute_factors(bool);              \
  template void Dfsph<D>::state_loaded();                     \
  template double Dfsph<D>::correct_density_error(double);    \
  template double Dfsph<D>::correct_divergence_error(double);
RTSPH_INSTANTIATE(2)
RTSPH_INSTANTIATE(3)
#undef RTSPH_INSTANTIATE

}  // namespace rtsph
