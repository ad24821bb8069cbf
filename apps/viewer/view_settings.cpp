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

void gas_defaults(const SimSpec& spec, bool style_given, bool color_given,
                  render::RenderSettings* s) {
  if (spec.open) s->walls = false;  // open space: no container to draw
  if (spec.method != "gas") return;
  if (!style_given) s->style = render::Style::Particles;
  if (!color_given) s->color = render::ColorMode::LogDensity;
}

}  // namespace rtsph::app
