#pragma once
// Self-gravitating SPH gas (Gingold & Monaghan 1977; Lucy 1977), in the modern form of Price
// 2012 (J. Comput. Phys. 231, 759): smoothing lengths hᵢ = η (mᵢ/ρᵢ)^(1/d) solved together with
// the density by Newton–Raphson, the "grad-h" terms Ωᵢ in the momentum equation (Springel &
// Hernquist 2002), a polytropic p = K ρ^γ or adiabatic ideal-gas equation of state, Monaghan's
// artificial viscosity, self-gravity softened by the kernel with its own grad-h term ζᵢ (Price &
// Monaghan 2007), and the toy star's linear force (Monaghan & Price 2004). Kick-drift-kick.
// Walls and obstacle samples exert no pressure on the gas (drift's contact still holds it in a
// closed domain); its scenes are open space (domain.open). docs/self-gravity.md has the equations.
#include "core/gravity_tree.h"
#include "solvers/fluid_world.h"

namespace rtsph {

template <int D>
class Gas final : public FluidWorld<D> {
 public:
  Gas(const SimSpec& spec, int threads);
  void step() override;

 protected:
  void measure_energies(SimStats& s) const override;
  void add_method_stats(SimStats& s) const override;  // h: the smallest hᵢ; c0: the largest cᵢ
  bool sort_after_edit() const override { return false; }  // the step sorts before any pair sum

 private:
  using W = FluidWorld<D>;
  void update_forces();     // sort → ρ, h, Ω → p → hydro + gravity + external accelerations
  void solve_density(Real hcap);     // ρᵢ, hᵢ, Ωᵢ, ζᵢ by Newton–Raphson, per particle
  double global_h() const;           // Gingold & Monaghan 1977, eq. 4
  void global_density(double h);     // ρᵢ with the Gaussian of one h; Ω = 1, ζ = 0
  template <class Grad>
  void hydro_sum(const Grad& grad);  // the pair loop of hydro_accelerations, per kernel
  void compute_pressure();
  void hydro_accelerations();        // pressure, grad-h, viscosity, gravitational grad-h; du/dt
  void add_self_gravity();           // kernel-softened gravity, direct or tree
  void add_external();               // uniform gravity, the spring, damping
  void kick_energy(double dt);       // u += du/dt dt (adiabatic)
  void predict(double half_dt);      // v* = v + a dt/2 (u* likewise), keeping a and du/dt
  void correct(double half_dt);      // v += (a_new − a_kept) dt/2
  double choose_time_step() const;
  double specific_energy(std::size_t i) const;  // uᵢ (J/kg)

  // Per-particle method fields (sorted with the fluid, saved in checkpoints).
  AlignedArray<Real> h_;       // m, smoothing length
  AlignedArray<Real> u_;       // J/kg, internal energy (adiabatic)
  AlignedArray<Real> dudt_;    // W/kg
  AlignedArray<Real> signal_;  // m/s, signal speed for the Courant condition
  AlignedArray<Real> phi_;     // J/kg, gravitational potential (for the energy)
  AlignedArray<Real> a_prev_[D], dudt_prev_;  // a(t), du/dt(t) during a step
  // Scratch, recomputed after each sort.
  AlignedArray<Real> omega_, zeta_, p_term_, a_coef_, cs_, mass_, gacc_[D];
  GravityTree tree_;
};

}  // namespace rtsph
