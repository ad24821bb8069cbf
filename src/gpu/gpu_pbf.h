#pragma once
// Position Based Fluids on the GPU: the CPU method's algorithm (solvers/pbf.h, Macklin & Müller
// 2013, Algorithm 1) stage for stage, each stage a compute pass (shaders/gpu/pbf_*.comp).
#include "gpu/gpu_world.h"

namespace rtsph::gpu {

template <int D>
class GpuPbf final : public GpuWorld<D> {
 public:
  GpuPbf(const SimSpec& spec, int threads);
  void step() override;

 private:
  double choose_time_step();
  void solve_density_constraint(double dt);  // λ, then Δx, Jacobi (eqs. 11-14)
  void xsph_and_vorticity(double dt);        // eqs. 15-17, and ρ at the corrected positions
  /// Line 6: each particle's neighbours, listed once per substep for the iterations.
  void list_neighbours();
  /// Line 2's surface forces, at x* (the CPU's Pbf::surface_forces_at_prediction), after the sort.
  void surface_forces_at_prediction();
  void bind_lists(const ComputeProgram& prog) const;
  void gate(int mode, int least = 0, int most = 0, double threshold = 0);  // pbf_gate.comp
  void add_method_stats(SimStats& s) const override;

  ComputeProgram external_, surface_, copy_, lambda_, correct_, velocity_, xsph_, vorticity_, apply_, list_, gate_;
  Buffer pred_, lambda_buf_, wgrad_, delta_, omega_;
  Buffer nlist_, blist_, ncount_;   // pbf_list.comp's lists (fluid, walls) and counts
  GLuint fluid_cap_ = 0, boundary_cap_ = 0;  // list slots per particle
  GLint64 max_block_bytes_ = 0;     // the largest storage block this GL allows
  bool lists_ = false;              // this substep's lists were built
  double stable_weight_ = 1;          // pbf::stable_weight, for solver.pbf.omega = 0
  double gradient_peak_ = 0;          // pbf::gradient_peak (m): s_corr acts below it
  double lattice_gradient_norm_ = 0;  // Σⱼ|∇ⱼCᵢ|² inside the rest lattice (1/m²)
  int iterations_ = 0;             // of the last substep (the next one's first batch)
  double iteration_sum_ = 0;       // over the substeps this object solved (not a resumed run's)
  std::uint64_t solves_ = 0;
};

}  // namespace rtsph::gpu
