// The plain path (PlainPass.h): a frame whose tree is a union of leaves,
// every ray starting outside all of them, drawn as depth-tested geometry
// straight into the G-buffer, with no peel, evaluator or normal pass.
//
// Vertex stage surface.vert with FACE_NORMAL and GROUP_MEMBERS: each draw
// is one leaf, numbered by its base instance, so vMember is the tree leaf.
// Only front faces are drawn (culling): from outside, a union's first
// surface is the nearest entry into any leaf.
//
// The nearest pass writes, as its depth, the order key of the fragment's
// tagged depth (peel.frag's GROUP uses the same key), so the depth test
// keeps exactly the nearest tagged depth, and among equal ones the lowest
// leaf (leaves are drawn in ascending order, the test is strict). TIE: the
// leaves that can come within the tolerance of another once more, each
// fragment within a quarter of the coincidence tolerance of the nearest
// (a copy of the nearest pass's depths) taking part with its leaf as the
// depth: the lowest such leaf wins, with its own surface, as the
// evaluator's rule for one face shared by several leaves names it
// (evaluate.frag, "the surface shown").
//
// Outputs: evaluate.frag's (tagged depth, leaf code) and normal.frag's
// (outward face normal, packed base colour) at once.
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit
layout(location = 2) flat in float vMember;     // the tree leaf

layout(location = 0) out float outDepth;
layout(location = 1) out int outLeaf;
layout(location = 2) out vec4 outNormal;

// Per tree leaf, its packed base colours (ShadePass::baseColors): x its own surface.
layout(std430, binding = kBufferPlainColors) readonly buffer BaseColors {
    vec2 baseColors[];
};

#ifdef TIE
layout(binding = kTexturePlainNearest) uniform sampler2D uNearest;  // the nearest pass's tagged depths
layout(location = kPlainTieTolerance) uniform float uTieTolerance;
#else
layout(location = kPlainKeyBase) uniform uint uKeyBase;  // bits of a depth before every fragment's

// As peel.frag's orderKey: the tagged depth's bits from uKeyBase's on, as a
// normal float in [0, 1) that orders exactly as the tagged depths do.
float orderKey(float tagged) {
    uint bits = floatBitsToUint(tagged);
    uint offset = bits > uKeyBase ? min(bits - uKeyBase, 0x3f000000u) : 0u;
    return uintBitsToFloat(offset + 0x00800000u);
}
#endif

void main() {
    float t = taggedDepth(vViewDepth, gl_FrontFacing);
    int leaf = int(vMember);
#ifdef TIE
    float nearest = texelFetch(uNearest, ivec2(gl_FragCoord.xy), 0).r;
    if (untagged(t) > untagged(nearest) + uTieTolerance) discard;
    // Leaves number fewer than 2^24 - 1: the key is exact and below 1.
    gl_FragDepth = (vMember + 1.0) / 16777216.0;
#else
    gl_FragDepth = orderKey(t);
#endif
    outDepth = t;
    outLeaf = leafCode(leaf, false);
    outNormal = vec4(vFaceNormal, baseColors[leaf].x);
}
