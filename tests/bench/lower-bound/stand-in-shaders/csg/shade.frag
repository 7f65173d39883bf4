// Stand-in for shaders/csg/shade.frag, for measuring only (benchmarks.md,
// "The pipeline's lower bound on llvmpipe"): every marked pixel gets one
// constant colour. No normal is read, no light, no outline: what is left is
// the pass itself (the colour clear, the stencil test, one fragment per
// marked pixel). The declarations are the real shader's, so ShadePass sets
// its uniforms as usual.
#include "csg/interface.glsl"

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

layout(binding = kTextureNormal) uniform sampler2D uNormal;

layout(location = kShadeBackground) uniform vec4 uBackground;
#include "csg/light.glsl"

void main() {
    outColor = vec4(0.5, 0.2, 0.1, 1.0);
}
