#pragma once
// Options of a headless render (`rtsph render`, and `rtsph` without a display).
#include <string>
#include <vector>

namespace rtsph::app {

struct RenderJob {
  std::string scene;
  std::string out;
  int frames = 0;            // 0 = end_time × fps
  double fps = 30;
  std::string size = "1280x720";
  std::string style = "surface";
  std::string color = "speed";
  std::string display = "obstacles";
  std::string colormap = "viridis";
  std::vector<double> range;
  double range_min = 0, range_max = 0;  // used when max > min
  int threads = 0;
  std::string backend;       // cpu, gpu or auto; empty: the scene's solver.backend, else auto
  std::vector<std::string> sets;
  bool quiet = false;
  bool time_passes = false;  // print the surface passes' CPU time
  int time_draw = 0;         // redraw the last frame this many times and print the draw rate
  // Given on the command line: a scene's own defaults (gas: particles by log density) yield.
  bool style_given = false, color_given = false;

};

/// Runs the job; returns the exit code (throws on bad input, like the other commands).
int render_scene(const RenderJob& job);

}  // namespace rtsph::app
