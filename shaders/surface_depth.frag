#version 430 core
// Surface pass 1 (van der Laan, Green & Sainz 2009): sphere depth splats. Each fluid particle
// (particle.vert's quad or point sprite) is ray-cast as a sphere; the nearest front surface
// wins the depth test and its eye distance goes to an R32F target. Splats behind the opaque
// scene (obstacles, walls, floor: its depth texture) are dropped, so hidden water neither
// shows nor bends the smoothing.
in vec3 v_color;
in vec3 v_pos_view;
flat in vec3 v_center_view;
in vec2 v_corner;

uniform mat4 u_proj;
uniform float u_radius;           // m
uniform int u_points;
uniform vec4 u_viewport;          // this pass's target: x, y, width, height in pixels
uniform sampler2D u_scene_depth;  // window depth of the opaque scene, full resolution

out float o_depth;                // eye distance -z_view of the front surface (m); 0 = none

float view_z(float window_depth) {
  return -u_proj[3][2] / (2.0 * window_depth - 1.0 + u_proj[2][2]);
}

void main() {
  vec2 uv = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw;
  vec3 pos_view = v_pos_view;
  if (u_points == 1) {
    vec2 ndc = uv * 2.0 - 1.0;
    pos_view = vec3((ndc + vec2(u_proj[2][0], u_proj[2][1])) / vec2(u_proj[0][0], u_proj[1][1]), -1.0);
  }
  vec3 rd = normalize(pos_view);
  float b = dot(rd, -v_center_view);
  float disc = b * b - (dot(v_center_view, v_center_view) - u_radius * u_radius);
  if (disc < 0.0) discard;
  vec3 p = (-b - sqrt(disc)) * rd;
  if (p.z < view_z(texture(u_scene_depth, uv).r)) discard;
  o_depth = -p.z;
  vec4 clip = u_proj * vec4(p, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) * (gl_DepthRange.far - gl_DepthRange.near) +
                 0.5 * (gl_DepthRange.far + gl_DepthRange.near);
}
