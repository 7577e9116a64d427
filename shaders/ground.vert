#version 330 core
// A square on the ground plane y = u_groundY around the scene centre.
layout(location = 0) in vec2 a_corner;  // -1..1
uniform mat4 u_viewProjection;
uniform vec3 u_center;    // world, scene centre projected on the ground
uniform float u_extent;   // metres, half size of the square
out vec3 v_worldPos;
void main() {
  v_worldPos = u_center + vec3(a_corner.x * u_extent, 0.0, a_corner.y * u_extent);
  gl_Position = u_viewProjection * vec4(v_worldPos, 1.0);
}
