// Dual depth peeling (Bavoil & Myers 2008), one geometry pass of one operand.
//
// The target is one layer of an RG32F array texture, cleared to
// (-FLT_MAX, -FLT_MAX) and MAX-blended, so after the pass it holds
// (-nearest, farthest) of the tagged depths that reached it. The first pass
// (PEEL_FIRST) lets every fragment through; later passes read the previous
// layer and keep only what lies strictly between its nearest and farthest,
// i.e. what no earlier pass has peeled. No depth test, no culling.
//
// GROUP (PeelPass::peelGroup): the members of a group of convex operands, all
// in one draw, a front face as (depth, -FLT_MAX) and a back face as
// (-FLT_MAX, -depth): the layer ends as (farthest entry, -nearest exit).
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
#ifdef COLLECT
// Collecting (PeelPass::collect): each fragment appends its tagged depth to
// its pixel's list; resolve.frag turns the lists into layers. A pixel whose
// fragments overflow the list keeps counting, so the resolve can tell.
layout(binding = 1, r32ui) uniform coherent uimage2D uFragmentCounts;
layout(binding = 2, r32f) uniform writeonly image2DArray uFragments;
#else
layout(location = 0) out vec2 outDepths;
#endif

#ifndef PEEL_FIRST
// Auto peeling tests the stencil (the pixel's surface count against the
// surfaces peeled so far) before the shader runs: pixels with nothing left
// cost no texture fetch. The test writes nothing, so running it early changes
// no result.
layout(early_fragment_tests) in;

// The previous layer. Another layer of the same texture is the render target:
// GL allows that read after a glTextureBarrier() (ARB_texture_barrier, core in
// 4.5) as long as no texel is both read and written by one draw.
layout(binding = 0) uniform sampler2DArray uLayers;
layout(location = 3) uniform int uPreviousLayer;
#endif

void main() {
    float t = taggedDepth(vViewDepth, gl_FrontFacing);
#ifdef COLLECT
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint slot = imageAtomicAdd(uFragmentCounts, pixel, 1u);
    if (slot < uint(COLLECT_CAPACITY)) imageStore(uFragments, ivec3(pixel, int(slot)), vec4(t));
#else
#ifndef PEEL_FIRST
    vec2 previous = texelFetch(uLayers, ivec3(gl_FragCoord.xy, uPreviousLayer), 0).rg;
    if (t <= -previous.r || t >= previous.g) discard;
#endif
#ifdef GROUP
    const float lowest = uintBitsToFloat(0xff7fffffu);  // -FLT_MAX, the cleared value
    outDepths = gl_FrontFacing ? vec2(t, lowest) : vec2(lowest, -t);
#else
    outDepths = vec2(-t, t);
#endif
#endif
}
