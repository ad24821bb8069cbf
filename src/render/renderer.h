#pragma once
// Draws particle state with OpenGL 4.3 core; never steps physics. Per frame: the SoA arrays
// are copied into one vertex buffer (upload) and drawn with one instanced call for the fluid
// and one per boundary group, plus a few calls for grid, walls and legend — O(N), no
// per-particle draw calls. 3D particles are ray-cast sphere impostors with true depth and
// Blinn-Phong shading; 2D particles are discs under an orthographic camera. Obstacles are
// drawn as solids from their geometry (SolidPass, one more call). With Style::Surface the
// fluid is drawn as a water surface instead: SurfacePass (3D, screen-space) or Surface2dPass
// (2D, filled contour), from the same vertex buffer (renderer_surface.cpp).
#include <epoxy/gl.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/particles.h"
#include "render/camera.h"
#include "render/colormap.h"
#include "render/render_settings.h"
#include "render/scene_lines.h"
#include "render/shader.h"
#include "render/solids.h"
#include "render/splat_batch.h"
#include "render/surface2d_pass.h"
#include "render/surface_pass.h"

namespace rtsph::render {

/// Where the legend's colour bar lies, in pixels (origin top-left): the top row shows the range
/// maximum, the bottom row the minimum.
struct LegendLayout {
  bool shown = false;
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  float vmin = 0, vmax = 1;
  std::string title;
};

struct DrawStats {
  int draw_calls = 0;
  std::size_t particles_drawn = 0;
  bool points = false;  // particles went out as point sprites (else instanced quads)
};

class Renderer {
 public:
  /// Needs a current OpenGL 4.3 core context; throws std::runtime_error if a shader fails.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// The container box; sets the grid and walls. Without it the particles' bounds are used.
  void set_domain(int dim, const Vec3f& lo, const Vec3f& hi);
  int dim() const { return dim_; }
  Vec3f domain_lo() const { return lo_; }
  Vec3f domain_hi() const { return hi_; }

  /// Copies the arrays to the GPU and computes the value ranges. boundary may be null.
  void upload(const ParticleView& fluid, const BoundaryView* boundary);
  /// The GPU backend's fluid, drawn straight from its buffers (no copy); boundary as upload().
  void use_device(const DeviceParticles& fluid, const BoundaryView* boundary);
  /// The obstacle solids to draw (display modes other than Fluid), in their current poses.
  void upload_solids(const std::vector<SolidShape>& solids) { solids_.set(solids); }
  /// Draws into the bound framebuffer (viewport 0,0,w,h), clearing it first.
  DrawStats draw(const Camera& camera, int width, int height, const RenderSettings& s);

  /// Draws only the legend (on top of what is in the bound framebuffer), e.g. at full
  /// resolution over a scene drawn at reduced resolution with s.legend = false.
  void draw_legend(int width, int height, const RenderSettings& s);

  /// Data range of the last upload for a mode (speed/velocity: [0, max |v|]).
  std::pair<float, float> data_range(ColorMode m) const;
  /// Range the colour map spans under these settings.
  std::pair<float, float> color_range(const RenderSettings& s) const;
  LegendLayout legend_layout(int width, int height, const RenderSettings& s) const;
  std::size_t fluid_count() const { return fluid_n_; }
  std::size_t obstacle_count() const { return obstacle_n_; }
  std::size_t wall_count() const { return wall_n_; }
  std::size_t solid_count() const { return solids_.count(); }
  /// Surface style: CPU time per pass (RenderSettings::time_passes) and the test output switch
  /// (0 shaded, 1 world normals as colour).
  const SurfacePassTimes& surface_times() const {
    return last_surface_2d_ ? surface2d_->times() : surface_->times();
  }
  void set_surface_output(int output) { surface_->set_output(output); }
  /// Points the last 3D surface frame splatted (splat_batch.h; 0 before one was drawn).
  std::size_t splat_count() const { return splats_.size(); }

