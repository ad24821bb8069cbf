// Built-in scene names and descriptions. The scenes themselves are scenes/*.json, embedded at
// build time; a test checks every embedded scene has a description here.
#include <algorithm>
#include <iterator>
#include <string_view>
#include <utility>

#include "scene/builtin_data.h"
#include "scene/scene.h"

namespace rtsph {
namespace {

constexpr std::pair<std::string_view, std::string_view> kDescriptions[] = {
    {"dam_break_2d", "Martin & Moyce dam break, 1 m x 2 m column in a 6 m tank (5,000 particles)"},
    {"dam_break_3d", "3D dam break, 0.4 x 0.8 x 0.6 m column in a 1.6 m tank (24,000 particles)"},
    {"double_dam_break_3d", "Two columns collapsing from opposite ends of a 2 m tank (27,000 particles)"},
    {"drop_into_pool_3d", "A falling cube of water splashing into a shallow pool (20,175 particles)"},
    {"hydrostatic_2d", "Water at rest in a 1 m box: pressure should settle to ρgh (5,000 particles)"},
    {"nozzle_obstacle_2d", "A 2.5 m/s jet hitting a fixed circle in a 2 m tank (up to 8,000 particles)"},
    {"nozzle_moving_obstacle_2d", "The nozzle jet with the circle sweeping back and forth (up to 8,000 particles)"},
    {"toy_star_2d", "Toy star (Monaghan & Price 2004): polytropic gas in a linear force, code units, relaxing to ρ ∝ R² − r² (1,976 particles)"},
    {"polytrope_star_3d", "n = 1 polytrope under its own gravity, code units G = 1, relaxing to Lane–Emden (5,616 particles)"},
    {"colliding_stars_3d", "Two n = 1 polytropes on an off-centre collision course, G = 1, tree gravity (4,352 particles)"},
    {"surface_tension_cube_3d", "A 0.15 m cube of water in zero gravity pulls itself into a sphere (surface tension, Akinci et al. 2013; 3,375 particles)"},
    {"validate_poiseuille_2d", "Poiseuille start-up (Morris et al. 1997): 1 mm channel, periodic in x, driven by a body force (160 particles)"},
};

}  // namespace

std::vector<std::pair<std::string, std::string>> builtin_scenes() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& s : scene_detail::embedded_scenes()) {
    const auto it = std::find_if(std::begin(kDescriptions), std::end(kDescriptions),
                                 [&](const auto& d) { return d.first == s.name; });
    out.emplace_back(std::string(s.name), it == std::end(kDescriptions) ? "" : std::string(it->second));
  }
  return out;
}

std::string builtin_scene_text(const std::string& name) {
  for (const auto& s : scene_detail::embedded_scenes())
    if (s.name == name) return std::string(s.text);
  return {};
}

}  // namespace rtsph
