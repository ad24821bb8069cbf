#version 430 core
// Sphere impostor: intersects the eye ray with the particle's sphere, writes the true depth and
// shades with Blinn-Phong. In 2D, a flat disc with a soft rim.
in vec3 v_color;
in vec3 v_pos_view;
flat in vec3 v_center_view;
in vec2 v_corner;

uniform mat4 u_proj;
uniform float u_radius;
uniform int u_dim;
uniform int u_ortho;
uniform int u_points;
uniform vec4 u_viewport;     // x, y, width, height in pixels

out vec4 o_color;

void main() {
  if (u_dim == 2) {
    vec2 corner = u_points == 1 ? gl_PointCoord * 2.0 - 1.0 : v_corner;
    float r2 = dot(corner, corner);
    if (r2 > 1.0) discard;
    o_color = vec4(v_color * (1.0 - 0.3 * r2), 1.0);
    return;
  }
  vec3 pos_view = v_pos_view;
  if (u_points == 1) {
    // The view-space point on the plane z = -1 (perspective) or at the centre's depth (ortho)
    // under this fragment.
    vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
    vec2 xy = (ndc - vec2(u_proj[3][0], u_proj[3][1])) / vec2(u_proj[0][0], u_proj[1][1]);
    pos_view = u_ortho == 1 ? vec3(xy, v_center_view.z) : vec3(xy, -1.0);
  }
  vec3 ro = u_ortho == 1 ? vec3(pos_view.xy, 0.0) : vec3(0.0);
  vec3 rd = u_ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(pos_view);
  vec3 oc = ro - v_center_view;
  float b = dot(rd, oc);
  float c = dot(oc, oc) - u_radius * u_radius;
  float disc = b * b - c;
  if (disc < 0.0) discard;
  float t = -b - sqrt(disc);
  vec3 p = ro + t * rd;
  vec3 n = (p - v_center_view) / u_radius;
  vec4 clip = u_proj * vec4(p, 1.0);
  float ndc_z = clip.z / clip.w;
  gl_FragDepth = 0.5 * ndc_z * (gl_DepthRange.far - gl_DepthRange.near) +
                 0.5 * (gl_DepthRange.far + gl_DepthRange.near);

  const vec3 L = normalize(vec3(0.35, 0.8, 0.5));
  vec3 V = -rd;
  vec3 H = normalize(L + V);
  float diffuse = max(dot(n, L), 0.0);
  float spec = pow(max(dot(n, H), 0.0), 48.0);
  vec3 col = v_color * (0.3 + 0.7 * diffuse) + vec3(0.3) * spec;
  o_color = vec4(col, 1.0);
}
