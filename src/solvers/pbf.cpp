// Position Based Fluids (Macklin & Müller 2013), Algorithm 1, one substep per step().
//
// Masses are kept (m = ρ0 V of the rest lattice), so with Cᵢ = ρᵢ/ρ0 − 1:
//   ∇ᵢCᵢ = (1/ρ0)(Σⱼ m∇Wᵢⱼ + Σ_b Ψ_b∇W_ib),  ∇ⱼCᵢ = −(m/ρ0)∇Wᵢⱼ                        (eq. 8)
//   λᵢ = −Cᵢ / (Σₖ|∇ₖCᵢ|² + ε)                                                           (eq. 11)
//   Δxᵢ = (1/ρ0)[Σⱼ m(λᵢ + λⱼ + s_corr)∇Wᵢⱼ + Σ_b Ψ_b 2λᵢ∇W_ib]                        (eq. 14)
// A boundary sample mirrors the particle's λ (as WCSPH's walls mirror its pressure), so the
// layer next to a wall carries the hydrostatic load instead of twice it; Σₖ|∇ₖCᵢ|² uses the
// same weights ((∇ᵢCᵢ with walls doubled)·∇ᵢCᵢ + Σⱼ|∇ⱼCᵢ|²), the Jacobi estimate of that system.
// ε and s_corr are given relative to a particle inside the rest lattice, so the defaults mean
// the same at every resolution.
#include "solvers/pbf.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/pair_loop.h"
#include "core/timer.h"
#include "solvers/jacobi.h"

