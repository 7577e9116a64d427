#version 330 core
// One triangle covering the screen.
out float v_height;  // 0 at the bottom of the screen, 1 at the top
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  v_height = 0.5 * p.y + 0.5;
  gl_Position = vec4(p, 1.0, 1.0);
}
