// `rtsph render SCENE --out PATH`: steps the simulation and renders frames headless through
// EGL (no display needed). PATH.png: the last frame; PATH.mp4: a video through ffmpeg;
// anything else: a directory of frame_000000.png, ….
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/progress.h"
#include "apps/run_summary.h"
#include "apps/sim_backend.h"
#include "apps/viewer/render_job.h"
#include "apps/viewer/scene_view.h"
#include "apps/viewer/view_settings.h"
#include "gpu/backend.h"
#include "gpu/gl_compute.h"
#include "render/gl_context.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

namespace rtsph::app {

bool parse_size(const std::string& text, int* w, int* h) {
  int a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X'))
    return false;
  if (a < 16 || b < 16 || a > 8192 || b > 8192) return false;
  *w = a;
  *h = b;
  return true;
}

void require_size(const std::string& text, int* w, int* h) {
  if (!parse_size(text, w, h))
    throw std::invalid_argument(fmt::format("--size {}: expected WxH, each from 16 to 8192, e.g. 1280x720", text));
}

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == suffix;
}
void print_pass_times(const render::SurfacePassTimes& t, std::size_t splats) {
  const double n = double(std::max(t.frames, 1L));
  if (t.dimension == 2) {
    std::fprintf(stderr, "rtsph render: 2D surface passes over %ld frames, ms/frame: splat %.2f, shade %.2f (at %dx%d)\n",
                 t.frames, 1e3 * t.splat_s / n, 1e3 * t.shade_s / n, t.width, t.height);
    return;
  }
  std::fprintf(stderr, "rtsph render: surface passes over %ld frames, ms/frame: scene %.2f, splat %.2f, smooth %.2f, normal %.2f, shade %.2f (last frame: %zu splats)\n",
               t.frames, 1e3 * t.scene_s / n, 1e3 * t.splat_s / n, 1e3 * t.smooth_s / n,
               1e3 * t.normal_s / n, 1e3 * t.shade_s / n, splats);
}
// `--time-draw N`: the last frame drawn N more times from what the renderer holds (the GPU
// backend's own buffers, or the last upload), each draw bounded by glFinish, no pixels read
// back and no step taken: the drawing's own rate at this image size, which bounds the viewer's.
void time_draws(render::Renderer& renderer, const render::OffscreenTarget& target, const render::Camera& cam,
                int width, int height, const render::RenderSettings& settings, int n) {
  target.bind();
  renderer.draw(cam, width, height, settings);  // warm: programs, buffers, textures
  glFinish();
  std::vector<double> ms(std::size_t(n), 0.0);
  for (double& m : ms) {
    target.bind();
    const auto a = std::chrono::steady_clock::now();
    renderer.draw(cam, width, height, settings);
    glFinish();
    m = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
  }
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  std::fprintf(stderr, "rtsph render: the last frame drawn %d times at %dx%d: median %.3f ms (%.1f frames/s), "
               "fastest %.3f ms, slowest %.3f ms\n", n, width, height, median, 1000.0 / median, ms.front(), ms.back());
}

}  // namespace

