// `rtsph view SCENE` and `rtsph` without arguments: the command line of the interactive viewer
// (GLFW + Dear ImGui; the Viewer class: viewer.h). Without a display, `rtsph` renders a short
// video headless instead.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "apps/run_summary.h"
#include "apps/viewer/render_job.h"
#include "apps/viewer/viewer.h"
#include "render/image_io.h"

namespace rtsph::app {

namespace {

int headless_default() {
  RenderJob job;
  job.scene = "dam_break_3d";
  const bool mp4 = !render::find_on_path("ffmpeg").empty();
  job.out = mp4 ? "rtsph_dam_break_3d.mp4" : "rtsph_dam_break_3d_frames";
  // PBF, the method the viewer's real-time profile runs, at the scene's own spacing (24k
  // particles): 16 s on a 2-core guest, where the scene's WCSPH took 44 s at 7k particles.
  job.sets = {"solver.method=pbf"};
  job.frames = 60;
  job.fps = 30;
  job.size = "960x540";
  job.color = "speed";
  std::fprintf(stderr,
               "rtsph: no display; rendering %s headless instead (2 s at 30 fps, PBF) to %s "
               "(use `rtsph view SCENE` on a display, `rtsph render SCENE --out PATH` for more)\n",
               job.scene.c_str(), mp4 ? job.out.c_str() : (job.out + "/ (ffmpeg not found: PNG frames)").c_str());
  return guarded([&] { return render_scene(job); });
}

}  // namespace

void add_view_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ViewOptions>();
  auto* cmd = app.add_subcommand("view", "Open the interactive viewer (GLFW + ImGui; press H for help)");
  cmd->add_option("scene", o->scene, "Scene file or built-in name (default dam_break_3d)");
  cmd->add_option("--set", o->sets, "Override a scene parameter, e.g. --set fluid.spacing=0.04");
  cmd->add_option("--threads", o->threads, "Solver threads (default: all cores but one)")->check(CLI::Range(0, 1024));
  cmd->add_option("--backend", o->backend, "Where the solver runs: cpu, gpu or auto (the GPU on a hardware OpenGL "
                                           "driver, the CPU on a software one); default: the scene's solver.backend")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  cmd->add_option("--size", o->size, "Window size WxH")->capture_default_str();
  cmd->add_option("--style", o->style, "surface (water surface; 2D: filled contour) or particles")->capture_default_str();
  cmd->add_option("--color", o->color, "solid, speed, velocity, pressure, density or log_density (particle style)")->capture_default_str();
  cmd->add_option("--display", o->display, "fluid, obstacles or all")->capture_default_str();
  cmd->add_option("--colormap", o->colormap, "viridis or turbo")->capture_default_str();
  cmd->add_flag("--paused", o->paused, "Start paused");
  cmd->add_option("--script", o->script, "Scripted input (see apps/viewer/script.h): for tests and demos");
  cmd->add_option("--frames", o->max_frames, "Quit after this many frames")->check(CLI::Range(1L, 1000000000L));
  cmd->add_flag("--report", o->report, "Print fps and simulation cost on exit");
  cmd->add_flag("--accurate", o->accurate, "Run the scene as written, not its real-time profile (scenes with viewer.realtime, e.g. the dam breaks, otherwise run PBF at a spacing this machine steps in real time)");
  cmd->add_option("--realtime-rate", o->realtime_rate,
                  "Fluid particle-substeps per second per solver thread (on the GPU backend: of the GPU) that "
                  "the real-time profile budgets for (default: measured on this machine, or on the GPU, when "
                  "the viewer starts: about half a second on the CPU, a few probes on the GPU)")
      ->check(CLI::Range(1.0, 1e12));
  cmd->add_flag("--time-passes", o->time_passes, "With --report: print the CPU time of each stage of a frame and of each surface pass (glFinish between them; slows drawing a little)");
  cmd->add_option("--render-scale", o->render_scale, "Draw the scene at this fraction of the window resolution (default: adaptive, to keep >= 30 fps)")->check(CLI::Range(0.1, 1.0));
  cmd->callback([o, cmd, &exit_code] {
    o->style_given = cmd->count("--style") > 0;
    o->color_given = cmd->count("--color") > 0;
    exit_code = guarded([&] {
      Viewer v(*o);
      int rc = v.run();
      if (rc == kGlfwInitFailed) {
        std::fprintf(stderr, "rtsph view: cannot open a window: %s\n", glfw_error_text().c_str());
        return 1;
      }
      return rc;
    });
  });
}

int run_default(int argc, char** argv) {
  (void)argc;
  (void)argv;
  if (!have_display()) return headless_default();
  return guarded([&] {
    ViewOptions o;
    Viewer v(o);
    int rc = v.run();
    if (rc == kGlfwInitFailed) {
      std::fprintf(stderr, "rtsph: cannot open a window (%s)\n", glfw_error_text().c_str());
      return headless_default();
    }
    return rc;
  });
}

}  // namespace rtsph::app
