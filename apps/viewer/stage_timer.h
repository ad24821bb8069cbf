#pragma once
// `rtsph view --time-passes`: CPU time of each stage of a drawn frame, measured with glFinish
// between stages (GL_TIME_ELAPSED reads 0 on llvmpipe, the driver this is for). The finishes
// stop the driver from overlapping one stage with the next, so the stages sum to a little more
// than an untimed frame; the first frames (shader compilation) are left out.
#include <epoxy/gl.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdio>

#include "render/surface_pass.h"

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

  /// One line on stdout: the stages, and the surface passes when the surface was drawn.
  void print(const render::SurfacePassTimes& t, std::size_t splats) const {
    std::printf("viewer: ms/frame over %ld frames (glFinish between stages):", counted());
    for (int i = 0; i < kCount; ++i) std::printf(" %s %.2f", kNames[i], ms(Stage(i)));
    if (t.frames > 0 && t.dimension == 2) {
      const double n = double(t.frames);
      std::printf("; 2D surface passes (within scene, at %dx%d): splat %.2f, shade %.2f", t.width,
                  t.height, 1e3 * t.splat_s / n, 1e3 * t.shade_s / n);
    } else if (t.frames > 0) {
      const double n = double(t.frames);
      std::printf("; surface passes (within scene, last at %dx%d): scene %.2f, splat %.2f, "
                  "smooth %.2f, normal %.2f, shade %.2f; %zu splats", t.width, t.height,
                  1e3 * t.scene_s / n, 1e3 * t.splat_s / n, 1e3 * t.smooth_s / n,
                  1e3 * t.normal_s / n, 1e3 * t.shade_s / n, splats);
    }
    std::printf("\n");
  }

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
