#pragma once
// Runs a Simulation on its own thread so the viewer stays responsive. After each batch of
// steps the particle arrays are copied into a snapshot and swapped into a shared slot under a
// mutex (double buffering); the UI thread swaps it out when it draws. Pacing: simulated time
// never runs ahead of real time; when the machine cannot keep up the real-time factor says so.
//
// The GPU backend runs on the caller's thread instead (on_caller_thread): its simulation lives
// in the drawing thread's OpenGL context, the viewer calls pump() once per frame, which steps
// for at most a frame's budget, and the frame carries the GPU's buffers instead of a copy.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "render/snapshot.h"
#include "render/solids.h"
#include "solvers/simulation.h"

namespace rtsph::app {

struct SimFrame {
  render::ParticleSnapshot particles;
  SimStats stats;
  std::vector<Vec3d> obstacle_centers;
  std::vector<render::SolidShape> obstacle_solids;  // geometry at the current poses
  double busy_s = 0;            // wall seconds spent in step() since the last reset
  double rtf = 0;               // simulated / real seconds over about the last second running
  double step_ms = 0;           // mean wall ms per step over the same window
  int behind_count = 0;         // times the solver fell 0.1 s behind real time since the reset
  double behind_s = 0;          // the simulated seconds those times skipped
  std::uint64_t serial = 0;     // increases with every published frame
  std::uint64_t generation = 0; // increases with every reset
  std::optional<DeviceParticles> device;  // GPU backend: draw from these, `particles` is empty
};

/// Builds a simulation for the runner (default: make_simulation, the CPU).
using SimFactory = std::function<std::unique_ptr<Simulation>(const SimSpec&, int threads)>;

class SimRunner {
 public:
  /// Builds the simulation on the calling thread (throws on a bad spec) and starts the thread.
  SimRunner(const SimSpec& spec, int threads, bool start_paused, SimFactory make = {},
            bool on_caller_thread = false);
  ~SimRunner();
  SimRunner(const SimRunner&) = delete;
  SimRunner& operator=(const SimRunner&) = delete;

  void set_paused(bool paused);
  bool paused() const { return paused_; }
  /// n single steps (pauses first).
  void step(int n = 1);
  /// Rebuilds the simulation from spec on the solver thread; errors go to take_error().
  void reset(const SimSpec& spec);
  void set_gravity(const Vec3d& g);
  void set_brush(const Brush& b);
  /// Moves an obstacle towards `center` at a bounded speed (min(3 m/s, c0/10)), so that a fast
  /// mouse drag does not teleport it through the fluid.
  void move_obstacle(int index, const Vec3d& center);
  void set_live_parameters(const SimSpec& spec);

  /// Swaps the newest published frame into *out; false if nothing new since the last call.
  bool fetch(SimFrame* out);
  /// Blocks until a frame newer than `serial` is published (or timeout); for scripts and tests.
  bool wait_for_frame(std::uint64_t serial, double timeout_s);
  std::string take_error();
  SimSpec spec() const;
  /// True while steps are pending or running (for scripts waiting on `step`).
  bool busy() const { return pending_steps_ > 0 || resetting_; }
  /// on_caller_thread only: runs commands and steps for at most budget_s of wall time.
  void pump(double budget_s);
  bool on_caller_thread() const { return inline_; }

 private:
  void loop();
  void run_loop();
  /// One pass of the solver loop: commands, a reset, a step or a batch of steps. Returns how
  /// long to wait before the next pass (0 or more: paused or ahead of real time), or -1.
  double tick();
  void publish(Simulation& sim);
  void step_once();  // one solver step, with obstacle goals applied
  std::vector<std::pair<bool, Vec3d>> obstacle_goals_;  // solver thread only
  double last_dt_ = 0, last_c0_ = 0;

  int threads_;
  SimFactory make_;
  bool inline_ = false;
  // Pacing anchors: simulated time may not exceed sim_anchor_ + (wall - wall_anchor_).
  double wall_anchor_ = 0, sim_anchor_ = 0;
  bool was_running_ = false;
  std::unique_ptr<Simulation> sim_;
  SimSpec spec_;
  mutable std::mutex cmd_mutex_;
  std::condition_variable cv_;
  std::deque<std::function<void(Simulation&)>> commands_;
  std::unique_ptr<SimSpec> reset_spec_;
  std::atomic<bool> paused_{false}, quit_{false}, resetting_{false};
  std::atomic<int> pending_steps_{0};
  std::string error_;

  std::mutex frame_mutex_;
  std::condition_variable frame_cv_;
  SimFrame shared_, staging_;
  bool fresh_ = false;
  std::uint64_t serial_ = 0, generation_ = 0;
  double busy_s_ = 0;
  // real-time factor window
  double win_sim0_ = 0, win_busy0_ = 0;
  std::uint64_t win_steps0_ = 0;
  double win_wall0_ = 0;
  double rtf_ = 0, step_ms_ = 0;
  int behind_count_ = 0;
  double behind_s_ = 0;
  std::thread thread_;
};

}  // namespace rtsph::app
