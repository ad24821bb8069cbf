// The Renderer (renderer.h): its programs and buffers, the particle upload with its value
// ranges, and the scene pass (draw). The other passes have their own files: the surface style
// (renderer_surface.cpp), the GPU backend's buffers (renderer_device.cpp) and the legend
// (renderer_legend.cpp).
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace rtsph::render {

namespace {

constexpr int kLutSize = 256;

}  // namespace

Renderer::Renderer()
    : particles_({"particle.vert", "particle.frag"}),
      lines_({"line.vert", "line.frag"}),
      overlay_({"overlay.vert", "overlay.frag"}),
      surface_(std::make_unique<SurfacePass>()),
      surface2d_(std::make_unique<Surface2dPass>()) {
  glGenVertexArrays(1, &fluid_vao_);
  glGenVertexArrays(1, &boundary_vao_);
  glGenVertexArrays(1, &line_vao_);
  glGenVertexArrays(1, &overlay_vao_);
  glGenVertexArrays(1, &splat_vao_);
  glGenBuffers(1, &splat_vbo_);
  glGenBuffers(1, &fluid_vbo_);
  glGenBuffers(1, &boundary_vbo_);
  glGenBuffers(1, &line_vbo_);
  glGenBuffers(1, &overlay_vbo_);
  glGenTextures(1, &lut_tex_);

  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<void*>(offsetof(LineVertex, r)));

  glBindVertexArray(overlay_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, overlay_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, r)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                        reinterpret_cast<void*>(offsetof(OverlayVertex, lut)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  ensure_lut(ColorMap::Viridis);
  GLfloat range[2] = {1, 1};
  glGetFloatv(GL_POINT_SIZE_RANGE, range);
  max_point_size_ = range[1];
}

Renderer::~Renderer() {
  GLuint vaos[] = {fluid_vao_, boundary_vao_, line_vao_, overlay_vao_};
  GLuint vbos[] = {fluid_vbo_, boundary_vbo_, line_vbo_, overlay_vbo_};
  glDeleteVertexArrays(4, vaos);
  glDeleteBuffers(4, vbos);
  glDeleteVertexArrays(1, &splat_vao_);
  glDeleteBuffers(1, &splat_vbo_);
  glDeleteTextures(1, &lut_tex_);
}

void Renderer::set_domain(int dim, const Vec3f& lo, const Vec3f& hi) {
  dim_ = dim;
  lo_ = lo;
  hi_ = hi;
  if (dim == 2) lo_.z = hi_.z = 0;
  have_domain_ = true;
}

void Renderer::ensure_lut(ColorMap map) {
  if (lut_map_ == static_cast<int>(map)) return;
  auto data = colormap_lut(map, kLutSize);
  glBindTexture(GL_TEXTURE_2D, lut_tex_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kLutSize, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, data.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  lut_map_ = static_cast<int>(map);
}

void Renderer::upload(const ParticleView& f, const BoundaryView* b) {
  if (!have_domain_) dim_ = f.dim;
  const std::size_t n = f.x[0] && f.x[1] ? f.count : 0;
  fluid_n_ = n;

  // Value ranges for the legend and auto colouring: one pass over the arrays.
  float vmax2 = 0;
  float pmin = std::numeric_limits<float>::max(), pmax = std::numeric_limits<float>::lowest();
  float rmin = pmin, rmax = pmax;
  const int vd = f.v[2] && f.dim == 3 ? 3 : 2;
  if (f.v[0] && f.v[1]) {
    for (std::size_t i = 0; i < n; ++i) {
      float s2 = f.v[0][i] * f.v[0][i] + f.v[1][i] * f.v[1][i];
      if (vd == 3) s2 += f.v[2][i] * f.v[2][i];
      vmax2 = std::max(vmax2, s2);
    }
  }
  if (f.pressure)
    for (std::size_t i = 0; i < n; ++i) {
      pmin = std::min(pmin, f.pressure[i]);
      pmax = std::max(pmax, f.pressure[i]);
    }
  if (f.density)
    for (std::size_t i = 0; i < n; ++i) {
      rmin = std::min(rmin, f.density[i]);
      rmax = std::max(rmax, f.density[i]);
    }
  max_speed_ = std::sqrt(vmax2);
  if (!f.pressure || n == 0) pmin = pmax = 0;
  if (!f.density || n == 0) rmin = rmax = 0;
  p_min_ = pmin;
  p_max_ = pmax;
  rho_min_ = rmin;
  rho_max_ = rmax;

  // Fluid: the present arrays packed one after another in one buffer (orphaned each frame).
  const float* arrays[8] = {f.x[0], f.x[1], f.dim == 3 ? f.x[2] : nullptr,
                            f.v[0], f.v[1], f.dim == 3 ? f.v[2] : nullptr,
                            f.density, f.pressure};
  int present = 0;
  for (const float* a : arrays) present += a ? 1 : 0;
  const GLsizeiptr bytes = static_cast<GLsizeiptr>(n * sizeof(float));
  glBindVertexArray(fluid_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, fluid_vbo_);
  glBufferData(GL_ARRAY_BUFFER, std::max<GLsizeiptr>(bytes * present, 4), nullptr, GL_STREAM_DRAW);
  GLintptr offset = 0;
  for (GLuint i = 0; i < 8; ++i) {
    if (arrays[i] && n > 0) {
      glBufferSubData(GL_ARRAY_BUFFER, offset, bytes, arrays[i]);
      glVertexAttribPointer(i, 1, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<void*>(offset));
      glVertexAttribDivisor(i, 1);
      glEnableVertexAttribArray(i);
      offset += bytes;
    } else {
      glDisableVertexAttribArray(i);
    }
  }

  upload_boundary(b);

  // The fluid's bounds: the surface passes work only where its projection falls.
  fluid_box_ = n > 0;
  if (n > 0) {
    Vec3f lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), 0};
    Vec3f hi{std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest(), 0};
    for (std::size_t i = 0; i < n; ++i) {
      lo.x = std::min(lo.x, f.x[0][i]); hi.x = std::max(hi.x, f.x[0][i]);
      lo.y = std::min(lo.y, f.x[1][i]); hi.y = std::max(hi.y, f.x[1][i]);
    }
    if (f.dim == 3 && f.x[2]) {
      lo.z = std::numeric_limits<float>::max();
      hi.z = std::numeric_limits<float>::lowest();
      for (std::size_t i = 0; i < n; ++i) {
        lo.z = std::min(lo.z, f.x[2][i]);
        hi.z = std::max(hi.z, f.x[2][i]);
      }
    }
    fluid_lo_ = lo;
    fluid_hi_ = hi;
    if (f.dim == 3 && f.x[2]) {
      positions_.resize(3 * n);
      for (int k = 0; k < 3; ++k) std::memcpy(positions_.data() + k * n, f.x[k], n * sizeof(float));
      splats_stale_ = true;
    } else {
      positions_.clear();
    }
    // Positions that are not finite (a blown-up run) leave no usable box.
    for (float v : {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}) fluid_box_ = fluid_box_ && std::isfinite(v);
    if (!have_domain_) {
      lo_ = lo;
      hi_ = hi;
    }
  }
}

