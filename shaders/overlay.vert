#version 330 core
// 2D overlay (legend, text) in pixels from the top-left corner.
layout(location = 0) in vec2 a_pixel;
layout(location = 1) in vec4 a_color;  // display RGBA
uniform vec2 u_viewport;               // pixels
out vec4 v_color;
void main() {
  v_color = a_color;
  gl_Position = vec4(2.0 * a_pixel.x / u_viewport.x - 1.0, 1.0 - 2.0 * a_pixel.y / u_viewport.y, 0.0, 1.0);
}
