// Renderer's surface style: hands the fluid's vertex buffer to the 3D screen-space surface
// (surface_pass.h) or the 2D metaball pass (surface2d_pass.h), then restores the state that
// Renderer::draw continues with.
#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rtsph::render {

// The pixels (x0, y0, x1, y1; GL's lower-left origin) that the fluid's bounding box, grown by
// the splat radius, projects to: every splat falls inside. The whole frame when a corner lies
// behind the eye.
std::array<int, 4> Renderer::screen_box(const Mat4& view, const Mat4& proj, int width,
                                        int height, float grow) const {
  const std::array<int, 4> full{0, 0, width, height};
  const Mat4 vp = proj * view;
  float x0 = 1, y0 = 1, x1 = -1, y1 = -1;
  for (int c = 0; c < 8; ++c) {
    const float x = (c & 1) ? fluid_hi_.x + grow : fluid_lo_.x - grow;
    const float y = (c & 2) ? fluid_hi_.y + grow : fluid_lo_.y - grow;
    const float z = (c & 4) ? fluid_hi_.z + grow : fluid_lo_.z - grow;
    const float w = vp.at(3, 0) * x + vp.at(3, 1) * y + vp.at(3, 2) * z + vp.at(3, 3);
    if (!(w > 1e-4f)) return full;
    const float nx = (vp.at(0, 0) * x + vp.at(0, 1) * y + vp.at(0, 2) * z + vp.at(0, 3)) / w;
    const float ny = (vp.at(1, 0) * x + vp.at(1, 1) * y + vp.at(1, 2) * z + vp.at(1, 3)) / w;
    x0 = std::min(x0, nx);
    x1 = std::max(x1, nx);
    y0 = std::min(y0, ny);
    y1 = std::max(y1, ny);
  }
  auto px = [](float ndc, int n, float pad) {
    return std::clamp(static_cast<int>(std::floor((0.5f * ndc + 0.5f) * n + pad)), 0, n);
  };
  return {px(x0, width, -2), px(y0, height, -2), px(x1, width, 3), px(y1, height, 3)};
}

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
    if (fluid_box_) f.box = screen_box(view, proj, width, height, 2 * s.particle_radius);
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
