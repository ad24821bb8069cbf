#include "gpu/backend.h"

#include <stdexcept>

#include <fmt/format.h>

#include "gpu/gpu_wcsph.h"

namespace rtsph::gpu {

bool gpu_supports_method(const std::string& method) { return method == "wcsph"; }

std::unique_ptr<Simulation> make_gpu_simulation(const SimSpec& spec, int threads) {
  if (!gpu_supports_method(spec.method))
    throw std::invalid_argument(fmt::format(
        "scene '{}': solver.method = \"{}\": the GPU backend runs \"wcsph\" so far; use --backend cpu",
        spec.name, spec.method));
  if (spec.dimension == 2) return std::make_unique<GpuWcsph<2>>(spec, threads);
  return std::make_unique<GpuWcsph<3>>(spec, threads);
}

}  // namespace rtsph::gpu
