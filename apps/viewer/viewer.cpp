// The interactive viewer's window, scene loading and frame loop (the Viewer class: viewer.h).
// The solver runs on its own thread (SimRunner); this thread only draws and handles input.
#include <epoxy/gl.h>
// epoxy provides GL; GLFW must not include a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "apps/sim_backend.h"
#include "apps/viewer/scene_view.h"
#include "apps/viewer/view_settings.h"
#include "apps/viewer/viewer.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "scene/realtime_profile.h"
#include "scene/scene.h"

namespace rtsph::app {

namespace {

std::string g_glfw_error;
void glfw_error(int code, const char* text) { g_glfw_error = fmt::format("{} (GLFW error {:#x})", text, code); }

Viewer* viewer_of(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

}  // namespace

const std::string& glfw_error_text() { return g_glfw_error; }

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string timestamp() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d_%H%M%S", std::localtime(&t));
  return buf;
}

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (d && *d) || (w && *w);
}

// Mesa's llvmpipe rasterises on worker threads, one per core by default, so under software GL
// the drawing also takes the core the solver was left with, and the solver thread (niced, see
// SimRunner::loop) waits. LP_NUM_THREADS = the cores neither the solver nor this thread use (0:
// rasterise on this thread). 3D PBF dam break, 10,695 particles, Xvfb, 1 solver thread on 2
// cores, 2026-11-25: real-time factor 0.85/0.88/0.88 by default, 0.99/0.95/0.88 with it
// (docs/performance.md). Not when the GPU backend runs: then llvmpipe is the solver. A user's
// own LP_NUM_THREADS wins; drivers other than llvmpipe ignore it.
void Viewer::leave_llvmpipe_spare_cores(const SimSpec& spec) const {
  if (choose_backend(opt_.backend, spec, "auto") == "gpu") return;
  const int hw = std::max(1, int(std::thread::hardware_concurrency()));
  const int spare = std::max(0, hw - threads_ - 1);
  setenv("LP_NUM_THREADS", std::to_string(spare).c_str(), /*overwrite=*/0);
}

Viewer::WindowResult Viewer::create_window() {
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit()) return WindowResult::InitFailed;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  int w = 1280, h = 720;
  parse_size(opt_.size, &w, &h);
  win_ = glfwCreateWindow(w, h, "rtsph", nullptr, nullptr);
  return win_ ? WindowResult::Ok : WindowResult::WindowFailed;
}

SimSpec Viewer::for_viewer(const SimSpec& scene, const std::vector<std::string>& sets) {
  scene_spec_ = scene;
  scene_sets_ = sets;
  for (const auto& a : sets) apply_override(scene_spec_, a);
  if (!realtime_) {
    profile_text_ = scene_spec_.viewer_realtime ? "as written (real-time profile off)" : "as written";
    return scene_spec_;
  }
  // The budget is this machine's: a fixed one (the reference machine's) ran a slower machine's
  // dam break at half its real speed. It is measured on what steps the scene, the GPU or the CPU
  // (before the backend is chosen, backend_.name is empty: the reference rate, provisionally).
  const bool gpu = backend_.name == "gpu";
  double rate = opt_.realtime_rate;
  const char* source = "--realtime-rate";
  if (rate <= 0 && scene_spec_.viewer_realtime && !backend_.name.empty()) {
    rate = machine_rate(scene_spec_.dimension);
    source = gpu ? "measured on this GPU" : "measured on this machine";
  }
  // The GPU steps as one device (threads = 1 in the budget), and its budget may refine the scene:
  // it was measured at the sizes it gives (measure_gpu_budget).
  RealtimeProfile p = realtime_profile(scene_spec_, gpu ? 1 : threads_, rate, gpu);
  if (rate > 0) p.rate_source = source;
  if (gpu) p.rate_per = "on the GPU";
  profile_text_ = p.describe();
  SimSpec out = p.spec;
  // The user's own overrides win over the profile's choices; the line says so, as a --set
  // solver.method=dfsph runs DFSPH, not the profile's PBF.
  for (const auto& a : sets) apply_override(out, a);
  if (!sets.empty()) profile_text_ += fmt::format("; then --set {}", fmt::join(sets, ", --set "));
  return out;
}

