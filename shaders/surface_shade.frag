#version 430 core
// Surface pass 5: shading at full resolution (van der Laan et al. 2009; Green, GDC 2010).
// The normal-and-depth image of pass 4 is read with bilinear filtering; its fourth channel is
// the covered fraction of the footprint (empty texels are 0 and drop out of the average; no
// water where less than half is covered). Over the surface:
// - Fresnel (Schlick) mixes a reflected sky gradient with the refracted scene;
// - refraction samples the opaque scene (floor grid, obstacles, walls) offset by normal ×
//   thickness, and only where what it samples lies behind the water;
// - Beer–Lambert: the refracted light is attenuated per channel by exp(−k·thickness) and the
//   water's own colour scattered in, so deep water is darker and bluer than shallow water;
// - a Blinn-Phong highlight of a sun fixed in the world;
// - thin spots (a ray through one or two droplets) are spray: drawn as small white drops.
// Where the scene is nearer than the water, or there is no water, the scene that the target
// already holds shows unchanged.
in vec2 v_uv;

uniform sampler2D u_scene;        // opaque scene colour, full resolution
uniform sampler2D u_scene_depth;  // its window depth
uniform sampler2D u_normal_depth; // (n.x, n.y, eye distance, 1), 0 = none (surface resolution)
uniform sampler2D u_thickness;    // summed thickness (m), surface resolution
uniform mat4 u_proj;
uniform mat3 u_view_to_world;     // rotation: view-space directions → world
uniform vec3 u_water;             // water colour (what deep water tends to)
uniform vec3 u_absorb;            // Beer–Lambert coefficients (1/m), from the water colour
uniform vec3 u_sun;               // direction to the sun, view space (fixed in the world)
uniform float u_radius;           // particle radius (m)
uniform int u_output;             // 0 shaded, 1 world normal as colour (tests)

out vec4 o_color;

const float kRefract = 0.2;       // refraction offset per metre of thickness (m/m)

float view_z(float window_depth) {
  return -u_proj[3][2] / (2.0 * window_depth - 1.0 + u_proj[2][2]);
}

vec3 view_pos(vec2 uv, float d) {
  vec2 ndc = uv * 2.0 - 1.0;
  return vec3((ndc + vec2(u_proj[2][0], u_proj[2][1])) * d / vec2(u_proj[0][0], u_proj[1][1]), -d);
}

vec3 sky(vec3 dir_world) {
  float up = dir_world.y;
  vec3 zenith = vec3(0.32, 0.52, 0.82), horizon = vec3(0.80, 0.86, 0.92), ground = vec3(0.22, 0.22, 0.24);
  return up >= 0.0 ? mix(horizon, zenith, sqrt(up)) : mix(horizon, ground, sqrt(-up));
}

void main() {
  vec4 nd = texture(u_normal_depth, v_uv);
  if (nd.w < 0.5) discard;  // no water: the target holds the scene already
  float d = nd.z / nd.w;
  float scene_wd = texture(u_scene_depth, v_uv).r;
  if (d <= 0.0 || d > -view_z(scene_wd)) discard;  // the scene is in front
  vec3 scene = texture(u_scene, v_uv).rgb;
  vec3 p = view_pos(v_uv, d);
  vec2 nxy = nd.xy / nd.w;
  vec3 n = normalize(vec3(nxy, sqrt(max(1.0 - dot(nxy, nxy), 0.0))));
  if (u_output == 1) {
    o_color = vec4(0.5 + 0.5 * (u_view_to_world * n), 1.0);
    vec4 clip = u_proj * vec4(p, 1.0);
    gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
    return;
  }

  float thickness = texture(u_thickness, v_uv).r;
  vec3 V = -normalize(p);
  // Refraction: offset the scene lookup by normal · thickness, converted to uv at this depth.
  vec2 off = n.xy * kRefract * min(thickness, 1.0) * vec2(u_proj[0][0], u_proj[1][1]) / (2.0 * d);
  vec2 ruv = clamp(v_uv - off, vec2(0.0), vec2(1.0));
  if (-view_z(texture(u_scene_depth, ruv).r) < d) ruv = v_uv;  // that point is in front: no bend
  vec3 behind = texture(u_scene, ruv).rgb;
  vec3 transmit = exp(-u_absorb * thickness);
  // Light scattered in by the water itself has the water's colour and grows with the mean
  // absorption (per channel it would turn mid depths green: blue is absorbed least).
  float scattered = 1.0 - dot(transmit, vec3(1.0 / 3.0));
  vec3 refracted = behind * transmit + u_water * 0.5 * scattered;

  vec3 r_world = u_view_to_world * reflect(-V, n);
  float c = 1.0 - max(dot(n, V), 0.0), c2 = c * c;
  float fresnel = 0.02 + 0.98 * c2 * c2 * c;
  // The sun is fixed in the world (high, to the side), so flat water glints only where it
  // mirrors it, not at a fixed place on the screen.
  vec3 L = u_sun;
  float spec = pow(max(dot(n, normalize(L + V)), 0.0), 200.0);
  vec3 col = mix(refracted, sky(r_world), fresnel) + vec3(0.8) * spec;

  // Spray: a ray through at most a couple of droplets. White, lit like a small sphere.
  float spray = 1.0 - smoothstep(1.0 * u_radius, 2.5 * u_radius, thickness);
  // Its outline comes from the thickness (soft, round splats), not from the coarse depth.
  vec3 drop = vec3(0.92, 0.95, 1.0) * (0.6 + 0.4 * max(dot(n, L), 0.0));
  float cover = smoothstep(0.4 * u_radius, 0.9 * u_radius, thickness);
  col = mix(col, mix(scene, drop, cover), spray);

  o_color = vec4(col, 1.0);
  vec4 clip = u_proj * vec4(p, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
}