int render_scene(const RenderJob& job) {
  SimSpec spec = load_scene(job.scene);
  for (const auto& s : job.sets) apply_override(spec, s);

  int width = 0, height = 0;
  require_size(job.size, &width, &height);
  render::RenderSettings settings = parse_render_options(job.style, job.color, job.display, job.colormap);
  settings.time_passes = job.time_passes;
  // Offline frames have no frame-rate budget: the fluid passes run at the image's resolution
  // (at the viewer's half, a 640x360 image drew spray as squares of 2x2-texel blocks).
  settings.surface_scale = 1.0f;
  gas_defaults(spec, job.style_given, job.color_given, &settings);
  if (job.range_max > job.range_min) {
    settings.auto_range = false;
    settings.range_min = float(job.range_min);
    settings.range_max = float(job.range_max);
  }
  if (!(job.fps > 0)) throw std::invalid_argument("--fps must be positive");
  // A name with another picture or video extension would become a directory of PNGs: refused.
  {
    std::string ext = std::filesystem::path(job.out).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* other : {".jpg", ".jpeg", ".gif", ".bmp", ".tif", ".tiff", ".webp", ".webm", ".mkv",
                              ".mov", ".avi", ".m4v"})
      if (ext == other)
        throw std::invalid_argument(fmt::format("--out {}: {} is not written; use FILE.png, FILE.mp4 or a directory",
                                                job.out, ext));
  }
  const int frames = job.frames > 0 ? job.frames : std::max(1, int(std::lround(spec.end_time * job.fps)));

  std::string err;
  auto ctx = render::HeadlessContext::create(&err);
  if (!ctx) {
    std::fprintf(stderr, "rtsph render: %s\n", err.c_str());
    return 1;
  }

  // Output: one PNG, an MP4, or a folder of PNGs.
  const bool single_png = ends_with(job.out, ".png");
  const bool want_mp4 = ends_with(job.out, ".mp4");
  std::unique_ptr<render::FrameSink> sink;
  std::string note;
  if (want_mp4) {
    const std::string ffmpeg = render::find_on_path("ffmpeg");
    if (!ffmpeg.empty()) {
      sink = render::make_ffmpeg_sink(ffmpeg, job.out, width, height, job.fps, &err);
    } else {
      const std::string dir = job.out.substr(0, job.out.size() - 4) + "_frames";
      note = fmt::format("ffmpeg is not on PATH: writing PNG frames to {}/ instead of {}", dir, job.out);
      sink = render::make_png_sequence_sink(dir, width, height, "frame_", &err);
    }
  } else if (!single_png) {
    sink = render::make_png_sequence_sink(job.out, width, height, "frame_", &err);
  } else {
    auto parent = std::filesystem::path(job.out).parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent))
      throw std::runtime_error(fmt::format("cannot write {}: no directory {}", job.out, parent.string()));
  }
  if (!single_png && !sink) throw std::runtime_error(err);
  if (!note.empty() && !job.quiet) std::fprintf(stderr, "rtsph render: %s\n", note.c_str());

  // auto: the GPU when the renderer is a hardware driver and the GPU runs this scene.
  std::string backend = choose_backend(job.backend, spec, "auto");
  if (backend == "auto")
    backend = !gpu::software_renderer() && gpu::gpu_cannot_run(spec).empty() ? "gpu" : "cpu";
  if (backend == "gpu") {
    if (const std::string why = gpu::compute_support_problem(); !why.empty())
      throw BackendUnavailable("--backend gpu: " + why);
    if (const std::string why = gpu::gpu_cannot_run(spec); !why.empty()) throw BackendUnavailable(why);
  }
  // The GPU simulation lives in this context; the renderer reads it back each frame.
  auto sim = backend == "gpu" ? gpu::make_gpu_simulation(spec, job.threads) : make_simulation(spec, job.threads);
  render::Renderer renderer;
  setup_scene_view(spec, renderer, settings);
  render::Camera cam;
  frame_scene(spec, cam, float(width) / float(height));
  render::OffscreenTarget target(width, height);

  const double t_end = (frames - 1) / job.fps;
  if (!job.quiet) {
    auto st = sim->stats();
    std::fprintf(stderr, "rtsph render: %s (%dD, %s backend), %zu fluid + %zu boundary particles, %d frame%s at %g fps, %dx%d, %s\n",
                 spec.name.c_str(), spec.dimension, backend.c_str(), st.fluid_particles, st.boundary_particles, frames,
                 frames == 1 ? "" : "s", job.fps, width, height, ctx->description().c_str());
  }
  Progress progress("render", std::max(t_end, 1e-9), job.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  double sim_s = 0, draw_s = 0;
  std::vector<unsigned char> pixels;
  for (int i = 0; i < frames; ++i) {
    const double t = i / job.fps;
    const auto a = std::chrono::steady_clock::now();
    while (sim->time() < t - 1e-12) sim->step();
    const auto b = std::chrono::steady_clock::now();
    sim_s += std::chrono::duration<double>(b - a).count();
    if (!single_png || i == frames - 1) {
      const BoundaryView boundary = sim->boundary();
      if (const auto device = sim->device_particles())
        renderer.use_device(*device, &boundary);  // the GPU backend: drawn from its buffers
      else
        renderer.upload(sim->fluid(), &boundary);
      renderer.upload_solids(obstacle_solids(*sim));
      target.bind();
      renderer.draw(cam, width, height, settings);
      pixels = target.read_rgba();
      if (sink && !sink->write(pixels.data())) throw std::runtime_error(sink->error());
      draw_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - b).count();
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress.update(t, fmt::format("frame {}/{}, {:.1f} frames/s", i + 1, frames, wall > 0 ? (i + 1) / wall : 0.0));
  }
  progress.finish();
  if (single_png) {
    if (!render::write_png(job.out, width, height, pixels.data()))
      throw std::runtime_error(fmt::format("cannot write {}", job.out));
  } else if (!sink->close()) {
    throw std::runtime_error(sink->error());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!job.quiet)
    std::fprintf(stderr, "rtsph render: %d frame%s, simulated 0..%.3f s in %.1f s (simulation %.1f s, drawing %.1f s)\n",
                 frames, frames == 1 ? "" : "s", t_end, wall, sim_s, draw_s);
  if (job.time_passes) print_pass_times(renderer.surface_times(), renderer.splat_count());
  if (job.time_draw > 0) time_draws(renderer, target, cam, width, height, settings, job.time_draw);
  std::printf("%s\n", single_png ? job.out.c_str() : sink->path().c_str());
  return 0;
}

