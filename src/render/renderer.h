#pragma once
// Draws particle state with OpenGL 4.3 core; never steps physics. Per frame: the SoA arrays
// are copied into one vertex buffer (upload) and drawn with one instanced call for the fluid
// and one per boundary group, plus a few calls for grid, walls and legend — O(N), no
// per-particle draw calls. 3D particles are ray-cast sphere impostors with true depth and
// Blinn-Phong shading; 2D particles are discs under an orthographic camera. Obstacles are
// drawn as solids from their geometry (SolidPass, one more call).
#include <epoxy/gl.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/particles.h"
#include "render/camera.h"
#include "render/colormap.h"
#include "render/shader.h"
#include "render/solids.h"

namespace rtsph::render {

enum class ColorMode { Solid, Speed, Velocity, Pressure, Density };
/// Fluid: fluid only. FluidObstacles: fluid and obstacle solids. All: also every boundary
/// particle (walls and the obstacles' Akinci samples), in the wall particle colour.
enum class DisplayMode { Fluid, FluidObstacles, All };
/// How particles are rasterised. Points: one point sprite per particle (fastest on software
/// rasterisers, limited to the driver's largest point size); Quads: one instanced quad per
/// particle (any size); Auto: points unless a particle could exceed the point size limit.
enum class ParticlePrimitive { Auto, Points, Quads };

std::string_view color_mode_name(ColorMode m);    // "solid", "speed", ...
bool parse_color_mode(std::string_view s, ColorMode* out);
std::string_view display_mode_name(DisplayMode m);  // "fluid", "obstacles", "all"
bool parse_display_mode(std::string_view s, DisplayMode* out);

struct RenderSettings {
  ColorMode color = ColorMode::Solid;
  ColorMap map = ColorMap::Viridis;
  DisplayMode display = DisplayMode::FluidObstacles;
  bool auto_range = true;       // else [range_min, range_max]
  float range_min = 0, range_max = 1;
  float particle_radius = 0.01f;  // m (drawn radius; half the spacing looks like a continuum)
  float boundary_radius = 0;      // m, boundary particles (display All); 0 = particle_radius
  bool legend = true;
  bool grid = true;
  bool walls = true;              // translucent container faces and outline
  Rgb water{0.13f, 0.42f, 0.85f};
  Rgb background{0.10f, 0.11f, 0.13f};
  Rgb obstacle{0.62f, 0.62f, 0.60f};  // solids
  Rgb wall_particles{0.45f, 0.47f, 0.52f};
  float ui_scale = 0;             // legend text scale; 0 = from the image height
  ParticlePrimitive primitive = ParticlePrimitive::Auto;
};

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

 private:
  struct LineVertex {
    float x, y, z;
    float r, g, b, a;
  };
  struct OverlayVertex {
    float x, y;
    float r, g, b, a;
    float lut;
  };
  void ensure_lut(ColorMap map);
  void draw_lines(const std::vector<LineVertex>& v, GLenum mode, const Mat4& mvp);
  void draw_overlay(const std::vector<OverlayVertex>& v, int width, int height);
  void build_legend(int width, int height, const RenderSettings& s,
                    std::vector<OverlayVertex>* out) const;
  void set_particle_uniforms(const Camera& cam, const Mat4& view, const Mat4& proj, float radius,
                             int color_mode, const Rgb& solid, std::pair<float, float> range);
  void draw_particles(GLuint vao, std::size_t first, std::size_t count, bool points);
  bool use_points(const Camera& cam, int height, const RenderSettings& s) const;

  Program particles_, lines_, overlay_;
  SolidPass solids_;
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
