#pragma once
// Screen-space fluid surface in 3D (van der Laan, Green & Sainz 2009; the depth filter after
// Truong & Yuksel 2018). Per frame:
//   scene      the opaque scene (floor grid, obstacles) into a colour + depth texture at full
//              resolution (drawn by Renderer between begin_scene() and draw());
//   splat      one draw of the fluid particles into two images (surface resolution): the
//              nearest sphere's eye distance (blend MAX of its inverse) and the thickness,
//              soft additive splats summing to the depth of water along each ray;
//   smooth     a separable bilateral filter of the depth, x then y, radius ∝ screen size;
//   normal     normals from the smoothed depth, stored with it;
//   shade      full resolution into the target (which holds the opaque scene), where there is
//              water: Fresnel mix of a sky gradient and the refracted scene, Beer–Lambert
//              absorption, highlight, spray; writes depth so later geometry (walls, boundary
//              particles) sorts with it.
// The fluid passes run at RenderSettings::surface_scale of the frame's resolution; the passes
// after the splats only inside the screen rectangle of the fluid's bounding box (scissor).
#include <array>
#include <functional>

#include "render/math.h"
#include "render/pass_clock.h"
#include "render/render_settings.h"
#include "render/shader.h"
#include "render/surface_target.h"

namespace rtsph::render {

/// What the surface needs of the frame; draw_fluid issues the fluid's splats' draw call with
/// the currently bound program (surface_splat.vert's attributes: x, y, z and, when weighted,
/// the splat's particle count).
struct SurfaceFrame {
  Mat4 view, proj;
  int width = 1, height = 1;      // the target's size (pixels)
  GLuint target_fbo = 0;
  bool points = true;             // particles go out as point sprites
  bool weighted = false;          // draw_fluid's attribute 3 holds splat weights (splat_batch.h)
  std::function<void()> draw_fluid;
  // Target pixels (x0, y0, x1, y1) outside which there is no water: the passes after the splats
  // skip the rest. The target already holds the opaque scene (the shading pass draws only
  // where there is water).
  std::array<int, 4> box{0, 0, 1 << 30, 1 << 30};
};

class SurfacePass {
 public:
  SurfacePass();  // needs a current GL context
  ~SurfacePass();
  SurfacePass(const SurfacePass&) = delete;
  SurfacePass& operator=(const SurfacePass&) = delete;

  /// Binds the full-resolution scene target; the caller clears it and draws the opaque scene.
  void begin_scene(int width, int height, bool time_passes);
  /// Runs depth, thickness, smoothing and shading; leaves the target bound with its viewport.
  /// Returns the number of draw calls.
  int draw(const SurfaceFrame& f, const RenderSettings& s);
  /// 0: shaded; 1: world-space normals as colours 0.5 + 0.5·n (tests).
  void set_output(int output) { output_ = output; }
  const SurfacePassTimes& times() const { return times_; }

 private:
  void lap(double* into) { clock_.lap(into); }

  Program splat_, smooth_, normal_, shade_;
  TextureTarget scene_, splat_target_, smooth_a_, smooth_b_, normal_target_;
  GLuint empty_vao_ = 0;
  int output_ = 0;
  PassClock clock_;
  SurfacePassTimes times_;
};

}  // namespace rtsph::render
