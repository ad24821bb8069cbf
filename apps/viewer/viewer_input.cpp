// The viewer's input (the Viewer class: viewer.h): mouse, keys and scroll from GLFW's callbacks,
// the brush and obstacle dragging they drive, and the scripted input (--script) that replays
// them for tests and demos. Apart from the window and frame loop (viewer.cpp) so each stays short.
#include <epoxy/gl.h>
// epoxy provides GL; GLFW must not include a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "apps/viewer/scene_view.h"
#include "apps/viewer/script.h"
#include "apps/viewer/viewer.h"
#include "render/renderer.h"

namespace rtsph::app {

namespace {

Vec3d to3d(const render::Vec3f& v) { return {v.x, v.y, v.z}; }
render::Vec3f to3f(const Vec3d& v) { return {float(v[0]), float(v[1]), float(v[2])}; }

}  // namespace

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

}  // namespace rtsph::app