namespace rtsph {

using simd::f8;
using simd::i8;

namespace {
// Jacobi relaxation of λ when the constraint is two-sided (solver.clamp_negative_pressure
// off). In a uniformly compressed region every neighbour moves too, so the per-particle estimate
// Σ|∇C|² undercounts the coupling about twice and full steps overshoot; with a one-sided
// constraint the clamp stops the overshoot, two-sided it grows (measured: a full 2D tank with a
// moving obstacle diverged in 7 steps at 1, and runs at 0.5, IISPH's and DFSPH's ω).
constexpr double kTwoSidedRelax = 0.5;
// The share of the Jacobi stability limit 2/λmax that solver.pbf.omega = 0 uses: the rest
// lattice's stiffest mode shrinks by |1 − ωλmax| = 0.8 per iteration. DFSPH's 0.75 (ω = 0.53 in
// 3D, where the mode halves) settled the validation's still-water box no better (rms 0.0082 m/s
// at 8 s against 0.0081) and slows the smooth modes more.
constexpr double kStableShare = 0.9;
}  // namespace

// solver.pbf.omega, the clamped iteration's weight. At Macklin & Müller's full step (1, the
// default) the iteration multiplies the rest lattice's stiffest mode (neighbours moving against
// each other) by 1 − λmax: −1.81 in 3D, −1.15 in 2D for the cubic spline at h = s. It grows, and
// only the one-sided clamp bounds it, in a cycle that flips sign each iteration: a 3D box of
// still water keeps an rms speed of 0.03 m/s over 10 s (1.9 times the validation's bound), and
// the 2D tank's kinetic energy flickers with the parity of the iteration count. A weight below
// 2/λmax damps that mode and the water comes to rest, but it slows the smooth modes that carry
// a deep column's load: 25-60% more iterations (docs/validation.md, session 21). So the full
// step stays the default, for real time, and 0 asks for the stable weight. (Switching between
// the two by the compression, per iteration or per substep, was tried: it cost 3-10%, and the
// mixed sequences pumped energy into a tank at rest, 0.05-0.13 J against 0.012 J in a 3D tank.)
template <int D>
double pbf::stable_weight(const SimSpec& spec, const ResolvedParams& prm) {
  const double lmax = jacobi_lambda_max<D>(spec, prm);
  return lmax > 0 ? std::min(1.0, kStableShare * 2.0 / lmax) : 1.0;
}
template double pbf::stable_weight<2>(const SimSpec&, const ResolvedParams&);
template double pbf::stable_weight<3>(const SimSpec&, const ResolvedParams&);

// s_corr acts on the pairs closer than r*, where the kernel's gradient |∇W| peaks (2h/3 for the
// cubic spline): below r* the pressure term's push weakens as a pair closes, so the pressure
// alone cannot keep it apart (the pairing instability), and that is what s_corr is for. Measured
// from its value at r*, it is zero for the pairs of water at rest (a spacing apart, 0.95 at the
// least in a settled box), so it no longer carries load there: at Macklin & Müller's full
// (W/W(Δq))ⁿ every pair pushed, as a pressure of its own that expanded the water and held a dam
// break's residual column up (PBF's Martin & Moyce height 15.4% → 3.8%, quick level;
// docs/validation.md, session 27). Spray stays apart (Pbf.SprayStaysApart: the closest pair of a
// 3D dam break 0.56 spacings apart, against 0.06 with s_corr off).
template <int D>
double pbf::gradient_peak(const SimSpec& spec, const ResolvedParams& prm) {
  return with_kernel<D>(spec.kernel, prm.h, [&](const auto& K) {
    constexpr int kSamples = 4096;
    double r_star = 0, g_max = 0;
    for (int k = 1; k < kSamples; ++k) {
      const double r = prm.support * k / kSamples;
      const double g = std::abs(double(K.grad_factor(Real(r * r)))) * r;
      if (g > g_max) { g_max = g; r_star = r; }
    }
    return r_star;
  });
}
template double pbf::gradient_peak<2>(const SimSpec&, const ResolvedParams&);
template double pbf::gradient_peak<3>(const SimSpec&, const ResolvedParams&);

// Computed per solve, since n and Δq are live. Applied where the weight is used (the correction,
// and the share of the pressure), not in the λ pass's cache: there one more operation per pair
// cost the 2D pass 17%.
template <int D>
double pbf::scorr_floor(const SimSpec& spec, const ResolvedParams& prm, double r_star) {
  const double dq = spec.pbf_scorr_dq * prm.support;
  return with_kernel<D>(spec.kernel, prm.h, [&](const auto& K) {
    const double w_dq = double(K.value(float(dq * dq)));
    return w_dq > 0 ? std::pow(double(K.value(float(r_star * r_star))) / w_dq, spec.pbf_scorr_n) : 0.0;
  });
}
template double pbf::scorr_floor<2>(const SimSpec&, const ResolvedParams&, double);
template double pbf::scorr_floor<3>(const SimSpec&, const ResolvedParams&, double);

template <int D>
Pbf<D>::Pbf(const SimSpec& spec, int threads) : W(spec, threads) {
  // Several sums per step over one neighbourhood: walk lists, not the grid.
  this->keep_neighbour_lists();
  stable_weight_ = pbf::stable_weight<D>(spec_, prm_);
  gradient_peak_ = pbf::gradient_peak<D>(spec_, prm_);
  lattice_gradient_norm_ = this->lattice_gradient_sum() / (prm_.rho0 * prm_.rho0);
  this->compute_density();
  this->measure_density_error();
  this->reset_stage_times();
}

// Algorithm 1: apply forces, predict, find neighbours, solve, update velocity, XSPH/vorticity.
template <int D>
void Pbf<D>::step() {
  const double dt = choose_time_step();
  {
    ScopedTimer timer(times_.integrate_s);
    this->accelerations({.viscosity = false, .wall_hydrostatic = true, .surface = false});  // gravity + brush (line 2)
    this->kick(dt);                              // vᵢ ⇐ vᵢ + Δt f_ext(xᵢ)
    this->drift(dt);                             // x*ᵢ ⇐ xᵢ + Δt vᵢ, wall contact   (line 3)
    this->advance_scene(this->time_ + dt, dt);   // obstacles, emitters, put-back
  }
  this->update_neighbours();                     // lines 5-7
  surface_forces_at_prediction(dt);              // line 2's surface forces, at x*
  save_predicted_positions();
  solve_density_constraint(dt);                  // lines 8-19
  {
    ScopedTimer timer(times_.integrate_s);
    update_velocity(dt);                         // line 21
    this->put_back_escaped();
  }
  xsph_and_vorticity(dt);                        // line 22, and the density reached
  this->measure_density_error();
  this->time_ += dt;
  this->dt_ = dt;
  ++this->steps_;
}

// A frame step split into substeps, shortened when the fastest particle would cross more than
// cfl spacings (a particle that jumps past a wall sample in one substep is never pushed back).
template <int D>
double Pbf<D>::choose_time_step() const {
  double dt = spec_.pbf_time_step / std::max(1, spec_.pbf_substeps);
  if (spec_.pbf_cfl > 0) {
    const double vmax = std::sqrt(this->max_speed_and_acceleration().v2);
    if (vmax > 0) dt = std::min(dt, spec_.pbf_cfl * spec_.spacing / vmax);
  }
  return dt;
}

// Akinci 2013's cohesion, curvature and adhesion are line 2's forces, but evaluated at the
// predicted positions x*, where the constraint that balances them is then solved: v += Δt a,
// x* += Δt² a. Evaluated at xᵢ instead (as gravity, which does not depend on x), the step adds
// the inward pull at xᵢ and the constraint's outward push at x*, and the step's velocity
// (x* + Δx − xᵢ)/Δt turns the pair into a torque: with Δx central about x*, the angular momentum
// changes by Σᵢ Δxᵢ × vᵢ per step, which grows with the spin itself. A drop held together by
// cohesion then spun up exponentially from its lattice's round-off (a 2D drop of 316 particles
// started at Ω = 1 rad/s reached 17.8 rad/s in 1.3 s at 8 substeps of 1/60 s; 32 substeps slowed
// that about thirtyfold). With both at x*, the pull and the push nearly cancel in Δx and the
// torque is of the order of the centripetal displacement, Ω³.
template <int D>
void Pbf<D>::surface_forces_at_prediction(double dt) {
  if (!this->surface_forces_active()) return;
  ScopedTimer timer(times_.integrate_s);
  const std::size_t n = fluid_.size();
  // aᵢ holds line 2's f_ext (gravity, brush, the walls' hydrostatic part), already applied and
  // kept for the statistics: the surface forces' share is what they add to it.
  for (int k = 0; k < D; ++k) {
    delta_[k].resize(n);
    const Real* a = fluid_.a[k].data();
    Real* out = delta_[k].data();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) { std::copy(a + b, a + e, out + b); });
  }
  this->add_surface_forces();
  const Real dtr = Real(dt), dt2 = Real(dt * dt);
  const auto walls = this->wall_planes();
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k) {
      const Real* a = fluid_.a[k].data();
      const Real* before = delta_[k].data();
      Real* v = fluid_.v[k].data();
      Real* x = fluid_.x[k].data();
      const Real lo = walls.lo[k], hi = walls.hi[k];
      for (std::size_t i = b; i < e; ++i) {
        const Real as = a[i] - before[i];
        v[i] += dtr * as;
        const Real xn = x[i] + dt2 * as;
        x[i] = xn < lo ? lo : xn > hi ? hi : xn;
      }
    }
  });
}

