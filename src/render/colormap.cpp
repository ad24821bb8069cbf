#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace rtsph::render {

namespace {

float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }

// Sixth-order polynomial fit of viridis (coefficients per channel, lowest order first).
constexpr double kViridis[7][3] = {
    {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
    {0.1050930431085774, 1.404613529898575, 1.384590162594685},
    {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
    {-4.634230498983486, -5.799100973351585, -19.33244095627987},
    {6.228269936347081, 14.17993336680509, 56.69055260068105},
    {4.776384997670288, -13.74514537774601, -65.35303263337234},
    {-5.435455855934631, 4.645852612178535, 26.3124352495832},
};

Rgb viridis(float tf) {
  double t = clamp01(tf);
  double c[3];
  for (int k = 0; k < 3; ++k) {
    double v = kViridis[6][k];
    for (int i = 5; i >= 0; --i) v = v * t + kViridis[i][k];
    c[k] = v;
  }
  return {clamp01(float(c[0])), clamp01(float(c[1])), clamp01(float(c[2]))};
}

// Polynomial approximation of Google's turbo colour map (Mikhailov 2019).
Rgb turbo(float tf) {
  double x = clamp01(tf);
  double x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x;
  double r = 0.13572138 + 4.61539260 * x - 42.66032258 * x2 + 132.13108234 * x3 -
             152.94239396 * x4 + 59.28637943 * x5;
  double g = 0.09140261 + 2.19418839 * x + 4.84296658 * x2 - 14.18503333 * x3 +
             4.27729857 * x4 + 2.82956604 * x5;
  double b = 0.10667330 + 12.64194608 * x - 60.58204836 * x2 + 110.36276771 * x3 -
             89.90310912 * x4 + 27.34824973 * x5;
  return {clamp01(float(r)), clamp01(float(g)), clamp01(float(b))};
}

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

Rgb colormap(ColorMap map, float t) {
  if (std::isnan(t)) t = 0;
  return map == ColorMap::Turbo ? turbo(t) : viridis(t);
}

float luminance(const Rgb& c) {
  return 0.2126f * srgb_to_linear(c.r) + 0.7152f * srgb_to_linear(c.g) +
         0.0722f * srgb_to_linear(c.b);
}

std::vector<unsigned char> colormap_lut(ColorMap map, int n) {
  n = std::max(n, 2);
  std::vector<unsigned char> out(static_cast<std::size_t>(n) * 4);
  for (int i = 0; i < n; ++i) {
    Rgb c = colormap(map, static_cast<float>(i) / static_cast<float>(n - 1));
    out[4 * i + 0] = static_cast<unsigned char>(std::lround(c.r * 255));
    out[4 * i + 1] = static_cast<unsigned char>(std::lround(c.g * 255));
    out[4 * i + 2] = static_cast<unsigned char>(std::lround(c.b * 255));
    out[4 * i + 3] = 255;
  }
  return out;
}

std::string_view colormap_name(ColorMap map) {
  return map == ColorMap::Turbo ? "turbo" : "viridis";
}

bool parse_colormap(std::string_view name, ColorMap* out) {
  if (name == "viridis") { *out = ColorMap::Viridis; return true; }
  if (name == "turbo") { *out = ColorMap::Turbo; return true; }
  return false;
}

}  // namespace rtsph::render