void add_render_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RenderJob>();
  auto* cmd = app.add_subcommand("render", "Render a scene to PNG / MP4 headless (EGL, no display needed)");
  cmd->add_option("scene", o->scene, "Scene file or built-in name (see `rtsph scenes`)")->required();
  cmd->add_option("--out", o->out, "Output: FILE.png (last frame), FILE.mp4 (video, ffmpeg) or a directory (frame_000000.png, …)")->required();
  cmd->add_option("--frames", o->frames, "Number of frames (default: the scene's end_time × fps)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--fps", o->fps, "Frames per simulated second; frames are 1/fps apart")->capture_default_str()->check(positive_number());
  cmd->add_option("--size", o->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--style", o->style, "surface (water surface; 2D: filled contour) or particles")->capture_default_str();
  cmd->add_option("--color", o->color, "solid, speed, velocity, pressure, density or log_density (particle style)")->capture_default_str();
  cmd->add_option("--display", o->display, "fluid, obstacles (fluid + obstacles) or all (with wall particles)")->capture_default_str();
  cmd->add_option("--colormap", o->colormap, "viridis or turbo")->capture_default_str();
  cmd->add_option("--range", o->range, "Fixed colour range MIN,MAX (default: automatic per frame)")->expected(2)->delimiter(',');
  cmd->add_option("--threads", o->threads, "Solver threads (0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--backend", o->backend, "Where the solver runs: cpu, gpu or auto (the GPU on a hardware "
                                           "OpenGL driver, the CPU on a software one); default: the scene's solver.backend")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  cmd->add_option("--set", o->sets, "Override a scene parameter, e.g. --set fluid.spacing=0.04");
  cmd->add_flag("--quiet", o->quiet, "No progress on the terminal");
  cmd->add_flag("--time-passes", o->time_passes, "Print the CPU time of each surface pass (glFinish between passes)");
  cmd->add_option("--time-draw", o->time_draw, "Then draw the last frame N more times, without stepping or "
                                               "reading pixels back, and print the median draw time (the viewer's "
                                               "frame rate at this size, drawing alone)")
      ->check(CLI::Range(1, 100000));
  cmd->callback([o, cmd, &exit_code] {
    o->style_given = cmd->count("--style") > 0;
    o->color_given = cmd->count("--color") > 0;
    if (o->range.size() == 2) {
      o->range_min = o->range[0];
      o->range_max = o->range[1];
      if (!(o->range_max > o->range_min)) {
        std::fprintf(stderr, "rtsph render: --range: MAX must exceed MIN\n");
        exit_code = 2;
        return;
      }
    }
    exit_code = guarded([&] { return render_scene(*o); });
  });
}

}  // namespace rtsph::app
