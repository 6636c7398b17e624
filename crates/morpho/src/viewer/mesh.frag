#version 300 es
precision highp float;
in vec3 vN;
in vec3 vP;
in float vV;
uniform vec3 uEye;
uniform vec3 uColor;
uniform int uMode;
uniform int uLit;
uniform vec2 uRange;
out vec4 o;
void main() {
  vec3 c = uColor;
  if (uMode == 1) {
    float t = clamp((vV - uRange.x) / max(uRange.y - uRange.x, 1e-30), 0.0, 1.0);
    bool s = uRange.x < 0.0 && uRange.y > 0.0;
    if (s) c = t < 0.5 ? vec3(2.0 * t, 2.0 * t, 1.0) : vec3(1.0, 2.0 - 2.0 * t, 2.0 - 2.0 * t);
    else c = vec3(0.27 + t * 0.72, t * 0.9, 0.33 + (t < 0.5 ? t * 0.4 : 0.53 - (t - 0.5) * 0.9));
    if (vV < -1e29) c = vec3(0.5);
  }
  if (uLit == 1) {
    vec3 n = normalize(vN);
    vec3 l = normalize(uEye - vP);
    c *= 0.3 + 0.7 * abs(dot(n, l));
  }
  o = vec4(c, 1.0);
}
