#version 430 core
// Surface pass 2: thickness. Every particle adds a soft splat, c(q) = A (1 − q²) over a disc
// of radius R = 2r (one spacing; the pass draws the sprites at radius R), additively and
// without depth test. A = 4r/π makes the splat's integral the particle's lattice cell, (2r)³,
// so a filled lattice sums to the true depth of water along the ray; a soft, wide kernel
// sums to a smooth image where exact chords through the spheres would carry the lattice's
// pattern into the refraction. Particles whose centre lies behind the opaque scene are left
// out. The shading pass turns the sum into Beer–Lambert absorption and the refraction offset,
// and reads a small sum as spray.
in vec3 v_color;
in vec3 v_pos_view;
flat in vec3 v_center_view;
in vec2 v_corner;

uniform mat4 u_proj;
uniform float u_radius;           // m: the splat radius R, twice the particle radius
uniform int u_points;
uniform vec4 u_viewport;
uniform sampler2D u_scene_depth;

out float o_thickness;            // m

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
  // q: distance of the ray from the centre over R.
  float b = dot(rd, -v_center_view);
  float q2 = (dot(v_center_view, v_center_view) - b * b) / (u_radius * u_radius);
  if (q2 >= 1.0) discard;
  if (v_center_view.z < view_z(texture(u_scene_depth, uv).r)) discard;
  float r = 0.5 * u_radius;
  float len = 4.0 * r / 3.14159265 * (1.0 - q2);
  o_thickness = len;
}
