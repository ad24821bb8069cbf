#pragma once
// The interactive viewer (`rtsph view`, `rtsph` without arguments): its one class, internal to
// apps/viewer. The class is large, so its members are defined by concern, one short file each:
// the window, scene loading and the frame loop (viewer.cpp); mouse, keys, brush, obstacle dragging
// and scripted input (viewer_input.cpp); screenshots and recording (viewer_capture.cpp); the
// ImGui panel (viewer_panel.cpp). The command line is view_command.cpp.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "apps/viewer/script.h"
#include "apps/viewer/sim_runner.h"
#include "apps/viewer/stage_timer.h"
#include "apps/viewer/viewer_backend.h"
#include "render/camera.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "solvers/spec.h"

// GLFW's header must come after epoxy's (GLFW_INCLUDE_NONE), so only the .cpp files include it.
struct GLFWwindow;

namespace rtsph::app {

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
  // The real-time profile's rate (fluid particle-substeps/s per solver thread); 0: measured on
  // this machine when the first profiled scene of a dimension loads.
  double realtime_rate = 0;
  float render_scale = 0;  // 0: adapt to keep ≥ 30 fps; else fixed fraction of the window
  bool time_passes = false;  // print each stage's and surface pass's CPU time (with --report)
  std::string backend;     // cpu, gpu, auto; empty: the scene's solver.backend, else auto
  bool style_given = false, color_given = false;  // on the command line: scene defaults yield
};

constexpr int kGlfwInitFailed = -100;  // run_default falls back to headless rendering

/// The last GLFW error, for the message when no window opens (set by viewer.cpp's callback).
const std::string& glfw_error_text();
double now_s();
std::string timestamp();  // local time, for screenshot and recording names
bool have_display();      // DISPLAY or WAYLAND_DISPLAY set

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
  void leave_llvmpipe_spare_cores(const SimSpec& spec) const;
  void load(const SimSpec& spec, bool reframe);
  void upload_frame();
  SimSpec for_viewer(const SimSpec& scene, const std::vector<std::string>& sets);
  void frame();
  void pace_for_solver();
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
  double machine_rate_[4] = {};  // by dimension: calibrated_rate of this machine's, once measured
  double machine_rate(int dimension);
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
  // Real time first (pace_for_solver): frames are held to kBehindFps while the solver thread
  // is behind real time.
  static constexpr double kBehindFps = 34;
  bool solver_behind_ = false;
  double frame_start_ = 0;
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

}  // namespace rtsph::app
