#pragma once
// Perceptual colour maps, evaluated on the CPU and uploaded as a lookup texture so that the
// particles, the legend and the tests all use the same numbers.
#include <array>
#include <string_view>
#include <vector>

namespace rtsph::render {

enum class ColorMap { Viridis, Turbo };

struct Rgb {
  float r = 0, g = 0, b = 0;
};

/// Colour at t in [0, 1] (clamped). Viridis: polynomial fit to matplotlib's viridis (max error
/// about 0.01); Turbo: Google's polynomial approximation of turbo.
Rgb colormap(ColorMap map, float t);

/// Relative luminance (Rec. 709 weights on linearised sRGB).
float luminance(const Rgb& c);

/// n samples at t = i/(n-1), RGBA8, for a GL_TEXTURE_2D of height 1.
std::vector<unsigned char> colormap_lut(ColorMap map, int n);

std::string_view colormap_name(ColorMap map);
bool parse_colormap(std::string_view name, ColorMap* out);

}  // namespace rtsph::render
