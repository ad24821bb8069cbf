#version 430 core
// 2D surface, pass 2: the region where the field reaches one half (the boundary of a filled
// lattice: half a spacing outside the outer particles) is filled with the water colour,
// antialiased over one pixel; a band a few pixels wide inside the contour is lighter (edge
// highlight). Blended over the scene behind.
in vec2 v_uv;

uniform sampler2D u_field;
uniform vec3 u_water;

out vec4 o_color;

void main() {
  vec4 f4 = texture(u_field, v_uv);
  float f = max(f4.r, f4.a);
  float aa = max(fwidth(f), 1e-4);
  float alpha = smoothstep(0.5 - aa, 0.5 + aa, f);
  if (alpha <= 0.0) discard;
  // Distance to the contour in pixels, from the field's screen gradient: the highlight is a
  // band of fixed width along the edge, whatever the field's small ripple inside.
  vec2 g = vec2(dFdx(f), dFdy(f));
  float dist_px = (f - 0.5) / max(length(g), 1e-4);
  float rim = 1.0 - smoothstep(0.5, 3.5, dist_px);
  vec3 col = mix(u_water, vec3(0.75, 0.88, 1.0), 0.5 * rim);
  o_color = vec4(col, alpha);
}
