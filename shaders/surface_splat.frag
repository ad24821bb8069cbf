#version 430 core
// Surface pass 2 (van der Laan, Green & Sainz 2009), depth and thickness in one draw: every
// fluid particle is a sprite of radius R = 2r (surface_splat.vert, u_radius = R) writing two
// images.
// - Depth (attachment 0, blend MAX): 1 / eye distance of the front of a sphere of radius
//   u_sphere = 1.5 r. Spheres of 1.5 r overlap on a lattice of spacing 2r (its deepest gap,
//   between four spheres, lies √2 r from their centres): no holes to see through, bumps of
//   0.4 r instead of r. The nearest surface has the largest inverse; 0 = no water.
// - Thickness (attachment 1, additive): a soft splat c(q) = A (1 − q²), q = distance of the
//   ray from the centre over R, with A = 4r/π so that its integral is the particle's lattice
//   cell (2r)³: a filled lattice sums to the depth of water along the ray, a smooth image
//   where exact chords through the spheres would carry the lattice's pattern.
// A merged cube of interior particles (render/splat_batch.h) adds thickness only, over a
// splat twice as wide: v_amount = k/2² keeps its integral k cells.
// The sprite is a few pixels wide, so q comes from the sprite coordinate (no ray per pixel)
// and the sphere's front from the centre's depth; particles behind the opaque scene were left
// out by the vertex stage. Every lane of every 4×4 block a sprite touches runs this shader on
// a software rasteriser: it is kept to a handful of operations.
flat in vec3 v_center_view;
flat in float v_amount;  // surface_splat.vert: 1 for a particle, k/4 for a merged cube of k
flat in float v_depth;   // > 0: writes depth (a particle, not a merged cube)
in vec2 v_corner;

uniform float u_radius;           // sprite radius R = 2r (m)
uniform float u_sphere;           // depth sphere radius (m)
uniform int u_points;

layout(location = 0) out float o_inv_depth;  // 1/m
layout(location = 1) out float o_thickness;  // m

void main() {
  vec2 c = u_points == 1 ? gl_PointCoord * 2.0 - 1.0 : v_corner;
  float q2 = dot(c, c);
  if (q2 >= 1.0) discard;
  o_thickness = v_amount * 2.0 * u_radius / 3.14159265 * (1.0 - q2);
  float disc = u_sphere * u_sphere - q2 * u_radius * u_radius;
  // The sphere's front lies sqrt(disc) nearer than its centre (view z grows towards the eye).
  o_inv_depth = disc >= 0.0 && v_depth > 0.0 ? -1.0 / (v_center_view.z + sqrt(disc)) : 0.0;
}
