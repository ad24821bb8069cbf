#include "render/surface_pass.h"

#include <algorithm>
#include <cmath>

namespace rtsph::render {

namespace {
constexpr int kSmoothRounds = 1;
constexpr float kDepthSplat = 1.5f;  // depth splat radius over the particle radius
void bind_texture(int unit, GLuint tex) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, tex);
}
}  // namespace

SurfacePass::SurfacePass()
    : splat_({"surface_splat.vert", "surface_splat.frag"}),
      smooth_({"surface_quad.vert", "surface_smooth.frag"}),
      normal_({"surface_quad.vert", "surface_normal.frag"}),
      shade_({"surface_quad.vert", "surface_shade.frag"}),
      // Depth is read texel by texel (or interpolated by hand, skipping empty texels);
      // the scene's colour is filtered.
      scene_(GL_RGBA8, TextureTarget::Depth::Texture, true),
      splat_target_(GL_R32F, TextureTarget::Depth::None, false, GL_R32F),
      smooth_a_(GL_R32F, TextureTarget::Depth::None, false),
      smooth_b_(GL_R32F, TextureTarget::Depth::None, false),
      normal_target_(GL_RGBA16F, TextureTarget::Depth::None, true) {
  glGenVertexArrays(1, &empty_vao_);
}

SurfacePass::~SurfacePass() { glDeleteVertexArrays(1, &empty_vao_); }

void SurfacePass::begin_scene(int width, int height, bool time_passes) {
  clock_.begin(time_passes);
  scene_.bind(width, height);
}

