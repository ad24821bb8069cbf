#pragma once
// Position Based Fluids (Macklin & Müller 2013): a density constraint Cᵢ = ρᵢ/ρ0 − 1 per
// particle, solved by Jacobi iterations on predicted positions, so steps can be a frame long.
// Walls and obstacles couple through the same Akinci boundary samples as every method.
#include "solvers/fluid_world.h"

namespace rtsph {

namespace pbf {
/// The stable Jacobi weight for the spec's kernel, h and spacing: min(1, 0.9 · 2/λmax)
/// (jacobi_lambda_max): the rest lattice's stiffest mode shrinks by 0.8 each iteration. 0.64 in
/// 3D and 0.84 in 2D for the cubic spline at h = spacing.
template <int D>
double stable_weight(const SimSpec& spec, const ResolvedParams& prm);
/// r* (m), where the kernel's |∇W| peaks (2h/3 for the cubic spline). s_corr's weight there,
/// (W(r*)/W(Δq))ⁿ, is subtracted from each pair's and clamped at 0, so s_corr acts only on pairs
/// closer than r* (pbf.cpp).
template <int D>
double gradient_peak(const SimSpec& spec, const ResolvedParams& prm);
/// That weight, (W(r*)/W(Δq))ⁿ, for the spec's kernel, Δq and n (both backends use it).
template <int D>
double scorr_floor(const SimSpec& spec, const ResolvedParams& prm, double r_star);
/// The weight of a clamped iteration's λ: solver.pbf.omega, or `stable` where that is 0.
inline double jacobi_weight(const SimSpec& spec, double stable) {
  return spec.pbf_omega > 0 ? spec.pbf_omega : stable;
}
}  // namespace pbf

template <int D>
class Pbf final : public FluidWorld<D> {
 public:
  Pbf(const SimSpec& spec, int threads);
  void step() override;

 private:
  using W = FluidWorld<D>;
  using W::spec_, W::pool_, W::prm_, W::fluid_, W::boundary_, W::ctx_, W::times_;

  double choose_time_step() const;
  void surface_forces_at_prediction(double dt);  // Akinci 2013 at x*, with the constraint
  void save_predicted_positions();
  void solve_density_constraint(double dt);  // λᵢ, then Δxᵢ (eqs. 11-14), Jacobi
  /// Returns the mean compression it measured. kShare: also s_corr's share of the pressure
  /// (scorr_share_), in the substep's first pass only.
  template <bool kShare>
  double compute_lambda();
  void apply_position_correction();
  void update_velocity(double dt);           // vᵢ = (x*ᵢ − xᵢ)/Δt (Algorithm 1, line 21)
  void xsph_and_vorticity(double dt);        // eqs. 15-17, and ρ at the corrected positions
  void add_method_stats(SimStats& s) const override;
  bool sort_after_edit() const override { return false; }  // step(): predict, then sort
  bool density_read_after_sort() const override {  // surface_forces_at_prediction
    return W::density_read_after_sort() || this->surface_forces_active();
  }

  double stable_weight_ = 1;         // pbf::stable_weight, for solver.pbf.omega = 0
  double gradient_peak_ = 0;         // pbf::gradient_peak (m)
  double lattice_gradient_norm_ = 0;  // Σⱼ|∇ⱼCᵢ|² of a particle inside the rest lattice (1/m²)
  AlignedArray<Real> lambda_, lambda_sum_, scorr_share_, rho_next_;
  std::array<AlignedArray<Real>, D> predicted_, delta_;
  AlignedArray<Real> packed_v_;  // 3D: (vx, vy, vz, ρ) records for the XSPH pass
  AlignedArray<Real> omega_[D == 2 ? 1 : 3];
  // What the λ pass leaves for the Δx pass of the same iteration (same positions): per listed
  // pair ∇ᵢWᵢⱼ and the s_corr weight (W/W(Δq))ⁿ (its floor is subtracted where it is read), zero on masked lanes; per particle the wall
  // gradient Σ_b Ψ_b∇W_ib. The Δx pass then evaluates no kernel and walks no wall.
  PairCache<D + 1> pair_cache_;  // per listed pair: ∇Wᵢⱼ (fields 0..D-1), s_corr weight (D)
  std::array<AlignedArray<Real>, D> wall_grad_;
  int iterations_ = 0;             // of the last substep
  double iteration_sum_ = 0;       // over the substeps this object solved (not a resumed run's)
  std::uint64_t solves_ = 0;
};

}  // namespace rtsph
