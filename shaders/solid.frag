#version 430 core
// Obstacle solids. 3D: Blinn-Phong with the particles' light; spheres are ray-cast and write
// their true depth, so fluid impostors and solids occlude each other correctly. 2D: flat fill
// with a soft darkened rim, which is what makes a filled shape read as a body, not a hole.
in vec3 v_pos_view;
in vec3 v_normal_view;
in vec2 v_local;
flat in vec4 v_shape;
flat in vec3 v_center_view;

uniform mat4 u_proj;
uniform int u_ortho;
uniform vec3 u_color;

out vec4 o_color;

vec3 lit(vec3 n, vec3 rd) {
  const vec3 L = normalize(vec3(0.35, 0.8, 0.5));
  vec3 H = normalize(L - rd);
  float diffuse = max(dot(n, L), 0.0);
  float spec = pow(max(dot(n, H), 0.0), 32.0);
  return u_color * (0.3 + 0.7 * diffuse) + vec3(0.18) * spec;
}

void main() {
  int kind = int(v_shape.x + 0.5);
  if (kind >= 2) {
    // Distance to the edge in metres; the rim darkens over a third of the smaller half-size.
    float d, half_min;
    if (kind == 2) {
      d = min(v_shape.y - abs(v_local.x), v_shape.z - abs(v_local.y));
      half_min = min(v_shape.y, v_shape.z);
    } else {
      d = v_shape.y - length(v_local);
      half_min = v_shape.y;
    }
    if (d < 0.0) discard;
    float rim = smoothstep(0.0, 0.35 * half_min, d);
    o_color = vec4(u_color * (0.55 + 0.45 * rim), 1.0);
    gl_FragDepth = gl_FragCoord.z;
    return;
  }
  vec3 rd = u_ortho == 1 ? vec3(0.0, 0.0, -1.0) : normalize(v_pos_view);
  if (kind == 0) {
    vec3 n = normalize(v_normal_view);
    if (dot(n, rd) > 0.0) n = -n;  // seen from inside: light the face we look at
    o_color = vec4(lit(n, rd), 1.0);
    gl_FragDepth = gl_FragCoord.z;
    return;
  }
  float r = v_shape.y;
  vec3 ro = u_ortho == 1 ? vec3(v_pos_view.xy, 0.0) : vec3(0.0);
  vec3 oc = ro - v_center_view;
  float b = dot(rd, oc);
  float disc = b * b - (dot(oc, oc) - r * r);
  if (disc < 0.0) discard;
  float t = -b - sqrt(disc);
  if (t < 0.0) discard;  // the eye is inside the sphere
  vec3 p = ro + t * rd;
  vec4 clip = u_proj * vec4(p, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) * (gl_DepthRange.far - gl_DepthRange.near) +
                 0.5 * (gl_DepthRange.far + gl_DepthRange.near);
  o_color = vec4(lit((p - v_center_view) / r, rd), 1.0);
}
