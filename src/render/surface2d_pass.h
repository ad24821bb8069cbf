#pragma once
// The 2D fluid surface ("metaballs", the 2014 reference's plan): the particles splat a smooth
// compact kernel into a density field (additive, RGBA16F at the frame's resolution), and a
// full-screen pass fills the region where the field reaches half its bulk value with the water
// colour, antialiased, with a lighter band along the contour. The kernel's support is two
// spacings (four drawn radii), wide enough that the contour of a filled lattice is straight to
// a small fraction of a spacing: no beads at the particle scale.
#include <functional>

#include "render/math.h"
#include "render/pass_clock.h"
#include "render/render_settings.h"
#include "render/shader.h"
#include "render/surface_target.h"

namespace rtsph::render {

class Surface2dPass {
 public:
  Surface2dPass();  // needs a current GL context
  ~Surface2dPass();
  Surface2dPass(const Surface2dPass&) = delete;
  Surface2dPass& operator=(const Surface2dPass&) = delete;

  /// Support of the splat kernel for a drawn particle radius (m).
  static float support(float particle_radius) { return 4.0f * particle_radius; }
  /// Splats the fluid (draw_fluid issues the draw with the bound program, radius = support)
  /// and fills the contour into target_fbo (width × height). Returns the draw calls.
  int draw(const Mat4& view, const Mat4& proj, int width, int height, GLuint target_fbo,
           bool points, const RenderSettings& s, const std::function<void()>& draw_fluid);
  /// RenderSettings::time_passes: the splat and shade passes' CPU time.
  const SurfacePassTimes& times() const { return times_; }

 private:
  Program splat_, shade_;
  TextureTarget field_;
  GLuint empty_vao_ = 0;
  PassClock clock_;
  SurfacePassTimes times_{.dimension = 2};
};

}  // namespace rtsph::render
