#pragma once
// CPU time of a frame's render passes (RenderSettings::time_passes), shared by the 3D surface
// and the 2D surface: glFinish between passes, so each lap holds its pass's GPU work and the
// sum exceeds the pipelined frame time a little. The first frame compiles the shaders and is
// not counted.
#include <epoxy/gl.h>

#include <chrono>

namespace rtsph::render {

/// Per-pass CPU time, summed over `frames`. `dimension` 3: the screen-space surface's passes;
/// 2: the metaball surface (splat and shade only).
struct SurfacePassTimes {
  double scene_s = 0, splat_s = 0, smooth_s = 0, normal_s = 0, shade_s = 0;
  long frames = 0;
  int width = 0, height = 0;  // the fluid passes' resolution in the last frame
  int dimension = 3;
};

class PassClock {
 public:
  /// Starts a frame's timing (when on): waits for the GL work so far.
  void begin(bool on) {
    on_ = on;
    if (!on_) return;
    glFinish();
    t_last_ = now_s();
  }
  /// Adds the time since the last lap to *into, after the GL work issued so far.
  void lap(double* into) {
    if (!on_) return;
    glFinish();
    const double t = now_s();
    if (warm_) *into += t - t_last_;
    t_last_ = t;
  }
  /// Ends the frame: counts it (once warm) into *frames.
  void end_frame(long* frames) {
    if (on_ && warm_) ++*frames;
    warm_ = true;
  }

 private:
  static double now_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
  bool on_ = false;
  bool warm_ = false;  // a frame has been drawn
  double t_last_ = 0;
};

}  // namespace rtsph::render
