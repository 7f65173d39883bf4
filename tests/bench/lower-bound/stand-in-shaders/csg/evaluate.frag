// Stand-in for shaders/csg/evaluate.frag, for measuring only (benchmarks.md,
// "The pipeline's lower bound on llvmpipe"): whatever the block's form, read
// the layer its record names and write its near surface. No walk and no
// tree: the cost left is the pass over the blocks (one fragment per pixel of
// every drawn block, one texel fetch, two outputs and a stencil mark). Every
// pixel gets the mark of slot 0 (a front face), so the normal pass after it
// draws less than it would: the measured floor is lower than the real one,
// never higher.
#ifdef LEAF_MARKS
#extension GL_ARB_shader_stencil_export : require
#endif
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(binding = kTextureLayers) uniform sampler2DArray uLayers;
#include "csg/blocks.glsl"
layout(location = kEvaluateTileOrigin) uniform ivec2 uTileOrigin;
layout(location = kEvaluateLoopBudget) uniform int uLoopBudget;  // kept active: EvaluatePass sets it
layout(location = kEvaluateCoincidence) uniform float uCoincidence;  // the same
layout(location = 0) out float outDepth;
layout(location = 1) out int outLeaf;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    vec2 layer = texelFetch(uLayers, ivec3(pixel, vRecord.x & kSlotLayerMask), 0).rg;
    if (layer.r <= -kClearedDepth || uLoopBudget < -5 || uCoincidence < 0.0) discard;
    outDepth = -layer.r;
    outLeaf = leafCode(0, false);
#ifdef LEAF_MARKS
    gl_FragStencilRefARB = stencilMark(0, faceBit(false, false));
#endif
}
