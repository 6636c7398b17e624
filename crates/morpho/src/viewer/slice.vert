#version 300 es
// a slice of a volume (slices.js): world position and the in-plane fractional sample index
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec2 aIdx;
uniform mat4 uMVP;
out vec2 vIdx;
void main() {
  vIdx = aIdx;
  gl_Position = uMVP * vec4(aPos, 1.0);
}