int SurfacePass::draw(const SurfaceFrame& f, const RenderSettings& s) {
  lap(&times_.scene_s);
  const float scale = std::clamp(s.surface_scale, 0.1f, 1.0f);
  const int w = std::max(8, static_cast<int>(std::lround(f.width * scale)));
  const int h = std::max(8, static_cast<int>(std::lround(f.height * scale)));
  const float r = s.particle_radius;
  times_.width = w;
  times_.height = h;
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  if (f.points) glEnable(GL_PROGRAM_POINT_SIZE);
  bind_texture(1, scene_.depth());

  // Splats: inverse depth (MAX) and thickness (additive) in one draw, no depth test.
  splat_target_.bind(w, h);
  const GLfloat zero[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, zero);
  glDisable(GL_DEPTH_TEST);
  glEnablei(GL_BLEND, 0);
  glEnablei(GL_BLEND, 1);
  glBlendEquationi(0, GL_MAX);
  glBlendEquationi(1, GL_FUNC_ADD);
  glBlendFunci(0, GL_ONE, GL_ONE);
  glBlendFunci(1, GL_ONE, GL_ONE);
  splat_.use();
  glUniformMatrix4fv(splat_.loc("u_view"), 1, GL_FALSE, f.view.data());
  glUniformMatrix4fv(splat_.loc("u_proj"), 1, GL_FALSE, f.proj.data());
  glUniform1f(splat_.loc("u_radius"), 2 * r);  // the thickness splat, one spacing wide
  glUniform1f(splat_.loc("u_sphere"), kDepthSplat * r);
  glUniform1i(splat_.loc("u_points"), f.points ? 1 : 0);
  glUniform1f(splat_.loc("u_viewport_h"), static_cast<float>(h));
  glUniform1i(splat_.loc("u_scene_depth"), 1);
  glUniform1i(splat_.loc("u_weighted"), f.weighted ? 1 : 0);
  f.draw_fluid();
  glDisablei(GL_BLEND, 0);
  glDisablei(GL_BLEND, 1);
  glBlendEquation(GL_FUNC_ADD);
  if (f.points) glDisable(GL_PROGRAM_POINT_SIZE);
  lap(&times_.splat_s);

  // The fluid's rectangle at the surface resolution (one texel of margin for the rounding), and
  // at the target's for the shading. Outside it the intermediate images are cleared, not drawn:
  // on a software rasteriser a clear costs a fraction of a full-screen pass.
  auto fit = [](int v, int from, int to) {
    return std::clamp(static_cast<int>(std::floor(double(v) * to / from)), 0, to);
  };
  const int bx0 = std::max(fit(f.box[0], f.width, w) - 1, 0);
  const int by0 = std::max(fit(f.box[1], f.height, h) - 1, 0);
  const int bx1 = std::min(fit(f.box[2], f.width, w) + 2, w);
  const int by1 = std::min(fit(f.box[3], f.height, h) + 2, h);
  const bool boxed = bx0 > 0 || by0 > 0 || bx1 < w || by1 < h;
  auto clear_outside = [&] {
    if (!boxed) return;
    glDisable(GL_SCISSOR_TEST);
    glClearBufferfv(GL_COLOR, 0, zero);
    glEnable(GL_SCISSOR_TEST);
    glScissor(bx0, by0, std::max(bx1 - bx0, 0), std::max(by1 - by0, 0));
  };

  // Smoothing: x then y.
  glBindVertexArray(empty_vao_);
  smooth_.use();
  glUniform1i(smooth_.loc("u_depth"), 0);
  glUniform1f(smooth_.loc("u_px_per_m"), f.proj.at(1, 1) * 0.5f * static_cast<float>(h));
  glUniform1f(smooth_.loc("u_radius"), r);
  glUniform1f(smooth_.loc("u_max_px"), 24.0f * scale / 0.5f);
  // Two rounds of x then y: one separable round leaves streaks along the lattice's rows.
  GLuint src = splat_target_.color();
  for (int round = 0; round < kSmoothRounds; ++round) {
    smooth_a_.bind(w, h);
    clear_outside();
    bind_texture(0, src);
    glUniform1i(smooth_.loc("u_inverse"), round == 0 ? 1 : 0);
    glUniform2i(smooth_.loc("u_dir"), 1, 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    smooth_b_.bind(w, h);
    clear_outside();
    bind_texture(0, smooth_a_.color());
    glUniform1i(smooth_.loc("u_inverse"), 0);
    glUniform2i(smooth_.loc("u_dir"), 0, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    src = smooth_b_.color();
  }
  lap(&times_.smooth_s);

  normal_target_.bind(w, h);
  clear_outside();
  normal_.use();
  bind_texture(0, smooth_b_.color());
  glUniform1i(normal_.loc("u_depth"), 0);
  glUniformMatrix4fv(normal_.loc("u_proj"), 1, GL_FALSE, f.proj.data());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  lap(&times_.normal_s);

  // Shading into the target at full resolution, with depth.
  glBindFramebuffer(GL_FRAMEBUFFER, f.target_fbo);
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_SCISSOR_TEST);
  {
    const int x0 = std::clamp(f.box[0] - 1, 0, f.width), y0 = std::clamp(f.box[1] - 1, 0, f.height);
    const int x1 = std::clamp(f.box[2] + 1, 0, f.width), y1 = std::clamp(f.box[3] + 1, 0, f.height);
    glScissor(x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0));
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  shade_.use();
  bind_texture(0, scene_.color());
  bind_texture(1, scene_.depth());
  bind_texture(2, normal_target_.color());
  bind_texture(3, splat_target_.color2());
  glUniform1i(shade_.loc("u_scene"), 0);
  glUniform1i(shade_.loc("u_scene_depth"), 1);
  glUniform1i(shade_.loc("u_normal_depth"), 2);
  glUniform1i(shade_.loc("u_thickness"), 3);
  glUniformMatrix4fv(shade_.loc("u_proj"), 1, GL_FALSE, f.proj.data());
  // The view matrix is a rotation and a translation: its rotation's transpose maps view → world.
  float rot[9];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) rot[c * 3 + k] = f.view.at(c, k);
  glUniformMatrix3fv(shade_.loc("u_view_to_world"), 1, GL_FALSE, rot);
  glUniform3f(shade_.loc("u_water"), s.water.r, s.water.g, s.water.b);
  // Beer–Lambert: deep water tends to the water colour, 2.5/m per unit of −ln(colour).
  auto absorb = [](float c) { return -std::log(std::max(c, 0.02f)) * 2.5f; };
  glUniform3f(shade_.loc("u_absorb"), absorb(s.water.r), absorb(s.water.g), absorb(s.water.b));
  // The sun, high and to the side in the world, in view space: the view's rotation applied.
  const Vec3f sun_world = normalize(Vec3f{0.4f, 1.0f, 0.3f});
  Vec3f sun;
  sun.x = f.view.at(0, 0) * sun_world.x + f.view.at(0, 1) * sun_world.y + f.view.at(0, 2) * sun_world.z;
  sun.y = f.view.at(1, 0) * sun_world.x + f.view.at(1, 1) * sun_world.y + f.view.at(1, 2) * sun_world.z;
  sun.z = f.view.at(2, 0) * sun_world.x + f.view.at(2, 1) * sun_world.y + f.view.at(2, 2) * sun_world.z;
  glUniform3f(shade_.loc("u_sun"), sun.x, sun.y, sun.z);
  glUniform1f(shade_.loc("u_radius"), r);
  glUniform1i(shade_.loc("u_output"), output_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_SCISSOR_TEST);
  glDepthFunc(GL_LESS);
  bind_texture(3, 0);
  bind_texture(2, 0);
  bind_texture(1, 0);
  glActiveTexture(GL_TEXTURE0);
  lap(&times_.shade_s);
  clock_.end_frame(&times_.frames);
  return 3 + 2 * kSmoothRounds;
}

}  // namespace rtsph::render
