#pragma once
// What the binding's files share: the scene and simulation objects Python holds. The binding is
// thin: every behaviour lives in the C++ libraries the CLI uses; these objects only own them,
// serialise access, and convert arrays.
#include <nanobind/nanobind.h>

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "apps/sim_backend.h"
#include "io/exporter.h"
#include "solvers/simulation.h"
#include "solvers/spec.h"

namespace rtsph::py {

namespace nb = nanobind;

/// A validated scene (rtsph.Scene): a SimSpec and nothing else.
struct PyScene {
  SimSpec spec;
};

/// The instability guard tripped (NaN/Inf or runaway compression): rtsph.InstabilityError.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The lock of a simulation. With the GPU backend it also makes the simulation's OpenGL context
/// current on the locking thread and releases it on unlock, so any Python thread may use it.
struct SimMutex {
  std::mutex m;
  app::BackendSimulation* sim = nullptr;
  void lock() {
    m.lock();
    sim->make_current();
  }
  void unlock() {
    sim->release_current();
    m.unlock();
  }
};
using Lock = std::lock_guard<SimMutex>;

/// rtsph.Simulation. One mutex guards the engine: a step runs with the GIL released, so other
/// Python threads (stepping their own simulations) run meanwhile, and a second thread touching
/// the same simulation waits instead of racing. The mutex is never held while taking the GIL.
struct PySimulation {
  PySimulation(const PyScene& scene, int threads, const std::string& backend);
  ~PySimulation();

  app::BackendSimulation sim;  // the engine, and on the GPU backend its headless GL context
  SimMutex mutex{.sim = &sim};
  int threads = 0;              // resolved: 0 (all cores) is replaced by the count in use
  std::string backend = "cpu";
  double max_density_error = 0;  // the instability guard's bound (the CLI's default)
  double wall_s = 0;             // wall time spent stepping, for the summary's rates
  long long steps_taken = 0;     // steps taken through this object (not from a checkpoint)
  // One exporter per (directory, format): successive export() calls write successive frames.
  std::map<std::string, std::unique_ptr<io::Exporter>> exporters;
  std::map<std::string, int> next_frame;
};

void bind_scene(nb::module_& m);
void bind_simulation(nb::module_& m);
void bind_render(nb::module_& m);

}  // namespace rtsph::py
