#include "gpu/backend.h"

#include <stdexcept>

#include <fmt/format.h>

#include <epoxy/gl.h>

#include "gpu/gpu_dfsph.h"
#include "gpu/gpu_pbf.h"
#include "gpu/gpu_wcsph.h"

namespace rtsph::gpu {

bool gpu_supports_method(const std::string& method) {
  return method == "wcsph" || method == "pbf" || method == "dfsph";
}

std::string gpu_cannot_run(const SimSpec& spec) {
  if (!gpu_supports_method(spec.method))
    return fmt::format("scene '{}': solver.method = \"{}\": the GPU backend runs \"wcsph\", \"pbf\" and \"dfsph\"; use --backend cpu",
                       spec.name, spec.method);
  return {};
}

bool software_renderer() {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = r ? r : "";
  for (const char* soft : {"llvmpipe", "softpipe", "swrast", "SVGA3D", "Software Rasterizer"})
    if (name.find(soft) != std::string::npos) return true;
  return false;
}

std::unique_ptr<Simulation> make_gpu_simulation(const SimSpec& spec, int threads) {
  if (const std::string why = gpu_cannot_run(spec); !why.empty()) throw std::invalid_argument(why);
  if (spec.method == "dfsph") {
    if (spec.dimension == 2) return std::make_unique<GpuDfsph<2>>(spec, threads);
    return std::make_unique<GpuDfsph<3>>(spec, threads);
  }
  if (spec.method == "pbf") {
    if (spec.dimension == 2) return std::make_unique<GpuPbf<2>>(spec, threads);
    return std::make_unique<GpuPbf<3>>(spec, threads);
  }
  if (spec.dimension == 2) return std::make_unique<GpuWcsph<2>>(spec, threads);
  return std::make_unique<GpuWcsph<3>>(spec, threads);
}

}  // namespace rtsph::gpu