void Renderer::upload_boundary(const BoundaryView* b) {
  // Boundary: obstacles first, then walls, so each group is one contiguous instance range.
  obstacle_n_ = wall_n_ = 0;
  glBindVertexArray(boundary_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, boundary_vbo_);
  const std::size_t nb = b && b->x[0] && b->x[1] && b->owner ? b->count : 0;
  if (nb > 0) {
    const int bd = b->dim == 3 && b->x[2] ? 3 : 2;
    scratch_.resize(nb * 3);
    std::size_t obst = 0;
    for (std::size_t i = 0; i < nb; ++i) obst += b->owner[i] >= 0 ? 1 : 0;
    std::size_t io = 0, iw = obst;
    for (std::size_t i = 0; i < nb; ++i) {
      std::size_t j = b->owner[i] >= 0 ? io++ : iw++;
      scratch_[j] = b->x[0][i];
      scratch_[nb + j] = b->x[1][i];
      scratch_[2 * nb + j] = bd == 3 ? b->x[2][i] : 0.0f;
    }
    obstacle_n_ = obst;
    wall_n_ = nb - obst;
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(scratch_.size() * sizeof(float)),
                 scratch_.data(), GL_STREAM_DRAW);
    for (GLuint i = 0; i < 3; ++i) {
      glVertexAttribPointer(i, 1, GL_FLOAT, GL_FALSE, 0,
                            reinterpret_cast<void*>(i * nb * sizeof(float)));
      glVertexAttribDivisor(i, 1);
      glEnableVertexAttribArray(i);
    }
  }
  for (GLuint i = nb > 0 ? 3 : 0; i < 8; ++i) glDisableVertexAttribArray(i);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

