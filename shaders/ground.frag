#version 330 core
// Ground: light floor with an anti-aliased grid, a soft contact shadow under the scene and a radial fade
// into the background.
in vec3 v_worldPos;
uniform vec3 u_center;
uniform vec2 u_shadowRadius;  // metres, half extents of the scene footprint (x, z)
uniform float u_extent;
uniform float u_gridStep;     // metres between grid lines
uniform vec3 u_floorColor;    // display RGB
uniform vec3 u_lineColor;     // display RGB
uniform vec3 u_eye;
out vec4 fragColor;

float gridLine(vec2 p, float step) {
  vec2 g = p / step;
  vec2 w = fwidth(g);
  vec2 d = abs(fract(g - 0.5) - 0.5) / max(w, vec2(1e-6));
  return 1.0 - min(min(d.x, d.y), 1.0);
}

void main() {
  if (u_eye.y < v_worldPos.y) discard;  // seen from below: no floor
  vec2 rel = v_worldPos.xz - u_center.xz;
  float minor = gridLine(rel, u_gridStep) * 0.35;
  float major = gridLine(rel, u_gridStep * 5.0);
  vec3 color = mix(u_floorColor, u_lineColor, max(minor, major) * 0.8);
  vec2 s = rel / max(u_shadowRadius, vec2(1e-3));
  float shadow = exp(-1.6 * dot(s, s));
  color *= 1.0 - 0.28 * shadow;
  float fade = 1.0 - smoothstep(0.35, 1.0, length(rel) / u_extent);
  fragColor = vec4(color, fade);
}
