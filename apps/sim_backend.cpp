#include "apps/sim_backend.h"

#include <fmt/format.h>

#include <stdexcept>

#ifdef RTSPH_HAVE_GPU
#include "gpu/backend.h"
#include "gpu/gl_compute.h"
#include "render/gl_context.h"
#endif

namespace rtsph::app {

std::string choose_backend(const std::string& flag, const SimSpec& spec, const std::string& command_default) {
  if (!flag.empty()) return flag;
  if (!spec.backend.empty() && spec.backend != "auto") return spec.backend;
  return command_default;
}

#ifdef RTSPH_HAVE_GPU
struct BackendSimulation::Gl {
  std::unique_ptr<render::HeadlessContext> context;
};
#else
struct BackendSimulation::Gl {};
#endif

BackendSimulation::BackendSimulation() = default;
BackendSimulation::~BackendSimulation() = default;
BackendSimulation::BackendSimulation(BackendSimulation&&) noexcept = default;
BackendSimulation& BackendSimulation::operator=(BackendSimulation&&) noexcept = default;

BackendSimulation BackendSimulation::make(const SimSpec& spec, int threads, const std::string& backend) {
  BackendSimulation out;
  out.backend_ = backend == "gpu" ? "gpu" : "cpu";
  if (backend != "gpu") {
    out.sim_ = make_simulation(spec, threads);
    out.description_ = "cpu";
    return out;
  }
#ifdef RTSPH_HAVE_GPU
  std::string err;
  out.gl_ = std::make_unique<Gl>();
  out.gl_->context = render::HeadlessContext::create(&err);
  if (!out.gl_->context)
    throw BackendUnavailable(fmt::format("--backend gpu: no OpenGL 4.3 context: {}", err));
  if (const std::string why = gpu::compute_support_problem(); !why.empty())
    throw BackendUnavailable("--backend gpu: " + why);
  try {
    out.sim_ = gpu::make_gpu_simulation(spec, threads);
  } catch (const std::invalid_argument& e) {
    throw BackendUnavailable(e.what());
  }
  out.description_ = "gpu (" + out.gl_->context->description() + ")";
  return out;
#else
  (void)threads;
  throw BackendUnavailable("--backend gpu: this rtsph was built without OpenGL (RTSPH_BUILD_VIEWER=OFF)");
#endif
}

#ifdef RTSPH_HAVE_GPU
void BackendSimulation::make_current() {
  if (gl_ && gl_->context) gl_->context->make_current();
}
void BackendSimulation::release_current() {
  if (gl_ && gl_->context) gl_->context->release();
}
#else
void BackendSimulation::make_current() {}
void BackendSimulation::release_current() {}
#endif

void BackendSimulation::reset() {
  make_current();
  sim_.reset();
  release_current();
  gl_.reset();
}

}  // namespace rtsph::app