// Measured once per dimension, on the built-in dam break's profile: on the CPU at the reference
// budget (the workload the reference rate was measured on; a scene of its own may start empty),
// on the GPU from there up to the size it keeps up with (measure_gpu_budget).
double Viewer::machine_rate(int dimension) {
  double& rate = machine_rate_[std::clamp(dimension, 0, 3)];
  if (rate > 0) return rate;
  const SimSpec dam = load_scene(dimension == 3 ? "dam_break_3d" : "dam_break_2d");
  const double t0 = now_s();
  if (backend_.name == "gpu") {
    const DeviceBudget g = measure_gpu_budget(dimension, 0.3);
    // At least a 16th of the CPU reference's, as on the CPU: a software GL (asked for with
    // --backend gpu) would otherwise make the scene a few hundred particles.
    rate = std::max(g.rate, realtime_particle_substeps_per_thread(dimension) / 16);
    std::fprintf(stderr,
                 "rtsph view: this GPU keeps %.0f fluid particles of %s in real time (PBF substeps of %s; "
                 "%.0f%% of each substep's real time; %.1f s): %.3g particle-substeps/s; the real-time profile "
                 "budgets %.3g (at least a 16th of the CPU reference machine's rate)\n",
                 g.particles, dam.name.c_str(), g.describe().c_str(), 100 * realtime_device_share(dimension), now_s() - t0,
                 g.rate, rate);
    return rate;
  }
  const RealtimeProfile reference = realtime_profile(dam, threads_);
  const double measured = measure_particle_substeps_per_thread(reference.spec, threads_, 0.4);
  rate = calibrated_rate(measured, dimension);
  std::fprintf(stderr,
               "rtsph view: this machine steps %.3g fluid particle-substeps/s per solver thread (%s, PBF, "
               "%.0f particles from rest, %.1f s); the real-time profile budgets %.3g (%.0f%%, at most twice "
               "the reference machine's %.3g)\n",
               measured, dam.name.c_str(), reference.fluid_particles, now_s() - t0, rate,
               100 * realtime_calm_share(dimension), realtime_particle_substeps_per_thread(dimension));
  return rate;
}

void Viewer::load(const SimSpec& spec, bool reframe) {
  spec_ = spec;
  edit_spec_ = spec;
  edit_pending_ = false;
  setup_scene_view(spec, *renderer_, settings_);
  if (reframe) {
    int w = 1, h = 1;
    glfwGetFramebufferSize(win_, &w, &h);
    frame_scene(spec, cam_, float(w) / float(std::max(h, 1)));
  }
  double extent = 0;
  for (int k = 0; k < spec.dimension; ++k) extent = std::max(extent, spec.domain_max[k] - spec.domain_min[k]);
  brush_radius_ = float(0.1 * extent);
  obstacle_targets_.assign(spec.obstacles.size(), std::nullopt);
  obstacle_sel_ = 0;
  gravity_on_ = true;
  e_kin_.clear();
  e_pot_.clear();
  e_tot_.clear();
  glfwSetWindowTitle(win_, fmt::format("rtsph — {} ({}D)", spec.name, spec.dimension).c_str());
}

void Viewer::toggle_fullscreen() {
  static int wx = 100, wy = 100, ww = 1280, wh = 720;
  if (glfwGetWindowMonitor(win_)) {
    glfwSetWindowMonitor(win_, nullptr, wx, wy, ww, wh, 0);
    return;
  }
  GLFWmonitor* m = glfwGetPrimaryMonitor();
  const GLFWvidmode* mode = m ? glfwGetVideoMode(m) : nullptr;
  if (!mode) {
    status("no monitor for fullscreen", true);
    return;
  }
  glfwGetWindowPos(win_, &wx, &wy);
  glfwGetWindowSize(win_, &ww, &wh);
  glfwSetWindowMonitor(win_, m, 0, 0, mode->width, mode->height, mode->refreshRate);
}

// The frame's particles to the renderer: the GPU backend's own buffers, or the CPU's snapshot.
void Viewer::upload_frame() {
  const BoundaryView b = frame_.particles.boundary();
  if (frame_.device) renderer_->use_device(*frame_.device, &b);
  else renderer_->upload(frame_.particles.fluid(), &b);
  renderer_->upload_solids(frame_.obstacle_solids);
}

