#version 430 core
// Obstacle solids (src/render/solids.cpp): box faces and 2D shapes are world-space triangles;
// a 3D sphere is a quad around its centre that the fragment shader ray-casts, grown as in
// particle.vert so that the perspective silhouette fits.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_local;
layout(location = 3) in vec4 a_shape;  // kind (0 box, 1 sphere, 2 rectangle, 3 circle), sizes

uniform mat4 u_view;
uniform mat4 u_proj;
uniform int u_ortho;

out vec3 v_pos_view;
out vec3 v_normal_view;
out vec2 v_local;
flat out vec4 v_shape;
flat out vec3 v_center_view;

void main() {
  v_shape = a_shape;
  v_local = a_local;
  vec4 pv = u_view * vec4(a_pos, 1.0);
  v_center_view = pv.xyz;
  v_normal_view = mat3(u_view) * a_normal;
  if (int(a_shape.x + 0.5) == 1) {
    float r = a_shape.y;
    float scale = 1.05;
    if (u_ortho == 0) {
      // On axis the silhouette spans r/sqrt(1 - (r/d)^2) at the centre's depth; off axis it is
      // stretched by about d/|z|.
      float d = length(pv.xyz);
      float q = min(r / max(d, 1e-6), 0.995);
      scale = min(d / max(-pv.z, 1e-6), 4.0) * 1.05 / sqrt(1.0 - q * q);
    }
    pv.xy += a_local * r * scale;
  }
  v_pos_view = pv.xyz;
  gl_Position = u_proj * pv;
}
