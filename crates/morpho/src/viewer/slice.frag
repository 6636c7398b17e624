#version 300 es
// the value at a slice pixel: bilinear in the four surrounding sample codes of the slice's grid
// plane, mapped through the colour map (uLut); a non-finite sample (code uNan) is grey
precision highp float;
precision highp usampler2D;
in vec2 vIdx;
uniform usampler2D uTex;
uniform sampler2D uLut;
uniform float uMax;
uniform int uNan;
uniform int uMode;
uniform vec3 uColor;
out vec4 o;
void main() {
  if (uMode == 1) { o = vec4(uColor, 1.0); return; }
  ivec2 sz = textureSize(uTex, 0);
  vec2 f = clamp(vIdx, vec2(0.0), vec2(sz - 1));
  ivec2 i0 = min(ivec2(floor(f)), sz - 1);
  ivec2 i1 = min(i0 + 1, sz - 1);
  vec2 t = f - vec2(i0);
  uint a = texelFetch(uTex, i0, 0).r, b = texelFetch(uTex, ivec2(i1.x, i0.y), 0).r;
  uint c = texelFetch(uTex, ivec2(i0.x, i1.y), 0).r, d = texelFetch(uTex, i1, 0).r;
  if (uNan >= 0 && (a == uint(uNan) || b == uint(uNan) || c == uint(uNan) || d == uint(uNan))) {
    o = vec4(0.5, 0.5, 0.5, 1.0);
    return;
  }
  float v = mix(mix(float(a), float(b), t.x), mix(float(c), float(d), t.x), t.y);
  float u = uMax > 0.0 ? clamp(v / uMax, 0.0, 1.0) : 0.0;
  o = vec4(texture(uLut, vec2((u * 255.0 + 0.5) / 256.0, 0.5)).rgb, 1.0);
}