// In open space a cloud (a star) may drift anywhere: the camera's target moves with the fluid's
// centre (the mean position, equal masses), so panning and orbiting still work relative to it.
void Viewer::follow_cloud() {
  const ParticleView f = frame_.particles.fluid();
  if (f.count == 0 || !f.x[0]) return;
  double c[3] = {0, 0, 0};
  for (int k = 0; k < f.dim; ++k)
    for (std::size_t i = 0; i < f.count; ++i) c[k] += f.x[k][i];
  const render::Vec3f centre{float(c[0] / double(f.count)), float(c[1] / double(f.count)),
                             float(c[2] / double(f.count))};
  if (cloud_centre_) cam_.target += centre - *cloud_centre_;
  cloud_centre_ = centre;
}

void Viewer::frame() {
  pace_for_solver();
  frame_start_ = now_s();
  timer_.start();
  if (!script_.empty()) run_script_step();
  // The GPU backend steps here, in this thread's context: at most about a 60th of a second per
  // frame, so drawing keeps its rate whatever a step costs.
  runner_->pump(1.0 / 60);
  if (std::string e = runner_->take_error(); !e.empty()) status(e, true);

  if (runner_->fetch(&frame_)) {
    if (frame_.generation != generation_) {
      generation_ = frame_.generation;
      e_kin_.clear();
      e_pot_.clear();
      e_tot_.clear();
      e_pot0_ = frame_.stats.potential_energy_j;
      obstacle_targets_.assign(frame_.obstacle_centers.size(), std::nullopt);
      cloud_centre_.reset();
    }
    upload_frame();
    if (spec_.open) follow_cloud();
    if (e_kin_.size() >= 4000) {
      // Keep the plot bounded: drop every other sample.
      for (auto* v : {&e_kin_, &e_pot_, &e_tot_}) {
        std::size_t j = 0;
        for (std::size_t i = 0; i < v->size(); i += 2) (*v)[j++] = (*v)[i];
        v->resize(j);
      }
    }
    if (e_kin_.empty() || frame_.stats.steps > 0) {
      const double ek = frame_.stats.kinetic_energy_j, ep = frame_.stats.potential_energy_j - e_pot0_;
      e_kin_.push_back(float(ek));
      e_pot_.push_back(float(ep));
      e_tot_.push_back(float(ek + ep));
    }
  }
  if (drag_ == Drag::BrushPush || drag_ == Drag::BrushPull) update_brush();

  timer_.lap(StageTimer::kUpload);
  int fbw = 1, fbh = 1;
  glfwGetFramebufferSize(win_, &fbw, &fbh);
  if (fbw > 0 && fbh > 0) {
    // Below full resolution (adaptive, to keep the UI ≥ 30 fps on slow GL) the scene is drawn
    // into a smaller framebuffer and stretched; the legend is drawn sharp on top. Screenshots
    // and recordings always get full resolution.
    const float scale = pending_screenshot_.empty() && !video_ ? scale_ : 1.0f;
    const int rw = std::max(16, int(fbw * scale)), rh = std::max(16, int(fbh * scale));
    if (scale < 0.999f && rw < fbw) {
      if (!lowres_ || lowres_->width() != rw || lowres_->height() != rh)
        lowres_ = std::make_unique<render::OffscreenTarget>(rw, rh);
      lowres_->bind();
      render::RenderSettings s = settings_;
      s.legend = false;
      renderer_->draw(cam_, rw, rh, s);
      timer_.lap(StageTimer::kScene);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, lowres_->fbo());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, rw, rh, 0, 0, fbw, fbh, GL_COLOR_BUFFER_BIT, GL_LINEAR);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      renderer_->draw_legend(fbw, fbh, settings_);
    } else {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      renderer_->draw(cam_, fbw, fbh, settings_);
      timer_.lap(StageTimer::kScene);
    }
    timer_.lap(StageTimer::kBlit);
    capture(fbw, fbh);
  }

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  draw_ui();
  if (drag_ == Drag::BrushPush || drag_ == Drag::BrushPull) {
    // Brush outline around the cursor, sized by the radius at the target's depth.
    int w = 1, h = 1;
    glfwGetWindowSize(win_, &w, &h);
    const float px = brush_radius_ / cam_.world_per_pixel(h);
    ImGui::GetForegroundDrawList()->AddCircle({float(mx_), float(my_)}, px,
                                              drag_ == Drag::BrushPush ? IM_COL32(255, 160, 60, 200) : IM_COL32(80, 200, 255, 200), 48, 2.0f);
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  timer_.lap(StageTimer::kUi);
  glfwSwapBuffers(win_);
  timer_.lap(StageTimer::kSwap);
  timer_.end_frame();

  // fps and simulation cost per drawn frame, over half-second windows
  ++fps_frames_;
  ++frames_total_;
  const double t = now_s();
  if (t - fps_t0_ >= 0.5) {
    fps_ = fps_frames_ / (t - fps_t0_);
    // Adaptive resolution: below 33 fps the drawing shrinks towards a budget of 36 fps (its
    // cost goes with the pixels, scale², plus a fixed part, so by at most the square root of the
    // shortfall, and at most 30% per half second); above 48 fps it grows by 10% (21% more
    // pixels: still above 33, so the two never chase each other).
    if (opt_.render_scale > 0)
      scale_ = std::min(opt_.render_scale, 1.0f);
    else if (fps_ < 33)
      scale_ = std::max(0.35f, scale_ * float(std::clamp(std::sqrt(fps_ / 36), 0.7, 0.95)));
    else if (fps_ > 48 && !solver_behind_)
      scale_ = std::min(1.0f, scale_ * 1.1f);
    sim_ms_per_frame_ = fps_frames_ ? 1000 * std::max(0.0, frame_.busy_s - fps_busy0_) / fps_frames_ : 0;
    fps_t0_ = t;
    fps_busy0_ = frame_.busy_s;
    fps_frames_ = 0;
  }
}

