#pragma once
// Making a simulation on the GPU backend. The caller owns the OpenGL context: it must be
// current on the calling thread when the simulation is made and whenever it is used.
#include <memory>
#include <string>

#include "solvers/simulation.h"

namespace rtsph::gpu {

/// The methods the GPU backend runs.
bool gpu_supports_method(const std::string& method);
/// Empty when the GPU backend can run `spec`, else one line naming the scene field it lacks.
std::string gpu_cannot_run(const SimSpec& spec);
/// True when the current context renders in software (Mesa llvmpipe/softpipe/swrast, VMware
/// SVGA without a host GPU), where the CPU backend is the faster one: `auto` picks the CPU there.
bool software_renderer();

/// A GPU simulation of `spec` in the current context. Throws std::invalid_argument for what the
/// backend cannot run (its message names the scene field) and std::runtime_error when the
/// context lacks what the backend needs.
std::unique_ptr<Simulation> make_gpu_simulation(const SimSpec& spec, int threads);

}  // namespace rtsph::gpu
