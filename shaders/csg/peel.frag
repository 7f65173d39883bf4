// Dual depth peeling (Bavoil & Myers 2008), one geometry pass of one operand.
//
// The target is one layer of an RG32F array texture, cleared to
// (-FLT_MAX, -FLT_MAX) and MAX-blended, so after the pass it holds
// (-nearest, farthest) of the tagged depths that reached it. The first pass
// (PEEL_FIRST) lets every fragment through; later passes read the previous
// layer and keep only what lies strictly between its nearest and farthest,
// i.e. what no earlier pass has peeled. No depth test, no culling.
//
// GROUP (GroupPeel.h): the members of a group, depth-tested against each
// other. Writes (tagged depth, tagged depth, member, member), of which the
// pass's colour mask keeps the entry or the exit half, and as its depth an
// order key of the tagged depth. GROUP_TIE: the members again, where they
// tie with the winners (below); UNION: the group is a union, whose winners
// are the nearest entry and the farthest exit.
#include "csg/interface.glsl"
#include "csg/surface.glsl"

#include "csg/surface-depth.glsl"
#ifdef COLLECT
// Collecting (PeelPass::peelThroughLists): each fragment appends its tagged depth to
// its pixel's list; resolve.frag turns the lists into layers. A pixel whose
// fragments overflow the list keeps counting, so the resolve can tell.
layout(binding = kImageFragmentCounts, r32ui) uniform coherent uimage2D uFragmentCounts;
layout(binding = kImageFragments, r32f) uniform writeonly image2DArray uFragments;
#elif defined(GROUP)
layout(location = kPeelKeyBase) uniform uint uKeyBase;  // bits of a depth before every fragment's
layout(location = 2) flat in float vMember;             // the member's index in its group
layout(location = 0) out vec4 outGroup;

// The tagged depth's bit pattern, from uKeyBase's on, as a normal float in
// [0, 1): positive floats order like their bits, so keys order exactly like
// tagged depths (equal only where they are), and a 32-bit float depth buffer
// stores them as they are. The scene's depths span far less than the 2^30
// patterns below 1.0.
float orderKey(float tagged) {
    uint bits = floatBitsToUint(tagged);
    uint offset = bits > uKeyBase ? min(bits - uKeyBase, 0x3f000000u) : 0u;
    return uintBitsToFloat(offset + 0x00800000u);
}
#elif defined(GROUP_TIE)
// A member's faces once more (GroupPeel.h, "ties"): a front face within the
// tolerance of the winning entry, or a back face within it of the winning
// exit, is that surface as far as rounding can tell; the lowest such member
// (its index as the depth, depth test LESS) writes its own tagged depth and
// index, of which the pass's colour mask keeps the entry or the exit half.
// An intersection's winners are the farthest entry and the nearest exit, a
// union's (UNION) the nearest entry and the farthest exit: the tolerance
// reaches from the winner toward the others.
layout(location = 2) flat in float vMember;
layout(location = kPeelTieTolerance) uniform float uTieTolerance;
layout(binding = kTextureGroupWinners) uniform sampler2D uWinners;
layout(location = 0) out vec4 outGroup;
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
layout(binding = kTextureLayers) uniform sampler2DArray uLayers;
layout(location = kPeelPreviousLayer) uniform int uPreviousLayer;
#endif

void main() {
    float t = taggedDepth(surfaceDepth(), gl_FrontFacing);
#ifdef COLLECT
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint slot = imageAtomicAdd(uFragmentCounts, pixel, 1u);
    if (slot < uint(kCollectCapacity)) imageStore(uFragments, ivec3(pixel, int(slot)), vec4(t));
#elif defined(GROUP)
    gl_FragDepth = orderKey(t);
    outGroup = vec4(t, t, vMember, vMember);
#elif defined(GROUP_TIE)
    vec4 winners = texelFetch(uWinners, ivec2(gl_FragCoord.xy), 0);
#ifdef UNION
    if (gl_FrontFacing) {
        if (winners.r < 0.0 || untagged(t) > untagged(winners.r) + uTieTolerance) discard;
    } else if (winners.g < 0.0 || untagged(t) < untagged(winners.g) - uTieTolerance) {
        discard;
    }
#else
    if (gl_FrontFacing) {
        if (winners.r < 0.0 || untagged(t) < untagged(winners.r) - uTieTolerance) discard;
    } else if (winners.g < 0.0 || untagged(t) > untagged(winners.g) + uTieTolerance) {
        discard;
    }
#endif
    // Members number fewer than 2^16: the depth stays below 1, exactly.
    gl_FragDepth = (vMember + 1.0) / 131072.0;
    outGroup = vec4(t, t, vMember, vMember);
#else
#ifndef PEEL_FIRST
    vec2 previous = texelFetch(uLayers, ivec3(gl_FragCoord.xy, uPreviousLayer), 0).rg;
    if (t <= -previous.r || t >= previous.g) discard;
#endif
    outDepths = vec2(-t, t);
#endif
}
