#include "apps/viewer/sim_runner.h"

#include "apps/viewer/scene_view.h"
#include "solvers/health.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <exception>

namespace rtsph::app {

namespace {
double now_s() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
}  // namespace

SimRunner::SimRunner(const SimSpec& spec, int threads, bool start_paused, SimFactory make,
                     bool on_caller_thread)
    : threads_(threads),
      make_(make ? std::move(make) : SimFactory([](const SimSpec& s, int t) { return make_simulation(s, t); })),
      inline_(on_caller_thread),
      sim_(make_(spec, threads)),
      spec_(spec) {
  paused_ = start_paused;
  publish(*sim_);
  wall_anchor_ = win_wall0_ = now_s();
  sim_anchor_ = win_sim0_ = sim_->time();
  if (!inline_) thread_ = std::thread([this] { loop(); });
}

void SimRunner::pump(double budget_s) {
  if (!inline_) return;
  const double start = now_s();
  try {
    while (!quit_ && tick() < 0 && now_s() - start < budget_s) {
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(cmd_mutex_);
    error_ = std::string("simulation stopped: ") + e.what();
    paused_ = true;
  }
}

SimRunner::~SimRunner() {
  quit_ = true;
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void SimRunner::set_paused(bool p) {
  paused_ = p;
  cv_.notify_all();
}

void SimRunner::step(int n) {
  paused_ = true;
  pending_steps_ += std::max(n, 0);
  cv_.notify_all();
}

void SimRunner::reset(const SimSpec& spec) {
  {
    std::lock_guard<std::mutex> lock(cmd_mutex_);
    reset_spec_ = std::make_unique<SimSpec>(spec);
    commands_.clear();
    resetting_ = true;
  }
  cv_.notify_all();
}

void SimRunner::set_gravity(const Vec3d& g) {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  commands_.push_back([g](Simulation& s) { s.set_gravity(g); });
}

void SimRunner::set_brush(const Brush& b) {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  commands_.push_back([b](Simulation& s) { s.set_brush(b); });
}

void SimRunner::move_obstacle(int index, const Vec3d& c) {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  commands_.push_back([this, index, c](Simulation& s) {
    if (index < 0 || index >= int(s.spec().obstacles.size())) return;
    if (int(obstacle_goals_.size()) <= index) obstacle_goals_.resize(index + 1, {false, Vec3d{}});
    obstacle_goals_[index] = {true, c};
  });
}

void SimRunner::step_once() {
  for (int i = 0; i < int(obstacle_goals_.size()); ++i) {
    auto& [active, goal] = obstacle_goals_[i];
    if (!active) continue;
    const Vec3d cur = sim_->obstacle_center(i);
    Vec3d d = goal - cur;
    const double len = norm(d);
    const double vmax = std::min(3.0, last_c0_ > 0 ? 0.1 * last_c0_ : 3.0);
    const double max_move = vmax * (last_dt_ > 0 ? last_dt_ : spec_.max_dt);
    if (len > max_move) d = d * (max_move / len);
    else active = false;
    sim_->move_obstacle(i, cur + d);
  }
  sim_->step();
  // The instability guard of `rtsph run`: stop and say why instead of drawing NaNs; R resets.
  if (auto msg = check_health_message(*sim_)) {
    std::lock_guard<std::mutex> lock(cmd_mutex_);
    error_ = "simulation unstable, paused (press R to reset): " + *msg;
    paused_ = true;
  }
}

void SimRunner::set_live_parameters(const SimSpec& spec) {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  commands_.push_back([spec](Simulation& s) { s.set_live_parameters(spec); });
}

std::string SimRunner::take_error() {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  std::string e;
  e.swap(error_);
  return e;
}

SimSpec SimRunner::spec() const {
  std::lock_guard<std::mutex> lock(cmd_mutex_);
  return spec_;
}

bool SimRunner::fetch(SimFrame* out) {
  std::lock_guard<std::mutex> lock(frame_mutex_);
  if (!fresh_) return false;
  std::swap(*out, shared_);
  fresh_ = false;
  return true;
}

bool SimRunner::wait_for_frame(std::uint64_t serial, double timeout_s) {
  std::unique_lock<std::mutex> lock(frame_mutex_);
  return frame_cv_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                            [&] { return serial_ > serial; });
}

void SimRunner::publish(Simulation& sim) {
  // Copy outside the lock into the private staging frame, then swap it into the shared slot.
  const BoundaryView b = sim.boundary();
  staging_.device = sim.device_particles();
  if (staging_.device) {
    // Zero copy: only the boundary goes into the snapshot (walls and obstacles are drawn from it).
    staging_.particles.copy_from(ParticleView{.dim = b.dim}, &b);
  } else {
    staging_.particles.copy_from(sim.fluid(), &b);
  }
  staging_.stats = sim.stats();
  last_dt_ = staging_.stats.dt_s;
  last_c0_ = staging_.stats.c0;
  staging_.obstacle_centers.clear();
  for (int i = 0; i < int(sim.spec().obstacles.size()); ++i)
    staging_.obstacle_centers.push_back(sim.obstacle_center(i));
  staging_.obstacle_solids = obstacle_solids(sim);
  staging_.busy_s = busy_s_;
  staging_.rtf = rtf_;
  staging_.step_ms = step_ms_;
  staging_.behind_count = behind_count_;
  staging_.behind_s = behind_s_;
  staging_.generation = generation_;
  {
    std::lock_guard<std::mutex> lock(frame_mutex_);
    staging_.serial = ++serial_;
    std::swap(staging_, shared_);
    fresh_ = true;
  }
  frame_cv_.notify_all();
}

void SimRunner::loop() {
  // The drawing thread comes first: on a machine with few cores (and software GL) the solver
  // takes what is left, and the real-time factor shows it.
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 5);
  try {
    run_loop();
  } catch (const std::exception& e) {
    // A failing step stops the solver thread but not the viewer: report it and stay paused.
    std::lock_guard<std::mutex> lock(cmd_mutex_);
    error_ = std::string("simulation stopped: ") + e.what();
    paused_ = true;
  }
}

void SimRunner::run_loop() {
  while (!quit_) {
    const double wait = tick();
    if (wait < 0) continue;
    std::unique_lock<std::mutex> lock(cmd_mutex_);
    cv_.wait_for(lock, std::chrono::duration<double>(wait));
  }
}

double SimRunner::tick() {
  // Commands and resets from the UI thread.
  std::deque<std::function<void(Simulation&)>> cmds;
  std::unique_ptr<SimSpec> reset;
  {
    std::lock_guard<std::mutex> lock(cmd_mutex_);
    cmds.swap(commands_);
    reset.swap(reset_spec_);
  }
  if (reset) {
    try {
      auto fresh = make_(*reset, threads_);
      {
        std::lock_guard<std::mutex> lock(cmd_mutex_);
        spec_ = *reset;
      }
      sim_ = std::move(fresh);
      ++generation_;
      obstacle_goals_.clear();
      busy_s_ = 0;
      rtf_ = step_ms_ = 0;
      behind_count_ = 0;
      behind_s_ = 0;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(cmd_mutex_);
      error_ = e.what();
    }
    resetting_ = false;
    was_running_ = false;
    publish(*sim_);
    return -1;
  }
  for (auto& c : cmds) c(*sim_);

  if (pending_steps_ > 0) {
    const double a = now_s();
    step_once();
    busy_s_ += now_s() - a;
    --pending_steps_;
    publish(*sim_);
    was_running_ = false;
    return -1;
  }
  if (paused_) {
    was_running_ = false;
    return 0.03;
  }

  const double wall = now_s();
  if (!was_running_) {
    wall_anchor_ = wall;
    sim_anchor_ = sim_->time();
    win_wall0_ = wall;
    win_sim0_ = sim_->time();
    win_busy0_ = busy_s_;
    win_steps0_ = sim_->step_count();
    was_running_ = true;
  }
  double allowed = sim_anchor_ + (wall - wall_anchor_);
  if (allowed - sim_->time() > 0.1) {
    // Behind real time: do not accumulate a backlog to catch up with later.
    ++behind_count_;
    behind_s_ += allowed - sim_->time();
    wall_anchor_ = wall;
    sim_anchor_ = sim_->time();
    allowed = sim_anchor_;
  }
  if (sim_->time() >= allowed) return std::clamp(sim_->time() - allowed, 0.001, 0.02);
  // A batch of steps: until real time is reached or ~1/60 s of work, then publish.
  const double batch_start = now_s();
  double t = batch_start;
  do {
    step_once();
    sim_->wait_idle();  // a GPU step returns early; its cost belongs to this batch
    const double e = now_s();
    busy_s_ += e - t;
    t = e;
  } while (sim_->time() < allowed && t - batch_start < 1.0 / 60 && !quit_ && !resetting_ &&
           pending_steps_ == 0 && !paused_);
  if (t - win_wall0_ >= 1.0) {
    const auto steps = sim_->step_count() - win_steps0_;
    rtf_ = (sim_->time() - win_sim0_) / (t - win_wall0_);
    step_ms_ = steps ? 1000 * (busy_s_ - win_busy0_) / double(steps) : 0;
    win_wall0_ = t;
    win_sim0_ = sim_->time();
    win_busy0_ = busy_s_;
    win_steps0_ = sim_->step_count();
  }
  publish(*sim_);
  return -1;
}

}  // namespace rtsph::app