// Real time first. The solver thread and the drawing share the cores (llvmpipe draws on them
// too), and a frame loop without vsync (Xvfb, --frames runs) draws as fast as it can, taking
// cores the solver needs to keep up. While the solver is behind real time (its real-time factor
// below 0.95, until it is back above 0.99) frames are held to kBehindFps, above the 30 fps the
// viewer promises, and the adaptive resolution does not grow. 2026-11-24, 3D PBF dam break at
// 7,020 particles under Xvfb: docs/performance.md.
void Viewer::pace_for_solver() {
  const bool running = !backend_.on_caller_thread && !runner_->paused() && frame_.rtf > 0;
  if (!running) {
    solver_behind_ = false;
    return;
  }
  if (frame_.rtf < 0.95) solver_behind_ = true;
  else if (frame_.rtf > 0.99) solver_behind_ = false;
  if (!solver_behind_ || frame_start_ == 0) return;
  const double wait = frame_start_ + 1.0 / kBehindFps - now_s();
  if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
}

int Viewer::run() {
  const int hw = int(std::thread::hardware_concurrency());
  threads_ = opt_.threads >= 0 ? opt_.threads : std::max(1, hw - 1);
  if (threads_ == 0) threads_ = std::max(1, hw);
  realtime_ = !opt_.accurate;
  const SimSpec scene = load_scene(opt_.scene);
  if (!opt_.script.empty()) script_ = load_script(opt_.script);
  // Provisional (the reference budget): the profile's method decides whether the GPU can run it,
  // and the budget is measured on the backend chosen, once the window's context exists.
  SimSpec spec = for_viewer(scene, opt_.sets);
  settings_ = parse_render_options(opt_.style, opt_.color, opt_.display, opt_.colormap);
  settings_.time_passes = opt_.time_passes;
  gas_defaults(spec, opt_.style_given, opt_.color_given, &settings_);
  int w = 0, h = 0;
  require_size(opt_.size, &w, &h);
  // After the options (a bad one is named wherever it is run), before any measurement: without
  // a display there is nothing to measure the machine for.
  if (!have_display()) {
    std::fprintf(stderr, "rtsph view: no display (DISPLAY / WAYLAND_DISPLAY unset); use `rtsph render` for headless output\n");
    return 1;
  }

  leave_llvmpipe_spare_cores(scene_spec_);
  switch (create_window()) {
    case WindowResult::Ok: break;
    case WindowResult::InitFailed: return kGlfwInitFailed;
    case WindowResult::WindowFailed:
      std::fprintf(stderr, "rtsph view: cannot create an OpenGL 4.3 core profile window: %s\n",
                   g_glfw_error.empty() ? "unknown reason" : g_glfw_error.c_str());
      glfwTerminate();
      return 1;
  }
  glfwMakeContextCurrent(win_);
  if (!render::gl_version_at_least_43()) {
    std::fprintf(stderr, "rtsph view: the window's OpenGL context is %d.%d; 4.3 core is needed\n",
                 epoxy_gl_version() / 10, epoxy_gl_version() % 10);
    glfwDestroyWindow(win_);
    glfwTerminate();
    return 1;
  }
  glfwSwapInterval(opt_.script.empty() && opt_.max_frames == 0 ? 1 : 0);
  glfwSetWindowUserPointer(win_, this);
  // Our callbacks first: ImGui's backend chains to them.
  glfwSetMouseButtonCallback(win_, [](GLFWwindow* w, int b, int a, int m) { viewer_of(w)->on_mouse_button(b, a, m); });
  glfwSetCursorPosCallback(win_, [](GLFWwindow* w, double x, double y) { viewer_of(w)->on_cursor(x, y); });
  glfwSetScrollCallback(win_, [](GLFWwindow* w, double, double dy) { viewer_of(w)->on_scroll(dy); });
  glfwSetKeyCallback(win_, [](GLFWwindow* w, int k, int, int a, int m) { viewer_of(w)->on_key(k, a, m); });

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(win_, true);
  ImGui_ImplOpenGL3_Init("#version 430 core");

  try {
    renderer_ = std::make_unique<render::Renderer>();
    builtins_ = builtin_scenes();
    backend_ = choose_viewer_backend(opt_.backend, spec);
    spec = for_viewer(scene, opt_.sets);  // now with the budget of the backend that steps it
    gl_renderer_ = render::gl_description();
    runner_ = std::make_unique<SimRunner>(spec, opt_.threads >= 0 ? opt_.threads : threads_, opt_.paused,
                                          backend_.make, backend_.on_caller_thread);
    load(spec, true);
    runner_->fetch(&frame_);
    generation_ = frame_.generation;
    e_pot0_ = frame_.stats.potential_energy_j;
    upload_frame();
    std::fprintf(stderr, "rtsph view: %s (%dD, %s, %s backend), %zu fluid + %zu boundary particles, %s\n",
                 spec.name.c_str(), spec.dimension, spec.method.c_str(), backend_.name.c_str(),
                 frame_.stats.fluid_particles, frame_.stats.boundary_particles, render::gl_description().c_str());
    std::fprintf(stderr, "rtsph view: %s%s\n", profile_text_.c_str(),
                 realtime_ && spec.viewer_realtime ? "; --accurate runs the scene as written" : "");
    run_t0_ = fps_t0_ = now_s();
    while (!quit_ && !glfwWindowShouldClose(win_)) {
      glfwPollEvents();
      frame();
      if (opt_.max_frames > 0 && frames_total_ >= opt_.max_frames) quit_ = true;
    }
    if (opt_.report) {
      const double wall = now_s() - run_t0_;
      SimFrame last;
      runner_->fetch(&last);
      const SimFrame& f = last.serial > frame_.serial ? last : frame_;
      std::printf("viewer: %s %s %zu fluid particles: %ld frames in %.2f s = %.2f fps (drawn at %.0f%%); "
                  "sim %.1f ms/frame, %.2f ms/step, sim time %.3f s, real-time factor %.4f; "
                  "fell behind real time %d times (%.3f s skipped)\n",
                  spec_.name.c_str(), spec_.method.c_str(), f.stats.fluid_particles, frames_total_, wall, frames_total_ / wall,
                  100 * scale_, 1000 * f.busy_s / std::max<long>(frames_total_, 1),
                  // The run's mean (the panel's figure is a one-second window: 0 in a shorter run).
                  f.stats.steps ? 1000 * f.busy_s / double(f.stats.steps) : f.step_ms,
                  f.stats.time_s, f.stats.time_s / wall, f.behind_count, f.behind_s);
      if (timer_.on()) timer_.print(renderer_->surface_times(), renderer_->splat_count());
    }
  } catch (...) {
    shutdown();
    throw;
  }
  shutdown();
  return 0;
}

void Viewer::shutdown() {
  runner_.reset();
  lowres_.reset();
  if (video_) {
    video_->close();
    std::fprintf(stderr, "rtsph view: %s\n", video_->describe().c_str());
    video_.reset();
  }
  renderer_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(win_);
  win_ = nullptr;
  // No glfwTerminate(): the process is about to exit, and closing the X display unloads the GL
  // driver, which leaves the driver's few leaked bytes with unsymbolisable stacks that
  // LeakSanitizer cannot match against tests/lsan.supp.
}

}  // namespace rtsph::app
