// `rtsph view SCENE` and `rtsph` without arguments: the interactive viewer (GLFW + Dear ImGui).
// The solver runs on its own thread (SimRunner); this thread only draws and handles input.
#include <epoxy/gl.h>
// epoxy provides GL; GLFW must not include a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/run_summary.h"
#include "apps/viewer/render_job.h"
#include "apps/viewer/scene_view.h"
#include "apps/viewer/script.h"
#include "apps/viewer/sim_runner.h"
#include "apps/viewer/stage_timer.h"
#include "apps/viewer/viewer_backend.h"
#include "apps/viewer/view_settings.h"
#include "render/gl_context.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "scene/params.h"
#include "scene/realtime_profile.h"
#include "scene/scene.h"

namespace rtsph::app {

namespace {

struct ViewOptions {
  std::string scene = "dam_break_3d";
  std::vector<std::string> sets;
  int threads = -1;  // -1: all cores but one (the UI needs one)
  std::string size = "1280x720";
  std::string script;
  std::string color = "solid";
  std::string style = "surface";
  std::string display = "obstacles";
  std::string colormap = "viridis";
  bool paused = false;
  long max_frames = 0;
  bool report = false;
  bool accurate = false;   // run scenes as written, not their real-time profile
  float render_scale = 0;  // 0: adapt to keep ≥ 30 fps; else fixed fraction of the window
  bool time_passes = false;  // print each stage's and surface pass's CPU time (with --report)
  std::string backend;     // cpu, gpu, auto; empty: the scene's solver.backend, else auto
  bool style_given = false, color_given = false;  // on the command line: scene defaults yield
};

constexpr int kGlfwInitFailed = -100;  // run_default falls back to headless rendering

std::string g_glfw_error;
void glfw_error(int code, const char* text) { g_glfw_error = fmt::format("{} (GLFW error {:#x})", text, code); }

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string timestamp() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d_%H%M%S", std::localtime(&t));
  return buf;
}

Vec3d to3d(const render::Vec3f& v) { return {v.x, v.y, v.z}; }
render::Vec3f to3f(const Vec3d& v) { return {float(v[0]), float(v[1]), float(v[2])}; }

class Viewer {
 public:
  explicit Viewer(ViewOptions o) : opt_(std::move(o)), timer_(opt_.time_passes) {}
  int run();

  // Input, from GLFW callbacks or the script.
  void on_mouse_button(int button, int action, int mods, bool from_script = false);
  void on_cursor(double x, double y, bool from_script = false);
  void on_scroll(double dy, bool from_script = false);
  void on_key(int key, int action, int mods, bool from_script = false);

 private:
  enum class Drag { None, Orbit, Pan, BrushPush, BrushPull, Obstacle };

  enum class WindowResult { Ok, InitFailed, WindowFailed };
  WindowResult create_window();
  void load(const SimSpec& spec, bool reframe);
  void upload_frame();
  SimSpec for_viewer(const SimSpec& scene, const std::vector<std::string>& sets);
  void frame();
  void follow_cloud();  // open space: the camera's target moves with the fluid's centre
  void draw_ui();
  void draw_parameters();
  void run_script_step();
  void shutdown();
  void update_brush();
  void move_obstacle_by(int axis, double sign);
  void toggle_recording();
  void toggle_fullscreen();
  void capture(int fbw, int fbh);
  std::optional<Vec3d> pick_point(double mx, double my) const;
  void status(std::string s, bool error = false) {
    status_ = std::move(s);
    status_error_ = error;
    status_time_ = now_s();
    if (!opt_.script.empty() || error) std::fprintf(stderr, "rtsph view: %s\n", status_.c_str());
  }
  Vec3d obstacle_target(int i) const {
    if (i < int(obstacle_targets_.size()) && obstacle_targets_[i]) return *obstacle_targets_[i];
    return i < int(frame_.obstacle_centers.size()) ? frame_.obstacle_centers[i] : Vec3d{};
  }

  ViewOptions opt_;
  ViewerBackend backend_;
  std::string gl_renderer_;
  GLFWwindow* win_ = nullptr;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<SimRunner> runner_;
  SimSpec spec_, edit_spec_;
  // The scene as loaded (with its --set overrides) and what the viewer made of it: its
  // real-time profile (viewer.realtime) unless the user asked for the scene as written.
  SimSpec scene_spec_;
  std::vector<std::string> scene_sets_;
  bool realtime_ = true;
  int threads_ = 1;
  std::string profile_text_;
  bool edit_pending_ = false;
  SimFrame frame_;
  std::uint64_t generation_ = ~0ull;
  render::Camera cam_;
  render::RenderSettings settings_;
  bool gravity_on_ = true;
  bool help_ = false;
  bool quit_ = false;

