// The plain path (PlainPass.h): a frame whose tree is a union of leaves,
// every ray starting outside all of them, drawn as depth-tested geometry
// straight into the G-buffer, with no peel, evaluator or normal pass.
//
// Vertex stage surface.vert with FACE_NORMAL and GROUP_MEMBERS: each draw
// is one leaf, numbered by its base instance, so vMember is the tree leaf.
// Only front faces are drawn (culling): from outside, a union's first
// surface is the nearest entry into any leaf.
//
// Depth is reversed (surface.vert's REVERSED_DEPTH, a 32-bit float depth
// buffer with clip control zero to one): the window depth is near / depth in
// perspective, so every depth keeps a float's relative precision. The
// nearest pass keeps the nearest surface (depth test GREATER), the lowest
// leaf among exactly equal ones (leaves are drawn in ascending order, the
// test is strict). TIE: the leaves that can come within the tolerance of
// another once more, in descending order, pulled toward the eye by more than
// a quarter of the tolerance and tested GEQUAL against the nearest pass's
// depths with no depth writes, so that the test, run before the shader,
// lets through every fragment that may tie and few others; the shader then
// keeps exactly those within a quarter of the tolerance of the nearest (a
// copy of the nearest pass's depths). Each writes its own surface, and the
// last, the lowest leaf there, stays: the surface the evaluator's rule names
// for a face that several leaves share (evaluate.frag, "the surface shown").
//
// LIT (frames without the outline, which alone needs a pixel's neighbours):
// each fragment also writes its lit colour into the image, as the shade pass
// would from the same normal and base colour (light.glsl), so the frame needs
// no shade pass. The last fragment written on a pixel writes all four.
//
// SHOWN (a frame only shown, nothing read back: FrameTargets'
// plainShownTarget and plainShownLitTarget): only what the image needs, at
// 0 the lit colour (LIT) or the normal and base colour (for the shade
// pass's outline), at 1 the depth and at 2 the leaf code, each drawn only
// where a pass reads it after (the tie pass the depth; the passes that
// blend translucent and '%' leaves both); no stencil marks when lit.
//
#include "csg/interface.glsl"
#include "csg/surface.glsl"

#include "csg/surface-depth.glsl"
layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit
layout(location = 2) flat in float vMember;     // the tree leaf

#ifdef LIT
#include "csg/light.glsl"
#endif
#ifdef SHOWN
#ifdef LIT
layout(location = 0) out vec4 outColor;
#else
layout(location = 0) out vec4 outNormal;
#endif
layout(location = 1) out float outDepth;
layout(location = 2) out int outLeaf;
#else
layout(location = 0) out float outDepth;
layout(location = 1) out int outLeaf;
layout(location = 2) out vec4 outNormal;
#ifdef LIT
layout(location = 3) out vec4 outColor;
#endif
#endif

// Per tree leaf, its packed base colours (ShadePass::baseColors): x its own surface.
layout(std430, binding = kBufferPlainColors) readonly buffer BaseColors {
    vec2 baseColors[];
};

#ifdef TIE
layout(early_fragment_tests) in;

layout(binding = kTexturePlainNearest) uniform sampler2D uNearest;  // the nearest pass's tagged depths
layout(location = kPlainTieTolerance) uniform float uTieTolerance;
#endif

void main() {
    float t = taggedDepth(surfaceDepth(), gl_FrontFacing);
#ifdef TIE
    float nearest = texelFetch(uNearest, ivec2(gl_FragCoord.xy), 0).r;
    if (untagged(t) > untagged(nearest) + uTieTolerance) discard;
#endif
    int leaf = int(vMember);
    outDepth = t;
    outLeaf = leafCode(leaf, false);
#ifdef LIT
    outColor = vec4(lightSurface(unpackBaseColor(baseColors[leaf].x), vFaceNormal), 1.0);
#endif
#if !defined(SHOWN) || !defined(LIT)
    outNormal = vec4(vFaceNormal, baseColors[leaf].x);
#endif
}
