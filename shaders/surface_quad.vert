#version 430 core
// One triangle covering the viewport, for the full-screen surface passes (no vertex buffer:
// the corners come from gl_VertexID). v_uv spans [0, 1]² over the viewport.
out vec2 v_uv;

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
