#version 430 core
// One instance per particle: a screen-aligned quad that the fragment shader turns into a
// ray-cast sphere (3D) or a disc (2D). Attributes are the SoA arrays, one float each.
layout(location = 0) in float a_x;
layout(location = 1) in float a_y;
layout(location = 2) in float a_z;
layout(location = 3) in float a_vx;
layout(location = 4) in float a_vy;
layout(location = 5) in float a_vz;
layout(location = 6) in float a_rho;
layout(location = 7) in float a_p;

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_radius;      // m
uniform int u_dim;           // 2 or 3
uniform int u_ortho;         // 1: orthographic projection
uniform int u_color_mode;    // 0 solid, 1 speed, 2 velocity, 3 pressure, 4 density, 5 log10 density
uniform vec2 u_range;        // value mapped to the ends of the colour map
uniform vec3 u_solid;        // colour for mode 0
uniform sampler2D u_lut;     // colour map, 1 texel high
uniform int u_points;        // 1: one GL_POINTS vertex per particle (point sprite), else a quad
uniform float u_viewport_h;  // pixels

out vec3 v_color;
out vec3 v_pos_view;         // point on the quad, view space
flat out vec3 v_center_view;
out vec2 v_corner;           // quad coordinate in [-1, 1]² (times the quad scale)

const vec2 kCorners[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));

vec3 lut(float t) {
  float n = float(textureSize(u_lut, 0).x);
  float u = (clamp(t, 0.0, 1.0) * (n - 1.0) + 0.5) / n;
  return textureLod(u_lut, vec2(u, 0.5), 0.0).rgb;
}

vec3 hue(float h) {
  vec3 k = clamp(abs(mod(h * 6.0 + vec3(0.0, 4.0, 2.0), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return k;
}

float norm_range(float v) {
  float d = u_range.y - u_range.x;
  return d > 0.0 ? (v - u_range.x) / d : 0.5;
}

void main() {
  vec3 center = vec3(a_x, a_y, u_dim == 3 ? a_z : 0.0);
  vec3 vel = vec3(a_vx, a_vy, u_dim == 3 ? a_vz : 0.0);
  float speed = length(vel);
  if (u_color_mode == 1) {
    v_color = lut(norm_range(speed));
  } else if (u_color_mode == 2) {
    // Direction → colour: hue wheel of the xy direction in 2D, RGB = ½(1 + v̂) in 3D; slow
    // particles fade to grey (the range's upper end is the speed of full saturation).
    vec3 dir = speed > 0.0 ? vel / speed : vec3(0.0);
    vec3 c = u_dim == 3 ? 0.5 + 0.5 * dir : hue(atan(dir.y, dir.x) / 6.2831853 + 0.5);
    v_color = mix(vec3(0.5), c, clamp(norm_range(speed), 0.0, 1.0));
  } else if (u_color_mode == 3) {
    v_color = lut(norm_range(a_p));
  } else if (u_color_mode == 4) {
    v_color = lut(norm_range(a_rho));
  } else if (u_color_mode == 5) {
    v_color = lut(norm_range(log(max(a_rho, 1e-30)) * 0.43429448));
  } else {
    v_color = u_solid;
  }

  vec4 cv = u_view * vec4(center, 1.0);
  v_center_view = cv.xyz;
  // Perspective stretches off-axis spheres radially by about |c|/|c.z|: grow the quad to match.
  float scale = 1.0;
  if (u_ortho == 0) {
    float lc = length(cv.xyz);
    scale = min(lc / max(-cv.z, 1e-6), 4.0) * (1.05 + u_radius / max(lc, 1e-6));
  }
  if (u_points == 1) {
    // Point sprite: the fragment shader casts its rays from gl_FragCoord. Software rasterisers
    // set up one point much faster than an instanced quad (llvmpipe: ~5x).
    v_corner = vec2(0.0);
    v_pos_view = cv.xyz;
    gl_Position = u_proj * vec4(cv.xyz, 1.0);
    float depth = u_ortho == 1 ? 1.0 : max(-cv.z, 1e-6);
    gl_PointSize = u_radius * scale * u_proj[1][1] * u_viewport_h / depth;
    return;
  }
  vec2 corner = kCorners[gl_VertexID] * scale;
  v_corner = corner;
  vec3 p = cv.xyz + vec3(corner * u_radius, 0.0);
  v_pos_view = p;
  gl_Position = u_proj * vec4(p, 1.0);
}
