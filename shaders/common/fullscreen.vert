// The vertex stage of every fullscreen pass (evaluate, shade): see fullscreen.glsl.
// vUv is (0,0) at the bottom-left corner of the viewport and (1,1) at the top-right.
#include "common/fullscreen.glsl"

layout(location = 0) out vec2 vUv;

void main() {
    vec2 p = fullscreenPosition(gl_VertexID);
    vUv = p * 0.5 + 0.5;
    gl_Position = vec4(p, 0.0, 1.0);
}
