// A group of convex operands' winners to its peeled layer (GroupPeel.h),
// fullscreen over the group's rectangle in the tile, stencil-tested: only
// pixels where every member's back face was counted run.
//
// The scratch image holds (farthest entry, nearest exit, entry member, exit
// member), -1 where no member had an entry. The group's interval on the ray
// runs from that entry to that exit, and is written as a convex operand's
// layer would hold it: (-entry, exit); (-exit, exit) where no member had an
// entry (the ray starts inside every one); nothing (the layer stays
// cleared) where the entry does not lie before the exit. Depths are compared
// untagged, as the evaluator does: an entry and an exit at one depth leave
// the ray outside. Where the group has a surface, the two members are kept
// in the group's layer of the ids.
//
// UNION: the group is a union of its members (the nearest entry, the
// farthest exit); it runs without the stencil test, and has an interval
// only where some member was entered (every ray starts outside).
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(early_fragment_tests) in;

layout(binding = kTextureGroupScratch) uniform sampler2D uScratch;
layout(binding = kImageGroupIds, r32ui) uniform writeonly uimage2DArray uIds;
layout(location = kGroupIdsLayer) uniform int uIdsLayer;

layout(location = 0) out vec2 outDepths;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 winners = texelFetch(uScratch, pixel, 0);
    float entry = winners.r;
    float exit = winners.g;
    int exitMember = int(winners.a);
    int entryMember = int(kNoMember);
#ifdef UNION
    // A union (no stencil test): an interval wherever a member was entered.
    if (entry < 0.0 || exit < 0.0) discard;
#endif
    if (entry < 0.0) {
        outDepths = vec2(-exit, exit);
    } else if (untagged(entry) < untagged(exit)) {
        outDepths = vec2(-entry, exit);
        entryMember = int(winners.b);
    } else {
        discard;
    }
    imageStore(uIds, ivec3(pixel, uIdsLayer), uvec4(uint(entryMember) | uint(exitMember) << kMemberBits));
}