template <int D>
void Pbf<D>::save_predicted_positions() {
  const std::size_t n = fluid_.size();
  for (int k = 0; k < D; ++k) {
    predicted_[k].resize(n);
    delta_[k].resize(n);
    const Real* x = fluid_.x[k].data();
    Real* out = predicted_[k].data();
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) { std::copy(x + b, x + e, out + b); });
  }
  lambda_.resize(n);
  lambda_sum_.resize(n);
  std::fill(lambda_sum_.begin(), lambda_sum_.begin() + n, Real(0));
  scorr_share_.resize(n);
}

// Jacobi iterations of the density constraint: at least solver.pbf.iterations, then on while the
// mean compression that the last λ pass measured (before its correction) is above
// solver.pbf.max_density_error, up to solver.pbf.max_iterations. A fixed count leaves a deep
// column compressed by several percent (2.4% at 40 layers, 4 iterations); the check costs
// nothing, as the λ pass sums the density anyway. Checking the density after the last correction
// would take one more λ pass per substep (about a tenth of a step); the correction lowers the
// error it was computed from, so what the step reports stays close to the tolerance (measured:
// 1.03% worst step for 1%, tests/solver_methods_test.cpp).
template <int D>
void Pbf<D>::solve_density_constraint(double dt) {
  const int least = std::max(1, spec_.pbf_iterations);
  const int most = std::max(least, spec_.pbf_max_iterations);
  const double tolerance = spec_.pbf_max_density_error;
  iterations_ = 0;
  for (;;) {
    double error;
    {
      ScopedTimer timer(times_.density_s);
      error = iterations_ == 0 ? compute_lambda<true>() : compute_lambda<false>();
    }
    {
      ScopedTimer timer(times_.forces_s);
      apply_position_correction();
    }
    ++iterations_;
    if (iterations_ >= most) break;
    if (iterations_ >= least && (tolerance <= 0 || error <= tolerance)) break;
  }
  iteration_sum_ += iterations_;
  ++solves_;
  // Equivalent pressure: Δxᵢ = Δt² aᵢ with aᵢ = −Σⱼ m(pᵢ/ρᵢ² + pⱼ/ρⱼ²)∇Wᵢⱼ gives
  // pᵢ = −ρᵢ² (Σλᵢ + N qᵢ) / (ρ0 Δt²), summed over the N iterations, qᵢ s_corr's share
  // (compute_lambda). Reported, never used.
  const double scale = -1.0 / (prm_.rho0 * dt * dt);
  const std::size_t n = fluid_.size();
  const double iterations = iterations_;
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      fluid_.p[i] = Real(scale * double(fluid_.rho[i]) * fluid_.rho[i] *
                         (double(lambda_sum_[i]) + iterations * scorr_share_[i]));
  });
}

