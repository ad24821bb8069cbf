#pragma once
// WCSPH on the GPU: the CPU method's algorithm (solvers/wcsph.h) stage for stage, each stage a
// compute pass (shaders/gpu/), on the same scene, parameters, kernels and boundary model.
#include "gpu/gpu_world.h"

namespace rtsph::gpu {

template <int D>
class GpuWcsph final : public GpuWorld<D> {
 public:
  GpuWcsph(const SimSpec& spec, int threads);
  void step() override;

 private:
  void update_forces();  // sort → density and pressure → wall pressure → accelerations
};

}  // namespace rtsph::gpu
