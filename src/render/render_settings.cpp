#include "render/render_settings.h"

namespace rtsph::render {

std::string_view color_mode_name(ColorMode m) {
  switch (m) {
    case ColorMode::Solid: return "solid";
    case ColorMode::Speed: return "speed";
    case ColorMode::Velocity: return "velocity";
    case ColorMode::Pressure: return "pressure";
    case ColorMode::Density: return "density";
    case ColorMode::LogDensity: return "log_density";
  }
  return "solid";
}

bool parse_color_mode(std::string_view s, ColorMode* out) {
  for (ColorMode m : {ColorMode::Solid, ColorMode::Speed, ColorMode::Velocity, ColorMode::Pressure,
                      ColorMode::Density, ColorMode::LogDensity})
    if (s == color_mode_name(m)) {
      *out = m;
      return true;
    }
  return false;
}

std::string_view display_mode_name(DisplayMode m) {
  switch (m) {
    case DisplayMode::Fluid: return "fluid";
    case DisplayMode::FluidObstacles: return "obstacles";
    case DisplayMode::All: return "all";
  }
  return "fluid";
}

bool parse_display_mode(std::string_view s, DisplayMode* out) {
  for (DisplayMode m : {DisplayMode::Fluid, DisplayMode::FluidObstacles, DisplayMode::All})
    if (s == display_mode_name(m)) {
      *out = m;
      return true;
    }
  return false;
}

std::string_view style_name(Style s) { return s == Style::Surface ? "surface" : "particles"; }

bool parse_style(std::string_view s, Style* out) {
  for (Style v : {Style::Particles, Style::Surface})
    if (s == style_name(v)) {
      *out = v;
      return true;
    }
  return false;
}

}  // namespace rtsph::render
