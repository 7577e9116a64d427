#version 330 core
// Vertical gradient: u_top at the top of the screen, a darker shade at the bottom.
in float v_height;
uniform vec3 u_top;     // display RGB
uniform vec3 u_bottom;  // display RGB
out vec4 fragColor;
void main() { fragColor = vec4(mix(u_bottom, u_top, clamp(v_height, 0.0, 1.0)), 1.0); }
