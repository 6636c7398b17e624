#version 300 es
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNrm;
layout(location = 2) in float aVal;
uniform mat4 uMVP;
uniform vec3 uOff;
uniform vec3 uScl;
uniform float uPS;
out vec3 vN;
out vec3 vP;
out float vV;
void main() {
  vec3 p = uOff + aPos * uScl;
  vP = p; vN = aNrm; vV = aVal;
  gl_Position = uMVP * vec4(p, 1.0);
  gl_PointSize = uPS;
}
