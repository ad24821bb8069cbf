// The viewer's ImGui panel (the Viewer class: viewer.h): scene picker, readouts and energy plots,
// view and brush settings, the help window, and the parameter editor, whose fields come from the
// parameter table (src/scene/params.cpp). Apart from the frame loop (viewer.cpp): it is long.
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "apps/viewer/view_settings.h"
#include "apps/viewer/viewer.h"
#include "scene/params.h"
#include "scene/scene.h"

namespace rtsph::app {

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

}  // namespace rtsph::app
