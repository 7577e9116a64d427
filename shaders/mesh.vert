#version 330 core
// Garment and avatar: world-space position and normal, plus per-corner display attributes.
layout(location = 0) in vec3 a_position;   // metres
layout(location = 1) in vec3 a_normal;     // smooth vertex normal
layout(location = 2) in vec3 a_bary;       // barycentric corner (1,0,0), (0,1,0), (0,0,1) for edge drawing
layout(location = 3) in vec3 a_panelColor; // linear RGB
layout(location = 4) in vec3 a_domainColor;// linear RGB
layout(location = 5) in float a_strain;    // stretch fraction, or a large negative value when absent
layout(location = 6) in float a_contact;   // 1 in contact, 0 otherwise
layout(location = 7) in vec2 a_uv;         // pattern coordinates, metres (the print's frame)

uniform mat4 u_viewProjection;
uniform float u_inset;  // metres: drawn this far inside along the normal (colliders: the contact thickness)

out vec3 v_worldPos;
out vec3 v_normal;
out vec3 v_bary;
out vec3 v_panelColor;
out vec3 v_domainColor;
flat out float v_strain;
out float v_contact;
out vec2 v_uv;

void main() {
  float len = length(a_normal);
  vec3 position = len > 0.0 ? a_position - (u_inset / len) * a_normal : a_position;
  v_worldPos = position;
  v_normal = a_normal;
  v_bary = a_bary;
  v_panelColor = a_panelColor;
  v_domainColor = a_domainColor;
  v_strain = a_strain;
  v_contact = a_contact;
  v_uv = a_uv;
  gl_Position = u_viewProjection * vec4(position, 1.0);
}
