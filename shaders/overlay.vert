#version 430 core
// Screen-space overlay (legend bar and its text) in pixels, origin top-left, y down.
layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec4 a_color;
layout(location = 2) in float a_lut;  // >= 0: take the colour from the colour map at this t
uniform vec2 u_viewport;
out vec4 v_color;
out float v_lut;
void main() {
  v_color = a_color;
  v_lut = a_lut;
  vec2 ndc = vec2(2.0 * a_pos.x / u_viewport.x - 1.0, 1.0 - 2.0 * a_pos.y / u_viewport.y);
  gl_Position = vec4(ndc, 0.0, 1.0);
}
