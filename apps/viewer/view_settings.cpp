#include "apps/viewer/view_settings.h"

#include <fmt/format.h>

#include <stdexcept>

namespace rtsph::app {

render::RenderSettings parse_render_options(const std::string& style, const std::string& color,
                                            const std::string& display,
                                            const std::string& colormap) {
  render::RenderSettings s;
  if (!render::parse_style(style, &s.style))
    throw std::invalid_argument(fmt::format("--style {}: expected particles or surface", style));
  if (!render::parse_color_mode(color, &s.color))
    throw std::invalid_argument(fmt::format(
        "--color {}: expected solid, speed, velocity, pressure, density or log_density", color));
  if (!render::parse_display_mode(display, &s.display))
    throw std::invalid_argument(
        fmt::format("--display {}: expected fluid, obstacles or all", display));
  if (!render::parse_colormap(colormap, &s.map))
    throw std::invalid_argument(fmt::format("--colormap {}: expected viridis or turbo", colormap));
  return s;
}

void gas_defaults(const SimSpec& spec, const std::string& style, const std::string& color,
                  render::RenderSettings* s) {
  if (spec.open) s->walls = false;  // open space: no container to draw
  if (spec.method != "gas") return;
  // A gas has no free surface, and its density spans decades: unless asked otherwise (the
  // commands' defaults are "surface" and "solid"/"speed"), particles coloured by log10 ρ.
  if (style == "surface") s->style = render::Style::Particles;
  if (color == "solid" || color == "speed") s->color = render::ColorMode::LogDensity;
}

}  // namespace rtsph::app