  Drag drag_ = Drag::None;
  double mx_ = 0, my_ = 0;
  int obstacle_sel_ = 0;
  Vec3d obstacle_plane_point_{};
  std::vector<std::optional<Vec3d>> obstacle_targets_;
  float brush_radius_ = 0.2f, brush_strength_ = 50.0f;
  bool brush_active_ = false;

  float scale_ = 1;  // fraction of the window resolution the scene is drawn at
  std::unique_ptr<render::OffscreenTarget> lowres_;
  std::unique_ptr<render::FrameSink> video_;
  int video_w_ = 0, video_h_ = 0;
  std::string pending_screenshot_;

  std::string status_;
  bool status_error_ = false;
  double status_time_ = 0;

  // readouts
  double fps_ = 0, sim_ms_per_frame_ = 0;
  double fps_t0_ = 0, fps_busy0_ = 0;
  long fps_frames_ = 0, frames_total_ = 0;
  double run_t0_ = 0;
  std::vector<float> e_kin_, e_pot_, e_tot_;
  double e_pot0_ = 0;
  std::optional<render::Vec3f> cloud_centre_;  // the fluid's centre at the last frame (open space)

  // scene picker
  std::vector<std::pair<std::string, std::string>> builtins_;
  char path_buf_[512] = {};

