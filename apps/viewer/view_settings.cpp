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
        "--color {}: expected solid, speed, velocity, pressure or density", color));
  if (!render::parse_display_mode(display, &s.display))
    throw std::invalid_argument(
        fmt::format("--display {}: expected fluid, obstacles or all", display));
  if (!render::parse_colormap(colormap, &s.map))
    throw std::invalid_argument(fmt::format("--colormap {}: expected viridis or turbo", colormap));
  return s;
}

}  // namespace rtsph::app