// ρᵢ, Cᵢ and λᵢ in one pair loop (eqs. 2, 1, 11), caching what the Δx pass needs. Returns the
// mean of max(0, ρᵢ/ρ0 − 1), summed in fixed blocks so it is the same for any thread count.
template <int D>
template <bool kShare>
double Pbf<D>::compute_lambda() {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass), support2 = Real(prm_.support * prm_.support);
  const double inv_rho0 = 1.0 / prm_.rho0, inv_rho02 = inv_rho0 * inv_rho0;
  const double eps = spec_.pbf_relaxation * lattice_gradient_norm_;
  const bool clamp = spec_.clamp_negative_pressure;
  const double omega = clamp ? pbf::jacobi_weight(spec_, stable_weight_) : kTwoSidedRelax;
  const PairArrays<D> pa = this->pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx, &bv = pa.bv;
  [[maybe_unused]] const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  const NeighbourList<D>& list = ctx_.fluid_list;  // current: update_neighbours() just ran
  pair_cache_.resize(list);
  for (int k = 0; k < D; ++k) wall_grad_[k].resize(n);
  // Hoisted: the loop's stores then cannot be taken to move the array.
  Real* cache_out[D + 1];
  for (int k = 0; k <= D; ++k) cache_out[k] = pair_cache_.at(0, k);
  const int n_corr = spec_.pbf_scorr_n;
  const double dq = spec_.pbf_scorr_dq * prm_.support;
  [[maybe_unused]] const double k_corr = spec_.pbf_scorr_k / std::max(lattice_gradient_norm_, 1e-30);
  // Records instead of gathers; the positions move every iteration, so copied here.
  const Real* const packed_x = this->pack_positions();
  Real* rho = fluid_.rho.data();
  Real* lambda = lambda_.data();
  Real* lambda_sum = lambda_sum_.data();
  [[maybe_unused]] Real* scorr_share = scorr_share_.data();
  const double compression = with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    const Real inv_w_dq = Real(1.0 / double(K.value(float(dq * dq))));
    const Real floor = Real(pbf::scorr_floor<D>(spec_, prm_, gradient_peak_));
    return pool_.parallel_reduce(n, 0.0, [&](std::size_t b, std::size_t e) {
      // Locals, not the captured originals: the cache stores are floats, so the compiler must
      // otherwise assume they may overwrite the kernel's float constants and reload them.
      const auto Kl = K;
      const Real w_dq_scale = inv_w_dq, q_floor = floor;
      const bool corr1 = n_corr & 1, corr2 = n_corr & 2, corr4 = n_corr & 4, corr8 = n_corr & 8;
      double block_compression = 0;
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
        f8 wf{}, wb{}, sq{}, gf[D] = {}, gb[D] = {}, vs{}, vw{}, vb{};
        std::size_t slot = list.first_slot(i);
        auto pair = [&](auto, const f8* d, f8 r2, i8 m) {
          const f8 G = simd::select(m, Kl.grad_factor(r2), f8{});
          const f8 w = simd::select(m, Kl.value(r2), f8{});
          wf += w;
          sq += G * G * r2;
          for (int k = 0; k < D; ++k) {
            const f8 g = G * d[k];
            gf[k] += g;
            simd::store(cache_out[k] + slot, g);
          }
          // (W/W(Δq))ⁿ by squaring: the bits of n are loop-invariant branches.
          const f8 q = w * w_dq_scale, q2 = q * q, q4 = q2 * q2;
          f8 qn = corr1 ? q : simd::splat(1.0f);
          if (corr2) qn *= q2;
          if (corr4) qn *= q4;
          if (corr8) qn *= q4 * q4;
          simd::store(cache_out[D] + slot, qn);
          if constexpr (kShare) {  // the pairs' virial weights xᵢⱼ·∇Wᵢⱼ = r²G, for s_corr's share
            const f8 v = G * r2;
            vw += v;
            vs += v * simd::max0(qn - q_floor);  // s_corr only below r* (pbf::gradient_peak)
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
                                      const f8 w = simd::select(m, simd::at(psi, j), f8{});
                                      wb += w * Kl.value(r2);
                                      const f8 G = w * Kl.grad_factor(r2);
                                      for (int k = 0; k < D; ++k) gb[k] += G * d[k];
                                      if constexpr (kShare) vb += G * r2;
                                    });
        const double r = double(mass) * simd::hsum(wf) + simd::hsum(wb);
        double dot = 0;
        for (int k = 0; k < D; ++k) {
          const double f = double(mass) * simd::hsum(gf[k]), w = simd::hsum(gb[k]);
          wall_grad_[k][i] = Real(w);
          dot += (f + 2.0 * w) * (f + w);
        }
        const double grad2 = (dot + double(mass) * mass * simd::hsum(sq)) * inv_rho02;
        double C = r * inv_rho0 - 1.0;
        block_compression += std::max(C, 0.0);
        if (clamp) C = std::max(C, 0.0);
        const double l = -omega * C / (grad2 + eps);
        rho[i] = Real(r);
        lambda[i] = Real(l);
        // s_corr is a pair term, (λᵢ + λⱼ + sᵢⱼ) in eq. 14, that carries load: its equivalent of
        // λ is the share qᵢ whose pairs qᵢ + qⱼ have the virial Σⱼ sᵢⱼ xᵢⱼ·∇Wᵢⱼ of the sᵢⱼ
        // themselves (the Irving–Kirkwood pressure of a pair force) in a locally uniform
        // neighbourhood: qᵢ = ½ Σⱼ sᵢⱼ wᵢⱼ / Σ wᵢⱼ, wᵢⱼ = xᵢⱼ·∇Wᵢⱼ. The walls' samples count in
        // the weights (a wall mirrors λᵢ, so a unit pressure's virial includes them) but exert no
        // s_corr: beside a wall the share falls, as the wall's λ carries that load. Reported in
        // the pressure only, so measured in the substep's first pass alone and counted once per
        // iteration (the corrections move the particles by a fraction of a spacing): summed in
        // every pass it cost the real-time profile's step about 5%.
        if constexpr (kShare) {
          const double vwi = simd::hsum(vw) + simd::hsum(vb) / double(mass);
          scorr_share[i] = Real(vwi != 0 ? -0.5 * k_corr * simd::hsum(vs) / vwi : 0.0);
        }
        lambda_sum[i] += Real(l);
      }
      return block_compression;
    }, ThreadPool::kPairs);
  });
  return n ? compression / double(n) : 0.0;
}

