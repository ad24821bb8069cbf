// Renderer's legend: the colour bar with its range and title, laid out in pixels and drawn
// in one overlay call on top of the scene (stb_easy_font for the text). Its own file, one per
// pass, so renderer.cpp keeps the particle upload and the scene pass.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace rtsph::render {

namespace {

float legend_scale(const RenderSettings& s, int height) {
  if (s.ui_scale > 0) return s.ui_scale;
  return std::max(1.0f, std::round(static_cast<float>(height) / 360.0f * 2.0f) / 2.0f);
}

std::string format_value(float v) {
  if (v == 0) return "0";
  return fmt::format("{:.4g}", v);
}

}  // namespace

LegendLayout Renderer::legend_layout(int width, int height, const RenderSettings& s) const {
  LegendLayout L;
  if (!s.legend || s.color == ColorMode::Solid || s.style == Style::Surface) return L;
  const float scale = legend_scale(s, height);
  const float margin = 10 * scale, bar_w = 12 * scale, title_h = 12 * scale;
  float bar_h = std::clamp(0.45f * static_cast<float>(height), 16.0f, 240.0f * scale);
  L.shown = true;
  L.x1 = static_cast<float>(width) - margin;
  L.x0 = L.x1 - bar_w;
  L.y0 = margin + title_h;
  L.y1 = L.y0 + bar_h;
  auto r = color_range(s);
  L.vmin = r.first;
  L.vmax = r.second;
  switch (s.color) {
    case ColorMode::Speed: L.title = "speed m/s"; break;
    case ColorMode::Velocity: L.title = dim_ == 3 ? "velocity: rgb=dir" : "velocity: hue=dir"; break;
    case ColorMode::Pressure: L.title = "pressure Pa"; break;
    case ColorMode::Density: L.title = "density kg/m3"; break;
    case ColorMode::LogDensity: L.title = "log10 density"; break;
    case ColorMode::Solid: break;
  }
  return L;
}

void Renderer::build_legend(int width, int height, const RenderSettings& s,
                            std::vector<OverlayVertex>* out) const {
  LegendLayout L = legend_layout(width, height, s);
  if (!L.shown) return;
  const float scale = legend_scale(s, height);
  auto quad = [&](float x0, float y0, float x1, float y1, Rgb c, float a, float t0, float t1) {
    OverlayVertex v00{x0, y0, c.r, c.g, c.b, a, t0}, v10{x1, y0, c.r, c.g, c.b, a, t0};
    OverlayVertex v01{x0, y1, c.r, c.g, c.b, a, t1}, v11{x1, y1, c.r, c.g, c.b, a, t1};
    out->insert(out->end(), {v00, v10, v11, v00, v11, v01});
  };
  auto text_width = [&](const std::string& t) {
    return static_cast<float>(stb_easy_font_width(const_cast<char*>(t.c_str()))) * scale;
  };
  auto text = [&](float x, float y, const std::string& t) {
    static thread_local std::vector<char> buf(64 * 1024);
    int quads = stb_easy_font_print(0, 0, const_cast<char*>(t.c_str()), nullptr, buf.data(),
                                    static_cast<int>(buf.size()));
    struct V { float x, y, z; unsigned char c[4]; };
    const V* v = reinterpret_cast<const V*>(buf.data());
    for (int q = 0; q < quads; ++q) {
      const V* k = v + 4 * q;
      OverlayVertex o[4];
      for (int i = 0; i < 4; ++i) o[i] = {x + k[i].x * scale, y + k[i].y * scale, 0.93f, 0.94f, 0.96f, 1.0f, -1.0f};
      out->insert(out->end(), {o[0], o[1], o[2], o[0], o[2], o[3]});
    }
  };
  std::string top = format_value(L.vmax), bottom = format_value(L.vmin);
  std::string mid = format_value(0.5f * (L.vmin + L.vmax));
  float label_w = std::max({text_width(top), text_width(bottom), text_width(mid)});
  float pad = 4 * scale;
  float panel_x0 = std::min(L.x0 - label_w - 2 * pad, L.x1 - text_width(L.title)) - pad;
  quad(panel_x0, L.y0 - 12 * scale - pad, L.x1 + pad, L.y1 + pad, {0.0f, 0.0f, 0.0f}, 0.45f, -1, -1);
  if (s.color == ColorMode::Velocity) {
    // Hue wheel (2D) or grey → saturated (3D, the speed axis of the direction colouring).
    const int seg = 24;
    for (int i = 0; i < seg; ++i) {
      float t0 = 1.0f - static_cast<float>(i) / seg, t1 = 1.0f - static_cast<float>(i + 1) / seg;
      float y0 = L.y0 + (L.y1 - L.y0) * i / seg, y1 = L.y0 + (L.y1 - L.y0) * (i + 1) / seg;
      auto col = [&](float t) {
        if (dim_ == 3) return Rgb{0.5f + 0.5f * t, 0.5f, 0.5f};
        float h = t * 6.0f;
        auto ch = [&](float o) { return std::clamp(std::fabs(std::fmod(h + o, 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f); };
        return Rgb{ch(0), ch(4), ch(2)};
      };
      Rgb c0 = col(t0), c1 = col(t1);
      OverlayVertex a{L.x0, y0, c0.r, c0.g, c0.b, 1, -1}, b{L.x1, y0, c0.r, c0.g, c0.b, 1, -1};
      OverlayVertex c{L.x1, y1, c1.r, c1.g, c1.b, 1, -1}, d{L.x0, y1, c1.r, c1.g, c1.b, 1, -1};
      out->insert(out->end(), {a, b, c, a, c, d});
    }
    if (dim_ == 2) {
      top = std::string("180 deg");
      mid = std::string("0");
      bottom = std::string("-180 deg");
    }
  } else {
    quad(L.x0, L.y0, L.x1, L.y1, {1, 1, 1}, 1.0f, 1.0f, 0.0f);
  }
  const float th = 8 * scale;  // stb_easy_font glyphs are ~7 units tall
  text(L.x1 - text_width(L.title), L.y0 - 11 * scale, L.title);
  text(L.x0 - pad - text_width(top), L.y0, top);
  text(L.x0 - pad - text_width(mid), 0.5f * (L.y0 + L.y1) - 0.5f * th, mid);
  text(L.x0 - pad - text_width(bottom), L.y1 - th, bottom);
}

void Renderer::draw_legend(int width, int height, const RenderSettings& s) {
  std::vector<OverlayVertex> ov;
  build_legend(width, height, s, &ov);
  if (ov.empty()) return;
  ensure_lut(s.map);
  glViewport(0, 0, width, height);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, lut_tex_);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  draw_overlay(ov, width, height);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glUseProgram(0);
  glDisable(GL_BLEND);
}

void Renderer::draw_overlay(const std::vector<OverlayVertex>& v, int width, int height) {
  if (v.empty()) return;
  overlay_.use();
  glUniform2f(overlay_.loc("u_viewport"), static_cast<float>(width), static_cast<float>(height));
  glUniform1i(overlay_.loc("u_lut"), 0);
  glBindVertexArray(overlay_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, overlay_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(OverlayVertex)),
               v.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
}

}  // namespace rtsph::render
