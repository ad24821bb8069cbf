#pragma once
// Divergence-Free SPH (Bender & Koschier 2015, 2017): two implicit pressure solves per step,
// one that keeps the density at ρ0 and one that keeps the velocity field divergence-free, so
// the step is limited by the flow speed (CFL) instead of the speed of sound.
#include <cstdint>
#include <string>
#include <vector>

#include "solvers/fluid_world.h"
#include "solvers/surface_density.h"

namespace rtsph {

// What the CPU and GPU backends' DFSPH share (the reasons are at the definitions in
// dfsph.cpp and dfsph_solve.cpp).
namespace dfsph {
/// Share of the last step's pressure the warm start applies.
inline constexpr double kWarm = 0.5;
/// The divergence solve leaves particles with fewer neighbours (fluid + boundary, itself
/// included) alone: free surface and spray (2017, §4.2).
template <int D>
inline constexpr float kMinNeighbours = D == 3 ? 20.0f : 7.0f;
/// The Jacobi sweeps' relaxation ω for the scene's kernel, from the rest lattice.
template <int D>
double jacobi_relaxation(const SimSpec& s, const ResolvedParams& prm);
/// Whether the density solve targets the fluid's mean kernel sum instead of ρ0: two-sided
/// pressure in a periodic box the fluid fills (Dfsph::correct_density_error says why).
template <int D>
bool targets_mean_density(const SimSpec& s, std::size_t fluid_count);
/// The Chebyshev weight of sweep `it` (0-based) of a clamped density solve with spectral radius
/// rho, from the previous sweep's `omega` (1 before the third sweep and for rho = 0).
double chebyshev_weight(int it, double rho, double omega);
/// Whether a solve that ran `sweeps` sweeps with Chebyshev's rho ends with one plain sweep: when
/// the acceleration acted (a third sweep with rho > 0). Both backends; the reason at Dfsph::solve.
bool smooths_last(int sweeps, double rho);
/// Δt = cfl·d/max(|v|max, √head), head = |g| times the fluid's extent along gravity, also bounded
/// by the force and viscous limits and max_dt; the fixed step in fixed mode.
double time_step(const SimSpec& s, const ResolvedParams& prm, double v2max, double a2max,
                 double head, double viscous_limit);
/// The solves' counters both backends keep, save in checkpoints (under the same names) and report.
struct Counters {
  int density_iterations = 0, divergence_iterations = 0;    // of the last step
  double density_iteration_sum = 0, divergence_iteration_sum = 0;
  std::uint64_t capped_steps = 0;  // steps whose density or divergence solve hit its cap
  void end_step(bool capped);      // adds the last step's counts to the sums
  void add_scalars(std::vector<StateField>& f);
  void add_stats(SimStats& s, std::uint64_t steps) const;
};
/// The instability guard's line for a solve that stopped at its cap above its tolerance.
std::string not_converged(const char* solve, int iterations, double t, double error, double tolerance);
}  // namespace dfsph

template <int D>
class Dfsph final : public FluidWorld<D> {
 public:
  Dfsph(const SimSpec& spec, int threads);
  void step() override;
  std::string solver_failure() const override { return failure_; }
  void state_loaded() override;

 private:
  using W = FluidWorld<D>;
  using W::spec_, W::pool_, W::prm_, W::fluid_, W::boundary_, W::ctx_, W::times_;

  double choose_time_step() const;
  /// αᵢ and neighbour counts (2017, eq. 8) and the sweeps' caches; with_density also sums ρᵢ
  /// (compute_density's sum, in the same order, so the same bits) in the same walk.
  void compute_factors(bool with_density = false);
  double correct_density_error(double dt);       // Algorithm 3
  double correct_divergence_error(double dt);    // Algorithm 2
  /// Warm start from `total` (last step's pressure), then projected Jacobi sweeps until the
  /// mean residual reaches the tolerance; leaves this step's total pressure in `total`.
  template <bool kDensity>
  int solve(double dt, AlignedArray<Real>& total, double tolerance, const char* name);
  /// Dρᵢ/Dt = Σⱼ m vᵢⱼ·∇Wᵢⱼ + Σ_b Ψ_b (vᵢ − v_b)·∇W_ib (eq. 9) with the current velocities,
  /// turned into this sweep's Pᵢ (pressure_); returns the mean relative residual.
  double residual(bool density, double dt, const AlignedArray<Real>& total);
  void apply_pressure(const Real* P, double dt);
  void add_method_scalars(std::vector<StateField>& f) override;
  void add_method_stats(SimStats& s) const override;

  AlignedArray<Real> factor_;        // 1/(|Σm∇W + Σ_bΨ∇W|-weighted sums), m^(2d+2)/kg² (eq. 8)
  AlignedArray<Real> neighbours_;    // fluid + boundary neighbours, for the divergence clamp
  AlignedArray<Real> pressure_;      // Pᵢ = κᵢ/ρᵢ of the current sweep (m^(d+2)/(kg s²))
  AlignedArray<Real> packed_v_;      // vᵢ as (x, y, z, 0) (3D) or (x, y) (2D) records, for the residual's loads
  AlignedArray<Real> last_step_;     // the previous sweep's change of Pᵢ (Chebyshev)
  AlignedArray<Real> warm_density_, warm_divergence_;  // Σκ/ρ of the last step, times Δt², Δt
  // The positions do not move between compute_factors() and the end of the next density solve
  // (both solves), so the sweeps read the kernel gradients from here instead of evaluating
  // them again: ∇Wᵢⱼ per listed pair (zero on masked lanes), and per particle the wall sums
  // Σ_b Ψ_b∇W_ib and Σ_b Ψ_b v_b·∇W_ib. Rebuilt by compute_factors(); never saved.
  PairCache<D> pair_grad_;  // ∇Wᵢⱼ per listed pair
  std::array<AlignedArray<Real>, D> wall_grad_;
  AlignedArray<Real> wall_rate_;
  // solver.dfsph.surface_density = "lattice": the density each particle's clamped solve keeps,
  // ρ0 τ(|cᵢ|) from its colour gradient (surface_density.h); rebuilt by compute_factors().
  CutSumTable cut_sums_;
  AlignedArray<Real> target_;
  // Fully periodic, two-sided solves: the kernel-sum density's mean over the fluid minus ρ0, which
  // no velocity field can remove (correct_density_error). 0 otherwise.
  double density_bias_ = 0;
  double relax_ = 0.5;               // Jacobi ω, set once from the kernel (jacobi_relaxation)
  dfsph::Counters counters_;
  std::string failure_;
};

}  // namespace rtsph
