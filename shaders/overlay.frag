#version 430 core
in vec4 v_color;
in float v_lut;
uniform sampler2D u_lut;
out vec4 o_color;
void main() {
  if (v_lut >= 0.0) {
    float n = float(textureSize(u_lut, 0).x);
    float u = (clamp(v_lut, 0.0, 1.0) * (n - 1.0) + 0.5) / n;
    o_color = vec4(texture(u_lut, vec2(u, 0.5)).rgb, 1.0);
  } else {
    o_color = v_color;
  }
}
