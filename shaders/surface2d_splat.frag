#version 430 core
// 2D surface ("metaballs"), pass 1: each particle adds a smooth compact kernel
// w(q) = (1 − q²)³, q = distance / support, to a density field (red, additive), normalised so
// that a filled lattice sums to 1. Alpha keeps the maximum of a small disc per particle
// (blend MAX), so an isolated drop stays visible although its field stays under the threshold.
in vec3 v_color;
in vec3 v_pos_view;
flat in vec3 v_center_view;
in vec2 v_corner;

uniform int u_points;
uniform float u_norm;         // 1 / (the field of a filled lattice)
uniform float u_drop;         // drop radius / support

out vec4 o_field;

void main() {
  vec2 c = u_points == 1 ? gl_PointCoord * 2.0 - 1.0 : v_corner;
  float q2 = dot(c, c);
  if (q2 >= 1.0) discard;
  float w = 1.0 - q2;
  o_field = vec4(w * w * w * u_norm, 0.0, 0.0, q2 < u_drop * u_drop ? 1.0 : 0.0);
}