  // script
  std::vector<ScriptCommand> script_;
  std::size_t script_pos_ = 0;
  int script_wait_ = 0;
  bool script_sync_ = false;
  struct ScriptDrag {
    int button = 0, mods = 0, frames = 1, done = 0;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  std::optional<ScriptDrag> script_drag_;
  StageTimer timer_;
};

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (d && *d) || (w && *w);
}

Viewer* viewer_of(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

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
  const RealtimeProfile p = realtime_profile(scene_spec_, threads_);
  profile_text_ = p.describe();
  SimSpec out = p.spec;
  // The user's own overrides win over the profile's choices.
  for (const auto& a : sets) apply_override(out, a);
  return out;
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

std::optional<Vec3d> Viewer::pick_point(double mx, double my) const {
  int w = 1, h = 1;
  glfwGetWindowSize(win_, &w, &h);
  const render::Ray ray = cam_.ray(float(mx), float(my), w, h);
  if (spec_.dimension == 2) return Vec3d{ray.origin.x, ray.origin.y, 0};
  // The first fluid particle the ray passes close to, else the plane through the domain centre
  // facing the camera.
  const ParticleView f = frame_.particles.fluid();
  const float r = std::max(settings_.particle_radius * 2.0f, 1e-6f);
  float best = 1e30f;
  for (std::size_t i = 0; i < f.count; ++i) {
    const render::Vec3f p{f.x[0][i], f.x[1][i], f.x[2][i]};
    const render::Vec3f d = p - ray.origin;
    const float t = render::dot(d, ray.dir);
    if (t <= 0 || t >= best) continue;
    const render::Vec3f off = d - ray.dir * t;
    if (render::dot(off, off) < r * r) best = t;
  }
  if (best < 1e30f) return to3d(ray.origin + ray.dir * best);
  render::Vec3f lo, hi, hit;
  scene_bounds(spec_, &lo, &hi);
  if (render::intersect_plane(ray, (lo + hi) * 0.5f, -cam_.forward(), &hit)) return to3d(hit);
  return std::nullopt;
}

void Viewer::update_brush() {
  const bool want = drag_ == Drag::BrushPush || drag_ == Drag::BrushPull;
  if (!want) {
    if (brush_active_) {
      runner_->set_brush(Brush{});
      brush_active_ = false;
    }
    return;
  }
  auto p = pick_point(mx_, my_);
  Brush b;
  b.active = p.has_value();
  if (p) b.center = *p;
  b.radius = brush_radius_;
  b.strength = drag_ == Drag::BrushPush ? brush_strength_ : -brush_strength_;
  runner_->set_brush(b);
  brush_active_ = b.active;
}

void Viewer::on_mouse_button(int button, int action, int mods, bool from_script) {
  if (!from_script && ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
  if (action == GLFW_RELEASE) {
    if (drag_ != Drag::None) {
      drag_ = Drag::None;
      update_brush();
    }
    return;
  }
  if (action != GLFW_PRESS) return;
  const bool shift = mods & GLFW_MOD_SHIFT, ctrl = mods & GLFW_MOD_CONTROL;
  if (button == GLFW_MOUSE_BUTTON_LEFT && shift) {
    drag_ = Drag::BrushPush;
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT && shift) {
    drag_ = Drag::BrushPull;
  } else if (button == GLFW_MOUSE_BUTTON_LEFT && ctrl) {
    if (frame_.obstacle_centers.empty()) {
      status("this scene has no obstacles to move");
      return;
    }
    // The obstacle whose centre is nearest to the mouse ray.
    int w = 1, h = 1;
    glfwGetWindowSize(win_, &w, &h);
    const render::Ray ray = cam_.ray(float(mx_), float(my_), w, h);
    float best = 1e30f;
    for (int i = 0; i < int(frame_.obstacle_centers.size()); ++i) {
      const render::Vec3f c = to3f(obstacle_target(i));
      const render::Vec3f d = c - ray.origin;
      const render::Vec3f off = d - ray.dir * render::dot(d, ray.dir);
      if (render::dot(off, off) < best) {
        best = render::dot(off, off);
        obstacle_sel_ = i;
      }
    }
    obstacle_plane_point_ = obstacle_target(obstacle_sel_);
    drag_ = Drag::Obstacle;
  } else if (button == GLFW_MOUSE_BUTTON_LEFT) {
    drag_ = spec_.dimension == 2 ? Drag::Pan : Drag::Orbit;
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    drag_ = Drag::Pan;
  }
  update_brush();
}

void Viewer::on_cursor(double x, double y, bool from_script) {
  (void)from_script;
  const double dx = x - mx_, dy = y - my_;
  mx_ = x;
  my_ = y;
  int w = 1, h = 1;
  glfwGetWindowSize(win_, &w, &h);
  switch (drag_) {
    case Drag::Orbit: cam_.orbit(float(-dx * 0.006), float(dy * 0.006)); break;
    case Drag::Pan: cam_.pan(float(dx), float(dy), h); break;
    case Drag::BrushPush:
    case Drag::BrushPull: update_brush(); break;
    case Drag::Obstacle: {
      const render::Ray ray = cam_.ray(float(x), float(y), w, h);
      render::Vec3f hit;
      const render::Vec3f n = spec_.dimension == 2 ? render::Vec3f{0, 0, 1} : -cam_.forward();
      if (render::intersect_plane(ray, to3f(obstacle_plane_point_), n, &hit)) {
        Vec3d c = to3d(hit);
        if (spec_.dimension == 2) c[2] = 0;
        obstacle_targets_[obstacle_sel_] = c;
        runner_->move_obstacle(obstacle_sel_, c);
      }
      break;
    }
    case Drag::None: break;
  }
}

void Viewer::on_scroll(double dy, bool from_script) {
  if (!from_script && ImGui::GetIO().WantCaptureMouse) return;
  cam_.zoom(float(std::pow(0.9, dy)));
}

void Viewer::move_obstacle_by(int axis, double sign) {
  if (frame_.obstacle_centers.empty()) {
    status("this scene has no obstacles to move");
    return;
  }
  if (axis == 2 && spec_.dimension == 2) return;
  double extent = 0;
  for (int k = 0; k < spec_.dimension; ++k) extent = std::max(extent, spec_.domain_max[k] - spec_.domain_min[k]);
  Vec3d c = obstacle_target(obstacle_sel_);
  c[axis] += sign * 0.02 * extent;
  obstacle_targets_[obstacle_sel_] = c;
  runner_->move_obstacle(obstacle_sel_, c);
}

void Viewer::on_key(int key, int action, int mods, bool from_script) {
  (void)mods;
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (!from_script && ImGui::GetIO().WantCaptureKeyboard) return;
  const float rot = 0.0872665f;  // 5°
  int w = 1, h = 1;
  glfwGetWindowSize(win_, &w, &h);
  const bool two = spec_.dimension == 2;
  switch (key) {
    case GLFW_KEY_SPACE: runner_->set_paused(!runner_->paused()); break;
    case GLFW_KEY_N: runner_->step(1); break;
    case GLFW_KEY_R:
      runner_->reset(spec_);
      status("reset");
      break;
    case GLFW_KEY_G:
      gravity_on_ = !gravity_on_;
      runner_->set_gravity(gravity_on_ ? edit_spec_.gravity : Vec3d{});
      status(gravity_on_ ? "gravity on" : "gravity off");
      break;
    case GLFW_KEY_1: toggle_fullscreen(); break;
    case GLFW_KEY_0: settings_.color = render::ColorMode::LogDensity; break;
    case GLFW_KEY_5: settings_.color = render::ColorMode::Density; break;
    case GLFW_KEY_6: settings_.color = render::ColorMode::Pressure; break;
    case GLFW_KEY_7: settings_.color = render::ColorMode::Velocity; break;
    case GLFW_KEY_8: settings_.color = render::ColorMode::Speed; break;
    case GLFW_KEY_9: settings_.color = render::ColorMode::Solid; break;
    case GLFW_KEY_TAB:
      settings_.display = render::DisplayMode((int(settings_.display) + 1) % 3);
      status(fmt::format("display: {}", render::display_mode_name(settings_.display)));
      break;
    case GLFW_KEY_LEFT: two ? cam_.pan(-20, 0, h) : cam_.orbit(-rot, 0); break;
    case GLFW_KEY_RIGHT: two ? cam_.pan(20, 0, h) : cam_.orbit(rot, 0); break;
    case GLFW_KEY_UP: two ? cam_.pan(0, -20, h) : cam_.orbit(0, rot); break;
    case GLFW_KEY_DOWN: two ? cam_.pan(0, 20, h) : cam_.orbit(0, -rot); break;
    case GLFW_KEY_Q: move_obstacle_by(0, -1); break;
    case GLFW_KEY_W: move_obstacle_by(0, +1); break;
    case GLFW_KEY_A: move_obstacle_by(1, -1); break;
    case GLFW_KEY_S: move_obstacle_by(1, +1); break;
    case GLFW_KEY_Z: move_obstacle_by(2, -1); break;
    case GLFW_KEY_X: move_obstacle_by(2, +1); break;
    case GLFW_KEY_F12:
      if (action == GLFW_PRESS) pending_screenshot_ = fmt::format("rtsph_{}_{}.png", spec_.name, timestamp());
      break;
    case GLFW_KEY_V:
      if (action == GLFW_PRESS) toggle_recording();
      break;
    case GLFW_KEY_F:
      settings_.style = settings_.style == render::Style::Surface ? render::Style::Particles : render::Style::Surface;
      status(fmt::format("style: {}", render::style_name(settings_.style)));
      break;
    case GLFW_KEY_H: help_ = !help_; break;
    case GLFW_KEY_ESCAPE: quit_ = true; break;
    default: break;
  }
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

void Viewer::toggle_recording() {
  if (video_) {
    const bool ok = video_->close();
    status(ok ? fmt::format("recording stopped: {}", video_->describe())
              : fmt::format("recording failed: {}", video_->error()),
           !ok);
    video_.reset();
    return;
  }
  int w = 1, h = 1;
  glfwGetFramebufferSize(win_, &w, &h);
  const std::string base = fmt::format("rtsph_{}_{}", spec_.name, timestamp());
  std::string err;
  const std::string ffmpeg = render::find_on_path("ffmpeg");
  if (!ffmpeg.empty())
    video_ = render::make_ffmpeg_sink(ffmpeg, base + ".mp4", w, h, 30, &err);
  else
    video_ = render::make_png_sequence_sink(base + "_frames", w, h, "frame_", &err);
  if (!video_) {
    status("cannot record: " + err, true);
    return;
  }
  video_w_ = w;
  video_h_ = h;
  status(ffmpeg.empty() ? fmt::format("recording PNG frames to {}_frames/ (ffmpeg not found)", base)
                        : fmt::format("recording MP4 to {}.mp4 via ffmpeg", base));
}

void Viewer::capture(int fbw, int fbh) {
  if (pending_screenshot_.empty() && !video_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  auto px = render::read_framebuffer(fbw, fbh);
  if (!pending_screenshot_.empty()) {
    if (render::write_png(pending_screenshot_, fbw, fbh, px.data()))
      status("screenshot saved: " + pending_screenshot_);
    else
      status("cannot write " + pending_screenshot_, true);
    pending_screenshot_.clear();
  }
  if (video_) {
    if (fbw != video_w_ || fbh != video_h_) {
      status("window size changed: recording stopped");
      toggle_recording();
    } else if (!video_->write(px.data())) {
      status("recording failed: " + video_->error(), true);
      video_.reset();
    }
  }
}

void Viewer::run_script_step() {
  if (script_pos_ >= script_.size() && !script_drag_ && script_wait_ == 0) return;
  if (script_drag_) {
    auto& d = *script_drag_;
    int w = 1, h = 1;
    glfwGetWindowSize(win_, &w, &h);
    ++d.done;
    const double f = std::min(1.0, double(d.done) / d.frames);
    on_cursor((d.x0 + (d.x1 - d.x0) * f) * w, (d.y0 + (d.y1 - d.y0) * f) * h, true);
    if (d.done >= d.frames) {
      on_mouse_button(d.button, GLFW_RELEASE, d.mods, true);
      script_drag_.reset();
    }
    return;
  }
  if (script_wait_ > 0) {
    --script_wait_;
    return;
  }
  if (script_sync_) {
    if (runner_->busy()) return;
    script_sync_ = false;
    script_wait_ = 2;  // let the last frame reach the screen
    return;
  }
  while (script_pos_ < script_.size()) {
    const ScriptCommand& c = script_[script_pos_++];
    if (c.op == "wait") {
      script_wait_ = std::stoi(c.args[0]);
      return;
    }
    if (c.op == "sync") {
      script_sync_ = true;
      return;
    }
    if (c.op == "key") {
      on_key(script_key(c.args[0]), GLFW_PRESS, 0, true);
      on_key(script_key(c.args[0]), GLFW_RELEASE, 0, true);
      continue;
    }
    if (c.op == "scroll") {
      on_scroll(std::stod(c.args[0]), true);
      continue;
    }
    if (c.op == "screenshot") {
      pending_screenshot_ = c.args[0];
      return;
    }
    if (c.op == "quit") {
      quit_ = true;
      return;
    }
    if (c.op == "drag") {
      ScriptDrag d;
      d.button = c.args[0] == "left" ? GLFW_MOUSE_BUTTON_LEFT
                 : c.args[0] == "right" ? GLFW_MOUSE_BUTTON_RIGHT
                                        : GLFW_MOUSE_BUTTON_MIDDLE;
      d.mods = c.args[1] == "shift" ? GLFW_MOD_SHIFT : c.args[1] == "ctrl" ? GLFW_MOD_CONTROL : 0;
      d.x0 = std::stod(c.args[2]);
      d.y0 = std::stod(c.args[3]);
      d.x1 = std::stod(c.args[4]);
      d.y1 = std::stod(c.args[5]);
      d.frames = c.args.size() > 6 ? std::max(1, std::stoi(c.args[6])) : 10;
      int w = 1, h = 1;
      glfwGetWindowSize(win_, &w, &h);
      on_cursor(d.x0 * w, d.y0 * h, true);
      on_mouse_button(d.button, GLFW_PRESS, d.mods, true);
      script_drag_ = d;
      return;
    }
  }
}

void Viewer::draw_parameters() {
  const int dim = edit_spec_.dimension;
  bool live_changed = false;
  for (const ParamInfo& p : parameter_table()) {
    if (p.key == "name" || p.key == "dimension") continue;
    ImGui::PushID(p.key.c_str());
    bool changed = false;
    const std::string label = p.unit.empty() ? p.key : fmt::format("{} [{}]", p.key, p.unit);
    switch (p.kind) {
      case ParamKind::Real: {
        double v = p.get(edit_spec_);
        if (ImGui::InputDouble(label.c_str(), &v, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue)) {
          v = std::clamp(v, p.min, p.max);
          if (!(p.min_exclusive && v <= p.min)) {
            p.set(edit_spec_, v);
            changed = true;
          }
        }
        break;
      }
      case ParamKind::Int: {
        int v = int(p.get(edit_spec_));
        if (ImGui::InputInt(label.c_str(), &v)) {
          p.set(edit_spec_, std::clamp(double(v), p.min, p.max));
          changed = true;
        }
        break;
      }
      case ParamKind::Bool: {
        bool v = p.get(edit_spec_) != 0;
        if (ImGui::Checkbox(label.c_str(), &v)) {
          p.set(edit_spec_, v ? 1 : 0);
          changed = true;
        }
        break;
      }
      case ParamKind::Enum: {
        const auto& choices = p.choices_for(dim);
        // get_param/set_param handle enums stored as numbers and as strings (solver.method).
        int v = int(get_param(edit_spec_, p.key));
        const char* cur = v >= 0 && v < int(choices.size()) ? choices[v].c_str() : "?";
        if (ImGui::BeginCombo(label.c_str(), cur)) {
          for (int i = 0; i < int(choices.size()); ++i)
            if (ImGui::Selectable(choices[i].c_str(), i == v)) {
              set_param(edit_spec_, p.key, i);
              changed = true;
            }
          ImGui::EndCombo();
        }
        break;
      }
      case ParamKind::Vec3: {
        Vec3d v = p.get_vec(edit_spec_);
        double a[3] = {v[0], v[1], v[2]};
        if (ImGui::InputScalarN(label.c_str(), ImGuiDataType_Double, a, dim, nullptr, nullptr, "%.4g",
                                ImGuiInputTextFlags_EnterReturnsTrue)) {
          for (int k = 0; k < 3; ++k) v[k] = std::clamp(a[k], p.min, p.max);
          p.set_vec(edit_spec_, v);
          changed = true;
        }
        break;
      }
      case ParamKind::String: {
        ImGui::TextDisabled("%s: %s", p.key.c_str(), p.get_text(edit_spec_).c_str());
        break;
      }
    }
    if (ImGui::IsItemHovered() && !p.help.empty())
      ImGui::SetTooltip("%s%s", p.help.c_str(), p.live ? "\n(applies immediately)" : "\n(applies on reset)");
    if (changed) {
      if (p.live)
        live_changed = true;
      else
        edit_pending_ = true;
    }
    ImGui::PopID();
  }
  if (live_changed) {
    runner_->set_live_parameters(edit_spec_);
    if (!gravity_on_) runner_->set_gravity({});
  }
  if (edit_pending_) {
    ImGui::TextColored({1, 0.8f, 0.3f, 1}, "Some changes apply on reset.");
    if (ImGui::Button("Apply and reset")) {
      try {
        SimSpec checked = parse_scene(scene_to_json(edit_spec_), "viewer");
        runner_->reset(checked);
        spec_ = checked;
        load(checked, false);
        status("parameters applied");
      } catch (const std::exception& e) {
        status(e.what(), true);
      }
    }
  }
}

void Viewer::draw_ui() {
  ImGui::SetNextWindowPos({10, 10}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({360, 620}, ImGuiCond_FirstUseEver);
  ImGui::Begin("rtsph");
  const SimStats& st = frame_.stats;
  ImGui::Text("%s (%dD)   %s", spec_.name.c_str(), spec_.dimension,
              runner_->paused() ? "PAUSED" : "running");
  ImGui::TextDisabled("%s backend, %s", backend_.name.c_str(), gl_renderer_.c_str());
  if (ImGui::Button(runner_->paused() ? "Run (Space)" : "Pause (Space)")) runner_->set_paused(!runner_->paused());
  ImGui::SameLine();
  if (ImGui::Button("Step (N)")) runner_->step(1);
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) runner_->reset(spec_);
  ImGui::SameLine();
  if (ImGui::Button("Help (H)")) help_ = !help_;

  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::BeginCombo("built-in", spec_.name.c_str())) {
      for (const auto& [name, desc] : builtins_) {
        if (ImGui::Selectable(name.c_str(), name == spec_.name)) {
          try {
            SimSpec s = for_viewer(load_scene(name), {});
            runner_->reset(s);
            load(s, true);
          } catch (const std::exception& e) {
            status(e.what(), true);
          }
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", desc.c_str());
      }
      ImGui::EndCombo();
    }
    if (ImGui::Checkbox("real-time profile", &realtime_)) {
      try {
        SimSpec s = for_viewer(scene_spec_, scene_sets_);
        runner_->reset(s);
        load(s, false);
        status(profile_text_);
      } catch (const std::exception& e) {
        status(e.what(), true);
      }
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Scenes marked viewer.realtime run with PBF at a spacing this machine\n"
                        "steps in real time. Off: the scene as written (its method and\n"
                        "resolution, e.g. WCSPH or DFSPH for accuracy). Resets the scene.");
    ImGui::TextDisabled("%s", profile_text_.c_str());
    ImGui::InputText("file", path_buf_, sizeof path_buf_);
    ImGui::SameLine();
    if (ImGui::Button("Load")) {
      try {
        SimSpec s = for_viewer(load_scene(path_buf_), {});
        runner_->reset(s);
        load(s, true);
      } catch (const std::exception& e) {
        status(e.what(), true);
      }
    }
  }
  if (ImGui::CollapsingHeader("Readouts", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Text("particles: %zu fluid, %zu boundary", st.fluid_particles, st.boundary_particles);
    ImGui::Text("sim time %.3f s   dt %.3g s   steps %llu", st.time_s, st.dt_s,
                static_cast<unsigned long long>(st.steps));
    ImGui::Text("%.1f fps   sim %.1f ms/frame   %.2f ms/step", fps_, sim_ms_per_frame_, frame_.step_ms);
    if (scale_ < 0.999f) {
      ImGui::SameLine();
      ImGui::TextDisabled("(drawn at %.0f%%)", 100 * scale_);
    }
    if (runner_->paused())
      ImGui::Text("real-time factor: paused");
    else if (frame_.rtf >= 0.995)
      ImGui::Text("real-time factor %.2f (real time)", frame_.rtf);
    else
      ImGui::TextColored({1, 0.7f, 0.3f, 1}, "real-time factor %.3f (machine too slow)", frame_.rtf);
    ImGui::Text("density error %.2f %% (max %.2f %%)", 100 * st.density_error, 100 * st.max_density_error);
    if (!e_kin_.empty()) {
      const auto minmax = [](const std::vector<float>& v) {
        auto [a, b] = std::minmax_element(v.begin(), v.end());
        return std::pair<float, float>{*a, *b};
      };
      auto [k0, k1] = minmax(e_kin_);
      auto [p0, p1] = minmax(e_pot_);
      auto [t0, t1] = minmax(e_tot_);
      const float lo = std::min({k0, p0, t0}), hi = std::max({k1, p1, t1});
      ImGui::PlotLines("kinetic J", e_kin_.data(), int(e_kin_.size()), 0, fmt::format("{:.4g} J", e_kin_.back()).c_str(), lo, hi, {0, 50});
      ImGui::PlotLines("potential J", e_pot_.data(), int(e_pot_.size()), 0, fmt::format("{:+.4g} J", e_pot_.back()).c_str(), lo, hi, {0, 50});
      ImGui::PlotLines("total J", e_tot_.data(), int(e_tot_.size()), 0, fmt::format("{:+.4g} J", e_tot_.back()).c_str(), lo, hi, {0, 50});
      ImGui::TextDisabled("potential and total relative to t = 0");
    }
  }
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int sty = int(settings_.style);
    if (ImGui::Combo("style (F)", &sty, "particles\0water surface\0")) settings_.style = render::Style(sty);
    const char* colors[] = {"solid (9)", "speed (8)", "velocity (7)", "pressure (6)", "density (5)",
                            "log density (0)"};
    int c = int(settings_.color);
    if (ImGui::Combo("colour", &c, colors, 6)) settings_.color = render::ColorMode(c);
    const char* maps[] = {"viridis", "turbo"};
    int m = int(settings_.map);
    if (ImGui::Combo("colour map", &m, maps, 2)) settings_.map = render::ColorMap(m);
    const char* displays[] = {"fluid", "fluid + obstacles", "everything (boundary particles)"};
    int d = int(settings_.display);
    if (ImGui::Combo("display (TAB)", &d, displays, 3)) settings_.display = render::DisplayMode(d);
    ImGui::Checkbox("auto range", &settings_.auto_range);
    if (!settings_.auto_range) {
      ImGui::InputFloat("min", &settings_.range_min, 0, 0, "%.4g");
      ImGui::InputFloat("max", &settings_.range_max, 0, 0, "%.4g");
    } else {
      ImGui::SameLine();
      if (ImGui::Button("fix current")) {
        auto r = renderer_->color_range(settings_);
        settings_.range_min = r.first;
        settings_.range_max = r.second;
        settings_.auto_range = false;
      }
    }
    ImGui::SliderFloat("radius [m]", &settings_.particle_radius, float(0.1 * spec_.spacing), float(1.5 * spec_.spacing), "%.4f");
    ImGui::Checkbox("grid", &settings_.grid);
    ImGui::SameLine();
    ImGui::Checkbox("walls", &settings_.walls);
    ImGui::SameLine();
    ImGui::Checkbox("legend", &settings_.legend);
    if (ImGui::Checkbox("gravity (G)", &gravity_on_)) runner_->set_gravity(gravity_on_ ? edit_spec_.gravity : Vec3d{});
  }
  if (ImGui::CollapsingHeader("Brush (Shift+drag)", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::SliderFloat("brush radius [m]", &brush_radius_, 0.01f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("strength [m/s2]", &brush_strength_, 1.0f, 500.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
    if (!frame_.obstacle_centers.empty()) {
      ImGui::SliderInt("obstacle (Ctrl+drag, q/w a/s z/x)", &obstacle_sel_, 0, int(frame_.obstacle_centers.size()) - 1);
      const Vec3d c = frame_.obstacle_centers[std::min<std::size_t>(obstacle_sel_, frame_.obstacle_centers.size() - 1)];
      ImGui::Text("obstacle centre %.3f %.3f %.3f", c[0], c[1], c[2]);
    }
  }
  if (ImGui::CollapsingHeader("Parameters")) draw_parameters();
  if (video_) ImGui::TextColored({1, 0.3f, 0.3f, 1}, "REC %s", video_->describe().c_str());
  if (!status_.empty() && now_s() - status_time_ < 8)
    ImGui::TextColored(status_error_ ? ImVec4{1, 0.4f, 0.4f, 1} : ImVec4{0.7f, 0.9f, 0.7f, 1}, "%s", status_.c_str());
  ImGui::End();

  if (help_) {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos({io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f}, ImGuiCond_Always, {0.5f, 0.5f});
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Help (H)", &help_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::TextUnformatted(kViewerHelp);
    ImGui::End();
  }
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
    else if (fps_ > 48)
      scale_ = std::min(1.0f, scale_ * 1.1f);
    sim_ms_per_frame_ = fps_frames_ ? 1000 * std::max(0.0, frame_.busy_s - fps_busy0_) / fps_frames_ : 0;
    fps_t0_ = t;
    fps_busy0_ = frame_.busy_s;
    fps_frames_ = 0;
  }
}

int Viewer::run() {
  const int hw = int(std::thread::hardware_concurrency());
  threads_ = opt_.threads >= 0 ? opt_.threads : std::max(1, hw - 1);
  if (threads_ == 0) threads_ = std::max(1, hw);
  realtime_ = !opt_.accurate;
  SimSpec spec = for_viewer(load_scene(opt_.scene), opt_.sets);
  if (!opt_.script.empty()) script_ = load_script(opt_.script);
  settings_ = parse_render_options(opt_.style, opt_.color, opt_.display, opt_.colormap);
  settings_.time_passes = opt_.time_passes;
  gas_defaults(spec, opt_.style_given, opt_.color_given, &settings_);
  int w = 0, h = 0;
  if (!parse_size(opt_.size, &w, &h))
    throw std::invalid_argument(fmt::format("--size {}: expected WxH, e.g. 1280x720", opt_.size));

  if (!have_display()) {
    std::fprintf(stderr, "rtsph view: no display (DISPLAY / WAYLAND_DISPLAY unset); use `rtsph render` for headless output\n");
    return 1;
  }
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
                  "sim %.1f ms/frame, %.2f ms/step, sim time %.3f s, real-time factor %.4f\n",
                  spec_.name.c_str(), spec_.method.c_str(), f.stats.fluid_particles, frames_total_, wall, frames_total_ / wall,
                  100 * scale_, 1000 * f.busy_s / std::max<long>(frames_total_, 1), f.step_ms,
                  f.stats.time_s, f.stats.time_s / wall);
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

int headless_default() {
  RenderJob job;
  job.scene = "dam_break_3d";
  const bool mp4 = !render::find_on_path("ffmpeg").empty();
  job.out = mp4 ? "rtsph_dam_break_3d.mp4" : "rtsph_dam_break_3d_frames";
  // Coarser than the scene (7k instead of 24k particles), so that it takes well under a minute
  // on a small CPU-only machine.
  job.sets = {"fluid.spacing=0.03"};
  job.frames = 60;
  job.fps = 30;
  job.size = "960x540";
  job.color = "speed";
  std::fprintf(stderr,
               "rtsph: no display; rendering %s headless instead (2 s at 30 fps, spacing 0.03 m) to %s "
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
  cmd->add_flag("--time-passes", o->time_passes, "With --report: print the CPU time of each stage of a frame and of each surface pass (glFinish between them; slows drawing a little)");
  cmd->add_option("--render-scale", o->render_scale, "Draw the scene at this fraction of the window resolution (default: adaptive, to keep >= 30 fps)")->check(CLI::Range(0.1, 1.0));
  cmd->callback([o, cmd, &exit_code] {
    o->style_given = cmd->count("--style") > 0;
    o->color_given = cmd->count("--color") > 0;
    exit_code = guarded([&] {
      Viewer v(*o);
      int rc = v.run();
      if (rc == kGlfwInitFailed) {
        std::fprintf(stderr, "rtsph view: cannot open a window: %s\n", g_glfw_error.c_str());
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
      std::fprintf(stderr, "rtsph: cannot open a window (%s)\n", g_glfw_error.c_str());
      return headless_default();
    }
    return rc;
  });
}

}  // namespace rtsph::app
