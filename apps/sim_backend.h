#pragma once
// Choosing where a simulation runs: `--backend cpu|gpu|auto` and the scene's solver.backend.
// A GPU simulation needs an OpenGL context current on the thread that uses it; for the headless
// commands (run, bench) this makes one through EGL and keeps it alive beside the simulation.
#include <memory>
#include <stdexcept>
#include <string>

#include "solvers/simulation.h"

namespace rtsph::app {

/// The backend to use: the command line's when given, else the scene's solver.backend, else
/// `command_default`; "auto" stays "auto" (resolve it where the GL renderer is known).
std::string choose_backend(const std::string& flag, const SimSpec& spec, const std::string& command_default);

/// A simulation and, for the GPU backend, the headless OpenGL context it lives in.
class BackendSimulation {
 public:
  BackendSimulation();
  ~BackendSimulation();
  BackendSimulation(BackendSimulation&&) noexcept;
  BackendSimulation& operator=(BackendSimulation&&) noexcept;
  Simulation* operator->() const { return sim_.get(); }
  Simulation& operator*() const { return *sim_; }
  Simulation* get() const { return sim_.get(); }
  explicit operator bool() const { return bool(sim_); }
  /// "cpu" or "gpu (EGL surfaceless, OpenGL 4.5 ..., llvmpipe ...)".
  const std::string& description() const { return description_; }
  const std::string& backend() const { return backend_; }

  /// Makes the simulation on `backend` ("cpu", "gpu"; "auto" means cpu here). For "gpu" without a
  /// usable context or for a scene the GPU cannot run, throws BackendUnavailable with one line.
  static BackendSimulation make(const SimSpec& spec, int threads, const std::string& backend);

  /// A GPU simulation is made with its context current on the calling thread. To use it from
  /// another thread (the Python API's), release it here and make it current there; GL allows a
  /// context to be current on one thread at a time. No-ops on the CPU backend.
  void make_current();
  void release_current();
  /// Destroys the simulation (a GPU one with its context current, so its buffers are freed).
  void reset();

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;  // declared before sim_: destroyed after it
  std::unique_ptr<Simulation> sim_;
  std::string description_, backend_;
};

/// The GPU backend was asked for and cannot run here (no EGL, no OpenGL 4.3 compute, a build
/// without OpenGL, or a scene it does not support). Commands exit with status 2.
struct BackendUnavailable : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

}  // namespace rtsph::app
