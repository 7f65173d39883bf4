// Stand-in for shaders/csg/shade.frag, for measuring only (benchmarks.md,
// "The pipeline's lower bound on llvmpipe"): every marked pixel gets one
// constant colour. No normal is read, no light, no outline: what is left is
// the pass itself (the colour clear, the stencil test, one fragment per
// marked pixel). The declarations are the real shader's, so ShadePass sets
// its uniforms as usual.
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

layout(binding = 0) uniform sampler2D uNormal;

layout(location = 0) uniform vec4 uBackground;
layout(location = 3) uniform vec3 uForward;
layout(location = 4) uniform vec3 uRight;
layout(location = 5) uniform vec3 uUp;
layout(location = 6) uniform vec2 uHalfExtent;
layout(location = 7) uniform int uOrthographic;
layout(location = 8) uniform ivec2 uSize;

void main() {
    outColor = vec4(0.5, 0.2, 0.1, 1.0);
}
