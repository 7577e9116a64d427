#version 330 core
// Two-sided key + fill + hemisphere lighting of the garment and the avatar, with the display modes.
in vec3 v_worldPos;
in vec3 v_normal;
in vec3 v_bary;
in vec3 v_panelColor;
in vec3 v_domainColor;
flat in float v_strain;
in float v_contact;
in vec2 v_uv;

// 0 shaded, 1 wireframe, 2 strain, 3 domains, 4 contacts, 5 avatar, 6 print
uniform int u_mode;
uniform bool u_edges;          // draw triangle edges
uniform vec4 u_edgeColor;      // display RGB + opacity
uniform vec3 u_eye;            // world
uniform vec3 u_keyDir;         // world, towards the light
uniform vec3 u_fillDir;
uniform vec3 u_rimDir;
uniform vec3 u_neutralColor;   // linear
uniform vec3 u_avatarColor;    // linear
uniform vec3 u_contactColor;   // linear
uniform vec3 u_ramp[8];        // strain colour stops, display RGB, evenly spaced over u_strainRange
uniform int u_rampCount;
uniform vec2 u_strainRange;    // stretch fractions mapped to the first and last stop
uniform sampler2D u_print;     // the fabric's print (display RGB), repeated
uniform bool u_hasPrint;
uniform float u_printWidth;    // metres of cloth per image width
uniform float u_printAspect;   // image height / width

out vec4 fragColor;

vec3 toLinear(vec3 c) { return pow(c, vec3(2.2)); }

vec3 rampColor(float s) {
  float t = clamp((s - u_strainRange.x) / max(u_strainRange.y - u_strainRange.x, 1e-9), 0.0, 1.0);
  float x = t * float(u_rampCount - 1);
  int i = min(int(floor(x)), u_rampCount - 2);
  return mix(u_ramp[i], u_ramp[i + 1], x - float(i));
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 viewDir = normalize(u_eye - v_worldPos);
  bool back = !gl_FrontFacing;
  if (back) n = -n;

  vec3 base;
  float specStrength = 0.06;
  float shininess = 20.0;
  if (u_mode == 5) {
    base = u_avatarColor;
    specStrength = 0.18;
    shininess = 40.0;
  } else if (u_mode == 0) {
    base = v_panelColor;
  } else if (u_mode == 2) {
    base = v_strain < -1e8 ? u_neutralColor : toLinear(rampColor(v_strain));
  } else if (u_mode == 3) {
    base = v_domainColor;
  } else if (u_mode == 4) {
    base = mix(u_neutralColor, u_contactColor, clamp(v_contact, 0.0, 1.0));
  } else if (u_mode == 6) {
    // The image's top row is t = 0 and the pattern's y points up: t runs against it.
    vec2 st = vec2(v_uv.x, -v_uv.y / u_printAspect) / u_printWidth;
    base = u_hasPrint ? toLinear(texture(u_print, st).rgb) : u_neutralColor;
  } else {
    base = u_neutralColor;
  }
  // The inside of the garment: darker and desaturated towards a lining grey, so it reads as the reverse.
  if (back && u_mode != 5) {
    base = mix(base, vec3(0.30, 0.29, 0.28), 0.45) * 0.75;
    specStrength *= 0.3;
  }

  vec3 hemi = mix(vec3(0.20, 0.19, 0.18), vec3(0.42, 0.44, 0.48), 0.5 + 0.5 * n.y);
  float key = max(dot(n, u_keyDir), 0.0);
  float fill = max(dot(n, u_fillDir), 0.0);
  float rim = pow(1.0 - max(dot(n, viewDir), 0.0), 3.0) * max(dot(n, u_rimDir) * 0.5 + 0.5, 0.0);
  vec3 h = normalize(u_keyDir + viewDir);
  float spec = key > 0.0 ? pow(max(dot(n, h), 0.0), shininess) : 0.0;

  vec3 color = base * (hemi + key * vec3(0.95, 0.92, 0.86) + fill * vec3(0.28, 0.31, 0.36)) +
               vec3(spec * specStrength) + rim * 0.12 * vec3(0.9, 0.95, 1.0);
  color = pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2));

  if (u_edges && u_mode != 5) {
    float d = min(min(v_bary.x, v_bary.y), v_bary.z);
    float w = fwidth(d);
    float line = 1.0 - smoothstep(0.5 * w, 1.5 * w, d);
    color = mix(color, u_edgeColor.rgb, line * u_edgeColor.a);
  }
  fragColor = vec4(color, 1.0);
}
