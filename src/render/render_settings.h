#pragma once
// How a frame is drawn: the settings the viewer, `rtsph render` and the Python module fill, and
// the names their options use.
#include <string_view>

#include "render/colormap.h"

namespace rtsph::render {

/// LogDensity: log₁₀ ρ, for a self-gravitating gas whose density spans decades.
enum class ColorMode { Solid, Speed, Velocity, Pressure, Density, LogDensity };
/// Fluid: fluid only. FluidObstacles: fluid and obstacle solids. All: also every boundary
/// particle (walls and the obstacles' Akinci samples), in the wall particle colour.
enum class DisplayMode { Fluid, FluidObstacles, All };
/// How particles are rasterised. Points: one point sprite per particle (fastest on software
/// rasterisers, limited to the driver's largest point size); Quads: one instanced quad per
/// particle (any size); Auto: points unless a particle could exceed the point size limit.
enum class ParticlePrimitive { Auto, Points, Quads };
/// How the fluid is drawn. Particles: one shaded ball (3D) or disc (2D) per particle, coloured
/// by the colour mode. Surface: 3D, a screen-space liquid surface (surface_pass.h); 2D, the
/// filled iso-contour of a splatted density field (surface2d_pass.h). The colour mode applies
/// to the particle style only.
enum class Style { Particles, Surface };

std::string_view color_mode_name(ColorMode m);    // "solid", "speed", ...
bool parse_color_mode(std::string_view s, ColorMode* out);
std::string_view display_mode_name(DisplayMode m);  // "fluid", "obstacles", "all"
bool parse_display_mode(std::string_view s, DisplayMode* out);
std::string_view style_name(Style s);  // "particles", "surface"
bool parse_style(std::string_view s, Style* out);

struct RenderSettings {
  /// Particles by default here (tests and library users draw what they upload); the apps
  /// (`rtsph view`, `rtsph render`, the no-argument run) default to Surface.
  Style style = Style::Particles;
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
  /// Surface style, 3D: fraction of the frame's resolution the fluid passes (depth, smoothing,
  /// thickness) run at; the shading pass runs at full resolution.
  float surface_scale = 0.5f;
  /// Surface style, 3D: interior particles of an uploaded fluid are splatted as merged cubes
  /// (splat_batch.h: fewer points, the same thickness integral); the GPU backend's fluid, never
  /// read back, is always splatted particle by particle, as it is with this off.
  bool merge_interior = true;
  /// Times each surface pass on the CPU with glFinish between passes (Renderer::pass_times);
  /// costs the pipelining, so off except for measurements.
  bool time_passes = false;
};

}  // namespace rtsph::render
