#pragma once
// Divergence-Free SPH on the GPU: the CPU method's step (solvers/dfsph.h; Bender & Koschier
// 2017, Algorithm 1) stage for stage, each stage a compute pass (shaders/gpu/dfsph_*.comp). The
// solves stop on the same mean residual, tested on the device after each sweep (dfsph_gate.comp):
// the host queues a batch of sweeps, as many as the last solve took, and reads the outcome back
// once per batch, so the GPU does not wait on the host between sweeps. The sweeps walk
// the grid's cell ranges and evaluate the kernel gradients again, where the CPU caches them per
// listed pair: the GPU recomputes rather than streams.
#include <string>
#include <vector>

#include "gpu/gpu_world.h"
#include "solvers/dfsph.h"

namespace rtsph::gpu {

template <int D>
class GpuDfsph final : public GpuWorld<D> {
 public:
  GpuDfsph(const SimSpec& spec, int threads);
  void step() override;
  std::string solver_failure() const override { return failure_; }
  void state_loaded() override;

 private:
  double choose_time_step();
  void factors(bool with_density);              // αᵢ (eq. 8), neighbour counts, wall sums; ρᵢ
  /// Warm start, then Jacobi sweeps to the tolerance (Algorithms 2 and 3); returns the sweeps.
  int solve(bool density, double dt, double tolerance, const char* name);
  void apply_pressure(int source);              // vᵢ += Δt aᵢ from solve[].x (0) or .z (2)
  void residual(bool density, double dt);       // this sweep's change; its error summed on the device
  void gate(int mode, int least = 0, int most = 0, double threshold = 0);  // dfsph_gate.comp
  void bind_method() const;
  void add_method_scalars(std::vector<StateField>& f) override;
  void add_method_stats(SimStats& s) const override;

  ComputeProgram nonpressure_, factors_, apply_, residual_, sweep_, totals_, gate_;
  Buffer solve_, factor_buf_, wgrad_, warm_, warm_alt_;
  // The CPU's method fields, in its order, so checkpoints resume on either backend: the
  // factors and the warm start are device fields; pressure and last_step are the CPU's scratch.
  AlignedArray<Real> factor_, neighbours_, pressure_, last_step_, warm_density_, warm_divergence_;
  double relax_ = 0.5;      // Jacobi ω (dfsph::jacobi_relaxation)
  double tiny_ = 0;         // 1/α below this: no neighbours to push
  std::vector<float> cut_table_;  // solver.dfsph.surface_density "lattice": (|c|, τ) rows; else empty
  double density_bias_ = 0; // as the CPU's Dfsph::correct_density_error
  dfsph::Counters counters_;  // saved as the CPU's are
  // Sweeps the last divergence [0] and density [1] solves took: the next one's first batch.
  // Only how often the host reads back depends on them, never a result.
  int last_sweeps_[2] = {1, 2};
  std::string failure_;
};

}  // namespace rtsph::gpu
