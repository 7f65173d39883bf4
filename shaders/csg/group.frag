// A group of convex operands' blend to its peeled layer (PeelPass::peelGroup),
// fullscreen over the group's rectangle in the tile, stencil-tested: only
// pixels where every member's back face was counted run.
//
// The scratch layer holds (farthest entry, -nearest exit) of the members'
// tagged depths, -FLT_MAX where no member had that surface. The group's
// interval on the ray runs from that entry to that exit, and is written as a
// convex operand's layer would hold it: (-entry, exit); (-exit, exit) where no
// member had an entry (the ray starts inside every one); nothing (the layer
// stays cleared) where the entry does not lie before the exit. Depths are
// compared untagged, as the evaluator does: an entry and an exit at one depth
// leave the ray outside.
#include "csg/surface.glsl"

layout(early_fragment_tests) in;

layout(binding = 0) uniform sampler2DArray uLayers;
layout(location = 0) uniform int uScratchLayer;

layout(location = 0) out vec2 outDepths;

void main() {
    vec2 blend = texelFetch(uLayers, ivec3(gl_FragCoord.xy, uScratchLayer), 0).rg;
    float entry = blend.r;
    float exit = -blend.g;
    if (entry < -3.0e38) {
        outDepths = vec2(-exit, exit);
    } else if (untagged(entry) < untagged(exit)) {
        outDepths = vec2(-entry, exit);
    } else {
        discard;
    }
}
