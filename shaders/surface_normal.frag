#version 430 core
// Surface pass 4: normals from the smoothed depth, at the surface resolution. Each texel's
// view-space position comes from its depth; the tangents are the smaller of the two one-sided
// differences in x and in y (van der Laan et al. 2009), so a silhouette does not bend the
// surface next to it. Output (n.x, n.y, depth, 1), view space, 0 where there is no water: the
// shading pass reads it with hardware bilinear filtering and divides by the fourth channel,
// which leaves empty texels out; n.z ≥ 0 follows from n.x, n.y (the surface faces the eye).
uniform sampler2D u_depth;     // smoothed eye distance, 0 = none
uniform mat4 u_proj;

out vec4 o_normal_depth;

vec3 view_pos(ivec2 texel, float d) {
  vec2 ndc = (vec2(texel) + 0.5) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  return vec3((ndc + vec2(u_proj[2][0], u_proj[2][1])) * d / vec2(u_proj[0][0], u_proj[1][1]), -d);
}

float depth_at(ivec2 t) {
  ivec2 hi = textureSize(u_depth, 0) - 1;
  return (any(lessThan(t, ivec2(0))) || any(greaterThan(t, hi))) ? 0.0 : texelFetch(u_depth, t, 0).r;
}

// Tangent along dir: the one-sided difference with the smaller depth step; 0 if no neighbour.
vec3 tangent(ivec2 c, vec3 p, ivec2 dir) {
  float dp = depth_at(c + dir), dm = depth_at(c - dir);
  vec3 a = dp > 0.0 ? view_pos(c + dir, dp) - p : vec3(0.0);
  vec3 b = dm > 0.0 ? p - view_pos(c - dir, dm) : vec3(0.0);
  if (dp <= 0.0) return b;
  if (dm <= 0.0) return a;
  return abs(a.z) < abs(b.z) ? a : b;
}

void main() {
  ivec2 c = ivec2(gl_FragCoord.xy);
  float d = depth_at(c);
  if (d <= 0.0) {
    o_normal_depth = vec4(0.0);
    return;
  }
  vec3 p = view_pos(c, d);
  vec3 tx = tangent(c, p, ivec2(1, 0)), ty = tangent(c, p, ivec2(0, 1));
  vec3 n = dot(tx, tx) > 0.0 && dot(ty, ty) > 0.0 ? normalize(cross(tx, ty)) : vec3(0.0, 0.0, 1.0);
  o_normal_depth = vec4(n.xy, d, 1.0);
}
