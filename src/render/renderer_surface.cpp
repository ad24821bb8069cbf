// Renderer's surface style: hands the fluid's vertex buffer to the 3D screen-space surface
// (surface_pass.h) or the 2D metaball pass (surface2d_pass.h), then restores the state that
// Renderer::draw continues with.
#include "render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rtsph::render {

bool Renderer::update_splats(float spacing) {
  const std::size_t n = fluid_n_;
  if (n == 0 || positions_.size() != 3 * n) return false;
  if (splats_stale_ || spacing != splats_spacing_) {
    splats_.build(positions_.data(), positions_.data() + n, positions_.data() + 2 * n, n, spacing);
    const std::size_t m = splats_.size();
    glBindVertexArray(splat_vao_);
    glBindBuffer(GL_ARRAY_BUFFER, splat_vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(splats_.data().size() * sizeof(float)),
                 splats_.data().data(), GL_STREAM_DRAW);
    for (GLuint i = 0; i < 4; ++i) {
      glVertexAttribPointer(i, 1, GL_FLOAT, GL_FALSE, 0,
                            reinterpret_cast<void*>(i * m * sizeof(float)));
      glEnableVertexAttribArray(i);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    splats_stale_ = false;
    splats_spacing_ = spacing;
  }
  return true;
}

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
  if (three) splat.particle_radius *= 2;  // a merged cube's splat is twice as wide
  const bool points = use_points(cam, height, splat);
  // The batch is built inside the splat pass's draw, so that its CPU time counts there.
  const bool batched =
      three && s.merge_interior && fluid_n_ > 0 && positions_.size() == 3 * fluid_n_;
  const float spacing = 2 * s.particle_radius;
  auto draw_fluid = [this, points, batched, spacing] {
    if (batched && update_splats(spacing)) draw_particles(splat_vao_, 0, splats_.size(), points);
    else draw_particles(fluid_vao_, 0, fluid_n_, points);
  };
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
    f.weighted = batched;
    if (fluid_box_) f.box = screen_box(view, proj, width, height, 2 * s.particle_radius);
    calls = surface_->draw(f, s);
    last_surface_2d_ = false;
  } else {
    last_surface_2d_ = true;
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