// Δxᵢ (eq. 14) with the artificial pressure s_corr = −k [(W(r)/W(Δq))ⁿ − (W(r*)/W(Δq))ⁿ]₊ (eq. 13,
// measured from r*: pbf::gradient_peak), then x += Δx.
// The gradients and weights are the λ pass's: the positions have not moved since.
template <int D>
void Pbf<D>::apply_position_correction() {
  const std::size_t n = fluid_.size();
  const Real mass_over_rho0 = Real(prm_.mass / prm_.rho0), inv_rho0 = Real(1.0 / prm_.rho0);
  // s_corr in units of a unit constraint's λ inside the rest lattice, −1/Σ|∇C|².
  const Real k_corr = Real(spec_.pbf_scorr_k / std::max(lattice_gradient_norm_, 1e-30));
  const Real q_floor = Real(pbf::scorr_floor<D>(spec_, prm_, gradient_peak_));
  const NeighbourList<D>& list = ctx_.fluid_list;
  const Real* lambda = lambda_.data();
  // Jacobi: every Δx comes from the same state, the λ pass's (λ and the cached gradients, not the
  // positions), so each particle can move as soon as its Δx is known. Then collision detection and
  // response against the container (Algorithm 1, line 14): a correction that would take a
  // particle through a wall plane stops it on the plane. (The velocity follows from the positions
  // in update_velocity.)
  const auto walls = this->wall_planes();
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const Real li = lambda[i];
      f8 acc[D] = {};
      // Masked lanes hold zero gradients, so they add nothing.
      for_each_cached_batch<D>(list, i, [&](i8 j, std::size_t slot) {
        const f8 c = li + simd::at(lambda, j) - k_corr * simd::max0(simd::load(pair_cache_.at(slot, D)) - q_floor);
        for (int k = 0; k < D; ++k) acc[k] += c * simd::load(pair_cache_.at(slot, k));
      });
      for (int k = 0; k < D; ++k) {
        const Real dx = mass_over_rho0 * simd::hsum(acc[k]) + 2.0f * li * inv_rho0 * wall_grad_[k][i];
        const Real xn = fluid_.x[k][i] + dx, lo = walls.lo[k], hi = walls.hi[k];
        fluid_.x[k][i] = xn < lo ? lo : xn > hi ? hi : xn;
      }
    }
  }, ThreadPool::kPairs);
}

// vᵢ = (x*ᵢ − xᵢ)/Δt. The predicted step already moved xᵢ by vᵢΔt, so only the correction the
// solver added changes the velocity; particles emitted or put back this step stay consistent.
template <int D>
void Pbf<D>::update_velocity(double dt) {
  const Real inv_dt = Real(1.0 / dt);
  pool_.parallel_for(fluid_.size(), [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < D; ++k) {
      Real* v = fluid_.v[k].data();
      const Real* x = fluid_.x[k].data();
      const Real* xp = predicted_[k].data();
      for (std::size_t i = b; i < e; ++i) v[i] += (x[i] - xp[i]) * inv_dt;
    }
  });
}

template <int D>
void Pbf<D>::add_method_stats(SimStats& s) const {
  s.pressure_iterations = iterations_;
  s.mean_pressure_iterations = solves_ ? iteration_sum_ / double(solves_) : iterations_;
}

template class Pbf<2>;
template class Pbf<3>;

}  // namespace rtsph
