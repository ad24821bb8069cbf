#include "render/surface2d_pass.h"

#include <cmath>

namespace rtsph::render {

Surface2dPass::Surface2dPass()
    : splat_({"particle.vert", "surface2d_splat.frag"}),
      shade_({"surface_quad.vert", "surface2d_shade.frag"}),
      field_(GL_RGBA16F, TextureTarget::Depth::None, true) {
  glGenVertexArrays(1, &empty_vao_);
}

Surface2dPass::~Surface2dPass() { glDeleteVertexArrays(1, &empty_vao_); }

int Surface2dPass::draw(const Mat4& view, const Mat4& proj, int width, int height,
                        GLuint target_fbo, bool points, const RenderSettings& s,
                        const std::function<void()>& draw_fluid) {
  const float h = support(s.particle_radius);
  const float spacing = 2.0f * s.particle_radius;
  // A filled square lattice of spacing a sums the kernel to (1/a²)∫w dA = π h² / (4 a²).
  const float norm = 4.0f * spacing * spacing / (3.14159265f * h * h);

  clock_.begin(s.time_passes);
  times_.width = width;
  times_.height = height;
  field_.bind(width, height);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
  glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  if (points) glEnable(GL_PROGRAM_POINT_SIZE);
  splat_.use();
  glUniformMatrix4fv(splat_.loc("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(splat_.loc("u_proj"), 1, GL_FALSE, proj.data());
  glUniform1f(splat_.loc("u_radius"), h);
  glUniform1i(splat_.loc("u_dim"), 2);
  glUniform1i(splat_.loc("u_ortho"), 1);
  glUniform1i(splat_.loc("u_color_mode"), 0);
  glUniform1i(splat_.loc("u_points"), points ? 1 : 0);
  glUniform1f(splat_.loc("u_viewport_h"), static_cast<float>(height));
  glUniform1f(splat_.loc("u_norm"), norm);
  glUniform1f(splat_.loc("u_drop"), 0.6f * s.particle_radius / h);
  draw_fluid();
  clock_.lap(&times_.splat_s);
  if (points) glDisable(GL_PROGRAM_POINT_SIZE);
  glBlendEquation(GL_FUNC_ADD);

  glBindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  glViewport(0, 0, width, height);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  shade_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, field_.color());
  glUniform1i(shade_.loc("u_field"), 0);
  glUniform3f(shade_.loc("u_water"), s.water.r, s.water.g, s.water.b);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindTexture(GL_TEXTURE_2D, 0);
  clock_.lap(&times_.shade_s);
  clock_.end_frame(&times_.frames);
  return 2;
}

}  // namespace rtsph::render
