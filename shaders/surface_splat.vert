#version 430 core
// Surface pass 2's vertex stage: one point sprite (or instanced quad) per fluid particle with
// only the three position attributes (particle.vert also fetches velocity, density and
// pressure for its colours, which the splats do not need). The particle's centre is tested
// against the opaque scene's depth here, once per particle instead of once per covered pixel:
// on a software rasteriser a sprite covers a few 4×4 blocks that are all shaded, so every
// per-fragment texture fetch costs tens of lanes per particle. A particle hidden behind the
// scene (obstacle, floor, walls) at its centre is left out of depth and thickness.
layout(location = 0) in float a_x;
layout(location = 1) in float a_y;
layout(location = 2) in float a_z;
layout(location = 3) in float a_weight;  // particles in the splat (render/splat_batch.h)

uniform mat4 u_view;
uniform mat4 u_proj;
uniform float u_radius;           // sprite radius R = 2r (m)
uniform int u_points;             // 1: point sprite, else an instanced quad
uniform float u_viewport_h;       // this pass's target height (pixels)
uniform sampler2D u_scene_depth;  // window depth of the opaque scene, full resolution
uniform int u_weighted;           // 1: a_weight holds the splat's particle count, else 1

flat out vec3 v_center_view;
flat out float v_amount;          // thickness scale: particles over the area's growth
flat out float v_depth;           // > 0: the splat writes depth (a particle, not a merged cube)
out vec2 v_corner;                // quad coordinate in [-1, 1]² (quads only)

const vec2 kCorners[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));

float view_z(float window_depth) {
  return -u_proj[3][2] / (2.0 * window_depth - 1.0 + u_proj[2][2]);
}

void main() {
  vec4 cv = u_view * vec4(a_x, a_y, a_z, 1.0);
  v_center_view = cv.xyz;
  vec4 clip = u_proj * vec4(cv.xyz, 1.0);
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  bool hidden = clip.w <= 0.0 || cv.z < view_z(textureLod(u_scene_depth, uv, 0.0).r);
  if (hidden) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: culled before setup
    gl_PointSize = 1.0;
    v_corner = vec2(0.0);
    v_amount = 0.0;
    v_depth = -1.0;
    return;
  }
  // A merged interior cube (weight > 1) is a thickness splat twice as wide, carrying its
  // particles' volume, with no depth: the particles around it are nearer the eye.
  float k = u_weighted == 1 ? a_weight : 1.0;
  bool merged = k > 1.5;
  float radius = merged ? 2.0 * u_radius : u_radius;
  v_amount = merged ? k * 0.25 : 1.0;
  v_depth = merged ? -1.0 : 1.0;
  if (u_points == 1) {
    // The sprite spans the sphere's projected diameter; the fragment stage measures the ray's
    // distance from the centre with gl_PointCoord (a sprite of a few pixels: the off-axis
    // stretch of perspective is below a pixel).
    v_corner = vec2(0.0);
    gl_Position = clip;
    gl_PointSize = max(radius * u_proj[1][1] * u_viewport_h / max(-cv.z, 1e-6), 1.0);
    return;
  }
  v_corner = kCorners[gl_VertexID];
  gl_Position = u_proj * vec4(cv.xyz + vec3(v_corner * radius, 0.0), 1.0);
}
