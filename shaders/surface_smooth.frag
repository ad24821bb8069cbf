#version 430 core
// Surface pass 3: one direction of a separable bilateral filter of the splatted depth, in the
// spirit of the narrow-range filter of Truong & Yuksel 2018. Gaussian weights over a radius that
// follows the particle's size on screen, times a Gaussian of the depth difference (σ of three
// particle radii: the spheres' bumps melt into one surface, a sloped surface keeps symmetric,
// continuous weights); samples more than eight radii behind are another sheet of water and are
// ignored, so silhouettes stay sharp. The centre is first pulled to the nearest depth within
// a spacing (at most two radii forward): a pixel that looks through a gap of the lattice into
// a lower layer belongs to the surface in front of it.
uniform sampler2D u_depth;     // eye distance, 0 = no fluid (u_inverse: its inverse)
uniform int u_inverse;         // 1: the input holds 1 / distance (the splat pass's image)
uniform ivec2 u_dir;           // (1, 0) or (0, 1)
uniform float u_px_per_m;      // pixels per metre at unit distance: proj[1][1] · height / 2
uniform float u_radius;        // particle radius (m)
uniform float u_max_px;        // filter radius cap (pixels)

out float o_depth;

const int kTaps = 4;           // samples on each side
const float kFilter = 3.0;     // filter radius in particle radii (one and a half spacings)
const int kHole = 6;           // widest gap filled (pixels)
const float kFar = 8.0;        // samples this many radii behind are another sheet

float fetch(ivec2 p) {
  float v = texelFetch(u_depth, clamp(p, ivec2(0), textureSize(u_depth, 0) - 1), 0).r;
  return u_inverse == 1 && v > 0.0 ? 1.0 / v : v;
}

void main() {
  ivec2 c = ivec2(gl_FragCoord.xy);
  float z = fetch(c);
  if (z <= 0.0) {
    // A gap between the splats (a thin sheet seen through its lattice) with water on both
    // sides within one spacing is filled with the nearer side: holes smaller than a particle
    // close, the outline of the water stays where it is.
    float zl = 0.0, zr = 0.0;
    int il = 0, ir = 0;
    for (int i = 1; i <= kHole; ++i) {
      float a = fetch(c - u_dir * i);
      float b = fetch(c + u_dir * i);
      if (il == 0 && a > 0.0) zl = a, il = i;
      if (ir == 0 && b > 0.0) zr = b, ir = i;
    }
    z = il > 0 && ir > 0 ? min(zl, zr) : 0.0;
    if (z <= 0.0 || float(il + ir) > 2.0 * u_radius * u_px_per_m / z) {
      o_depth = 0.0;
      return;
    }
  }
  float r_px = clamp(kFilter * u_radius * u_px_per_m / z, 1.0, u_max_px);
  float step = max(r_px / float(kTaps), 1.0);
  float inv2s2 = 1.0 / (2.0 * 0.25 * r_px * r_px);   // σ = r_px / 2
  float d[2 * kTaps + 1];
  float z_near = z;
  float spacing_px = 2.0 * u_radius * u_px_per_m / z;
  for (int i = -kTaps; i <= kTaps; ++i) {
    float x = float(i) * step;
    d[i + kTaps] = fetch(c + u_dir * int(round(x)));
    if (d[i + kTaps] > 0.0 && abs(x) <= spacing_px) z_near = min(z_near, d[i + kTaps]);
  }
  float zc = min(z, z_near + 2.0 * u_radius);
  float inv2z2 = 1.0 / (2.0 * 9.0 * u_radius * u_radius);
  float far = zc + kFar * u_radius;
  float sum = 0.0, wsum = 0.0;
  for (int i = -kTaps; i <= kTaps; ++i) {
    float x = float(i) * step;
    float di = d[i + kTaps];
    if (di <= 0.0 || di > far) continue;
    float dz = di - zc;
    float w = exp(-x * x * inv2s2 - dz * dz * inv2z2);
    sum += w * di;
    wsum += w;
  }
  o_depth = sum / wsum;
}
