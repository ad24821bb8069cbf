#version 430 core
// Surface pass 1 (van der Laan, Green & Sainz 2009), depth and thickness in one draw: every
// fluid particle is a sprite of radius R = 2r (particle.vert, u_radius = R) writing two images.
// - Depth (attachment 0, blend MAX): 1 / eye distance of the front of a sphere of radius
//   u_sphere = 1.5 r. Spheres of 1.5 r overlap on a lattice of spacing 2r (its deepest gap,
//   between four spheres, lies √2 r from their centres): no holes to see through, bumps of
//   0.4 r instead of r. The nearest surface has the largest inverse; 0 = no water.
// - Thickness (attachment 1, additive): a soft splat c(q) = A (1 − q²), q = distance of the
//   ray from the centre over R, with A = 4r/π so that its integral is the particle's lattice
//   cell (2r)³: a filled lattice sums to the depth of water along the ray, a smooth image
//   where exact chords through the spheres would carry the lattice's pattern.
// Splats behind the opaque scene (obstacles, walls, floor: its depth texture) are left out of
// both, so hidden water neither shows nor thickens what is in front.
in vec3 v_color;
in vec3 v_pos_view;
flat in vec3 v_center_view;
in vec2 v_corner;

uniform mat4 u_proj;
uniform float u_radius;           // sprite radius R = 2r (m)
uniform float u_sphere;           // depth sphere radius (m)
uniform int u_points;
uniform vec4 u_viewport;          // this pass's target: x, y, width, height in pixels
uniform sampler2D u_scene_depth;  // window depth of the opaque scene, full resolution

layout(location = 0) out float o_inv_depth;  // 1/m
layout(location = 1) out float o_thickness;  // m

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
  float perp2 = dot(v_center_view, v_center_view) - b * b;  // squared ray-centre distance
  float q2 = perp2 / (u_radius * u_radius);
  if (q2 >= 1.0) discard;
  float scene_z = view_z(texture(u_scene_depth, uv).r);
  if (v_center_view.z < scene_z) discard;
  o_thickness = 2.0 * u_radius / 3.14159265 * (1.0 - q2);
  float disc = u_sphere * u_sphere - perp2;
  o_inv_depth = 0.0;
  if (disc >= 0.0) {
    float z = ((-b - sqrt(disc)) * rd).z;
    if (z >= scene_z) o_inv_depth = -1.0 / z;
  }
}