 private:
  struct OverlayVertex {
    float x, y;
    float r, g, b, a;
    float lut;
  };
  void ensure_lut(ColorMap map);
  void upload_boundary(const BoundaryView* boundary);
  void draw_lines(const std::vector<LineVertex>& v, GLenum mode, const Mat4& mvp);
  void draw_overlay(const std::vector<OverlayVertex>& v, int width, int height);
  /// The legend's overlay triangles (renderer_legend.cpp, with draw_legend and draw_overlay).
  void build_legend(int width, int height, const RenderSettings& s,
                    std::vector<OverlayVertex>* out) const;
  void set_particle_uniforms(const Camera& cam, const Mat4& view, const Mat4& proj, float radius,
                             int color_mode, const Rgb& solid, std::pair<float, float> range);
  void draw_particles(GLuint vao, std::size_t first, std::size_t count, bool points);
  bool use_points(const Camera& cam, int height, const RenderSettings& s) const;
  void draw_container(const Camera& cam, const Mat4& vp, bool faces, bool edges, DrawStats* st);
  /// Brings the splat buffer up to date; false when there is none (the device's fluid).
  bool update_splats(float spacing);
  std::array<int, 4> screen_box(const Mat4& view, const Mat4& proj, int width, int height,
                                float grow) const;
  /// The fluid in the surface style (renderer_surface.cpp); leaves target_fbo bound.
  int draw_surface(const Camera& cam, const Mat4& view, const Mat4& proj, int width, int height,
                   GLuint target_fbo, const RenderSettings& s);

  Program particles_, lines_, overlay_;
  SolidPass solids_;
  std::unique_ptr<SurfacePass> surface_;
  std::unique_ptr<Surface2dPass> surface2d_;
  bool last_surface_2d_ = false;  // the last surface drawn was the 2D one (surface_times)
  GLuint fluid_vao_ = 0, fluid_vbo_ = 0;
  GLuint boundary_vao_ = 0, boundary_vbo_ = 0;
  GLuint line_vao_ = 0, line_vbo_ = 0;
  GLuint overlay_vao_ = 0, overlay_vbo_ = 0;
  GLuint lut_tex_ = 0;
  int lut_map_ = -1;
  std::size_t fluid_n_ = 0, obstacle_n_ = 0, wall_n_ = 0;
  int dim_ = 3;
  bool have_domain_ = false;
  Vec3f lo_{0, 0, 0}, hi_{1, 1, 1};
  bool fluid_box_ = false;  // fluid_lo_/hi_ bound the uploaded fluid (not the device's)
  Vec3f fluid_lo_{0, 0, 0}, fluid_hi_{0, 0, 0};
  // The 3D surface's splats (splat_batch.h), built from a copy of the uploaded positions when
  // the surface is drawn; none for the device's fluid.
  std::vector<float> positions_;  // x, y, z arrays of fluid_n_ each
  SplatBatch splats_;
  bool splats_stale_ = true;
  float splats_spacing_ = 0;
  GLuint splat_vao_ = 0, splat_vbo_ = 0;
  float max_point_size_ = 1;
  float max_speed_ = 0, p_min_ = 0, p_max_ = 0, rho_min_ = 0, rho_max_ = 0;
  std::vector<float> scratch_;
};

/// Framebuffer object with colour and depth renderbuffers for headless rendering.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  void bind() const;
  GLuint fbo() const { return fbo_; }
  int width() const { return w_; }
  int height() const { return h_; }
  /// RGBA8 pixels, top row first.
  std::vector<unsigned char> read_rgba() const;

 private:
  int w_, h_;
  GLuint fbo_ = 0, color_ = 0, depth_ = 0;
};

/// Reads the bound framebuffer's colour (RGBA8, top row first).
std::vector<unsigned char> read_framebuffer(int width, int height);

}  // namespace rtsph::render
