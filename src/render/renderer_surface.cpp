// Renderer's surface style: hands the fluid's vertex buffer to the 3D screen-space surface
// (surface_pass.h) or the 2D metaball pass (surface2d_pass.h), then restores the state that
// Renderer::draw continues with.
#include "render/renderer.h"

namespace rtsph::render {

int Renderer::draw_surface(const Camera& cam, const Mat4& view, const Mat4& proj, int width,
                           int height, GLuint target_fbo, const RenderSettings& s) {
  const bool three = dim_ == 3;
  RenderSettings splat = s;  // points or quads, from the radius the splats are drawn at
  splat.boundary_radius = 0;
  splat.particle_radius = three ? 2 * s.particle_radius : Surface2dPass::support(s.particle_radius);
  const bool points = use_points(cam, height, splat);
  auto draw_fluid = [this, points] { draw_particles(fluid_vao_, 0, fluid_n_, points); };
  int calls = 0;
  if (three) {
    SurfaceFrame f;
    f.view = view;
    f.proj = proj;
    f.width = width;
    f.height = height;
    f.target_fbo = target_fbo;
    f.points = points;
    f.draw_fluid = draw_fluid;
    calls = surface_->draw(f, s);
  } else {
    calls = surface2d_->draw(view, proj, width, height, target_fbo, points, s, draw_fluid);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, lut_tex_);
  glDisable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glDepthMask(GL_TRUE);
  if (three) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  }
  return calls;
}

}  // namespace rtsph::render
