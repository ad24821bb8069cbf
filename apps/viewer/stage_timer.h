#pragma once
// `rtsph view --time-passes`: CPU time of each stage of a drawn frame, measured with glFinish
// between stages (GL_TIME_ELAPSED reads 0 on llvmpipe, the driver this is for). The finishes
// stop the driver from overlapping one stage with the next, so the stages sum to a little more
// than an untimed frame; the first frames (shader compilation) are left out.
#include <epoxy/gl.h>

#include <array>
#include <chrono>
#include <cstdio>

namespace rtsph::app {

class StageTimer {
 public:
  enum Stage { kUpload, kScene, kBlit, kUi, kSwap, kCount };
  static constexpr std::array<const char*, kCount> kNames = {"upload", "scene", "blit+legend",
                                                             "ui", "swap"};
  explicit StageTimer(bool on) : on_(on) {}
  bool on() const { return on_; }

  void start() {
    if (!on_) return;
    glFinish();
    t_ = now_s();
  }
  void lap(Stage s) {
    if (!on_) return;
    glFinish();
    const double t = now_s();
    if (frames_ >= kWarmup) sum_s_[s] += t - t_;
    t_ = t;
  }
  void end_frame() {
    if (on_) ++frames_;
  }
  long counted() const { return frames_ > kWarmup ? frames_ - kWarmup : 0; }
  double ms(Stage s) const { return counted() ? 1e3 * sum_s_[s] / double(counted()) : 0.0; }

 private:
  static constexpr long kWarmup = 5;
  static double now_s() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
  }
  bool on_;
  double t_ = 0;
  long frames_ = 0;
  std::array<double, kCount> sum_s_{};
};

}  // namespace rtsph::app