std::pair<float, float> Renderer::data_range(ColorMode m) const {
  switch (m) {
    case ColorMode::Speed:
    case ColorMode::Velocity: return {0.0f, max_speed_};
    case ColorMode::Pressure: return {p_min_, p_max_};
    case ColorMode::Density: return {rho_min_, rho_max_};
    case ColorMode::LogDensity:  // the shader's log10 of ρ, floored as it floors it
      return {std::log10(std::max(rho_min_, 1e-30f)), std::log10(std::max(rho_max_, 1e-30f))};
    case ColorMode::Solid: break;
  }
  return {0.0f, 1.0f};
}

std::pair<float, float> Renderer::color_range(const RenderSettings& s) const {
  auto r = s.auto_range ? data_range(s.color) : std::pair<float, float>{s.range_min, s.range_max};
  if (!(r.second > r.first)) {
    // A constant field. Zero (fluid at rest): [0, 1], so it shows as the low end of the map;
    // otherwise a small interval centred on the value.
    if (r.first == 0) return {0.0f, 1.0f};
    float pad = std::fabs(r.first) * 1e-3f;
    r = {r.first - pad, r.first + pad};
  }
  return r;
}

void Renderer::draw_lines(const std::vector<LineVertex>& v, GLenum mode, const Mat4& mvp) {
  if (v.empty()) return;
  lines_.use();
  glUniformMatrix4fv(lines_.loc("u_mvp"), 1, GL_FALSE, mvp.data());
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(LineVertex)), v.data(),
               GL_STREAM_DRAW);
  glDrawArrays(mode, 0, static_cast<GLsizei>(v.size()));
}

bool Renderer::use_points(const Camera& cam, int height, const RenderSettings& s) const {
  if (s.primitive != ParticlePrimitive::Auto) return s.primitive == ParticlePrimitive::Points;
  // Largest on-screen diameter any particle can have: at the nearest possible depth, with the
  // off-axis stretch allowance of the shader (at most 4x, usually < 1.5x).
  const float r = std::max(s.particle_radius, s.boundary_radius);
  const float f = 1.0f / std::tan(0.5f * cam.fovy);
  float px;
  if (cam.dim == 2) {
    px = 2 * r / cam.world_per_pixel(height);
  } else {
    const float nearest = std::max(cam.znear(), cam.distance - cam.scene_radius);
    px = 2 * r * 1.6f * f * static_cast<float>(height) * 0.5f / nearest;
  }
  return px < 0.9f * max_point_size_;
}

void Renderer::draw_particles(GLuint vao, std::size_t first, std::size_t count, bool points) {
  glBindVertexArray(vao);
  for (GLuint i = 0; i < 8; ++i) glVertexAttribDivisor(i, points ? 0 : 1);
  if (points)
    glDrawArrays(GL_POINTS, static_cast<GLint>(first), static_cast<GLsizei>(count));
  else
    glDrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count),
                                      static_cast<GLuint>(first));
}

