#pragma once
// What `rtsph view` and `rtsph render` share about how a frame looks: the option spellings
// parsed into RenderSettings, and the viewer's help text.
#include <string>

#include "render/render_settings.h"
#include "solvers/spec.h"

namespace rtsph::app {

/// Settings from the options' spellings; throws std::invalid_argument naming the bad option.
render::RenderSettings parse_render_options(const std::string& style, const std::string& color,
                                            const std::string& display,
                                            const std::string& colormap);

/// Scene-dependent defaults: no container drawn in open space; for the gas method, particles
/// coloured by log10 ρ, since a gas has no free surface and its density spans decades, unless
/// --style or --color was given on the command line.
void gas_defaults(const SimSpec& spec, bool style_given, bool color_given,
                  render::RenderSettings* s);

inline constexpr const char* kViewerHelp =
    "Mouse\n"
    "  left drag            orbit (2D: pan)\n"
    "  middle drag          pan\n"
    "  wheel                zoom\n"
    "  Shift + left drag    brush: push fluid away\n"
    "  Shift + right drag   brush: pull fluid in\n"
    "  Ctrl + left drag     move the nearest obstacle\n"
    "Keys\n"
    "  Space   pause / resume        N   single step\n"
    "  R       reset                 G   gravity on / off\n"
    "  1       fullscreen            TAB display: fluid / +obstacles / all\n"
    "  F       style: water surface / particles\n"
    "  0 5 6 7 8 9 colour (particle style): log density / density / pressure / velocity / speed / solid\n"
    "  arrows  rotate the camera (2D: pan)\n"
    "  q/w a/s z/x   move the selected obstacle along -/+ x, y, z\n"
    "  F12     screenshot (PNG)      V   start / stop video recording\n"
    "  H       this help             Esc quit";

}  // namespace rtsph::app