void Renderer::set_particle_uniforms(const Camera& cam, const Mat4& view, const Mat4& proj,
                                     float radius, int color_mode, const Rgb& solid,
                                     std::pair<float, float> range) {
  glUniformMatrix4fv(particles_.loc("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(particles_.loc("u_proj"), 1, GL_FALSE, proj.data());
  glUniform1f(particles_.loc("u_radius"), radius);
  glUniform1i(particles_.loc("u_dim"), dim_);
  glUniform1i(particles_.loc("u_ortho"), cam.dim == 2 ? 1 : 0);
  glUniform1i(particles_.loc("u_color_mode"), color_mode);
  glUniform2f(particles_.loc("u_range"), range.first, range.second);
  glUniform3f(particles_.loc("u_solid"), solid.r, solid.g, solid.b);
  glUniform1i(particles_.loc("u_lut"), 0);
}

void Renderer::draw_container(const Camera& cam, const Mat4& vp, bool faces, bool edges,
                              DrawStats* st) {
  // Translucent faces on the far side of the box (those the eye sees from the inside) and the
  // twelve edges, depth-tested against the particles, not writing depth.
  std::vector<LineVertex> f, e;
  build_walls_3d(cam.eye(), lo_, hi_, &f, &e);
  glEnable(GL_BLEND);
  glDepthMask(GL_FALSE);
  if (faces) draw_lines(f, GL_TRIANGLES, vp);
  if (edges) draw_lines(e, GL_LINES, vp);
  glDepthMask(GL_TRUE);
  st->draw_calls += int(faces) + int(edges);
}

DrawStats Renderer::draw(const Camera& cam, int width, int height, const RenderSettings& s) {
  DrawStats st;
  width = std::max(width, 1);
  height = std::max(height, 1);
  const bool three = dim_ == 3;
  // Surface style, 3D: the opaque scene goes to a texture that the water refracts.
  GLint target_fbo = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_fbo);
  const bool surface = s.style == Style::Surface && fluid_n_ > 0;
  if (surface && three) surface_->begin_scene(width, height, s.time_passes);
  glViewport(0, 0, width, height);
  glClearColor(s.background.r, s.background.g, s.background.b, 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ensure_lut(s.map);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, lut_tex_);
  for (GLuint i = 0; i < 8; ++i) glVertexAttrib4f(i, 0, 0, 0, 1);

  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const Mat4 view = cam.view(), proj = cam.projection(aspect), vp = proj * view;
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_BLEND);
  // Destination alpha stays 1 so that saved frames are opaque.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  if (three) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  const Vec3f size = hi_ - lo_;
  const float extent = std::max({size.x, size.y, three ? size.z : 0.0f, 1e-3f});

  // What the fluid lies in front of: the ground grid (3D: the floor plane, 2D: behind the
  // particles), in 2D the walls, the obstacle solids; with the 3D surface also the container's
  // far faces, which lie behind the water and are part of the refracted scene.
  std::vector<LineVertex> lv;
  if (s.grid) build_grid_lines(dim_, lo_, hi_, &lv);
  auto draw_opaque = [&] {
    glEnable(GL_BLEND);
    if (!lv.empty()) {
      glDepthMask(GL_FALSE);
      draw_lines(lv, GL_LINES, vp);
      glDepthMask(GL_TRUE);
      ++st.draw_calls;
    }
    if (!three && s.walls) {
      // 2D walls: a translucent band around the domain.
      std::vector<LineVertex> tri;
      build_walls_2d(lo_, hi_, std::max(2.0f * s.particle_radius, 0.01f * extent), &tri);
      draw_lines(tri, GL_TRIANGLES, vp);
      ++st.draw_calls;
    }
    glDisable(GL_BLEND);  // solids and particles are opaque; blending costs a read per fragment
    // Obstacle solids before the particles: in 2D (no depth test) the fluid lies on top of
    // them; in 3D both write their true depth, so the order does not matter.
    if (s.display != DisplayMode::Fluid && solids_.draw(dim_, view, proj, cam.dim == 2, s.obstacle))
      ++st.draw_calls;
    if (surface && three && s.walls) draw_container(cam, vp, true, false, &st);
  };
  draw_opaque();
  if (surface && three) {
    // The opaque scene went to the surface's texture (what the water refracts); drawn again
    // into the target, the shading pass needs to touch only the pixels around the water.
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target_fbo));
    glViewport(0, 0, width, height);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_opaque();
  }
  if (surface) {
    st.draw_calls += draw_surface(cam, view, proj, width, height, GLuint(target_fbo), s);
    st.particles_drawn += fluid_n_;
  }

  // Particles: one draw for the fluid, one for the boundary particles (display All).
  particles_.use();
  const float br = s.boundary_radius > 0 ? s.boundary_radius : s.particle_radius;
  const bool points = use_points(cam, height, s);
  st.points = points;
  if (points) glEnable(GL_PROGRAM_POINT_SIZE);
  glUniform1i(particles_.loc("u_points"), points ? 1 : 0);
  glUniform1f(particles_.loc("u_viewport_h"), static_cast<float>(height));
  glUniform4f(particles_.loc("u_viewport"), 0, 0, static_cast<float>(width), static_cast<float>(height));
  if (fluid_n_ > 0 && !surface) {
    set_particle_uniforms(cam, view, proj, s.particle_radius, static_cast<int>(s.color), s.water,
                          color_range(s));
    draw_particles(fluid_vao_, 0, fluid_n_, points);
    ++st.draw_calls;
    st.particles_drawn += fluid_n_;
  }
  // Obstacle samples and walls are one contiguous range (obstacles first, see upload()).
  if (s.display == DisplayMode::All && obstacle_n_ + wall_n_ > 0) {
    set_particle_uniforms(cam, view, proj, br, 0, s.wall_particles, {0.0f, 1.0f});
    draw_particles(boundary_vao_, 0, obstacle_n_ + wall_n_, points);
    ++st.draw_calls;
    st.particles_drawn += obstacle_n_ + wall_n_;
  }
  if (points) glDisable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_BLEND);

  if (three && s.walls) draw_container(cam, vp, !surface, true, &st);

  // Legend, in pixels on top of everything.
  glDisable(GL_DEPTH_TEST);
  std::vector<OverlayVertex> ov;
  build_legend(width, height, s, &ov);
  if (!ov.empty()) {
    draw_overlay(ov, width, height);
    ++st.draw_calls;
  }

  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  return st;
}

}  // namespace rtsph::render
