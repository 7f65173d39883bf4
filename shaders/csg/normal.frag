// Normal recovery: the operands are drawn once more over the pixels the
// evaluator wrote (vertex stage surface.vert, as the peel pass), and the
// fragment that is the visible surface the evaluator chose (same leaf, same
// facing, same tagged depth) writes its triangle's world-space face normal
// (a flat varying, surface.vert's FACE_NORMAL),
// flipped where the leaf acts as a subtracted operand: the outward normal
// of the result. Its w is the surface's base colour for the shade pass, a
// uniform of this draw. The stencil holds the evaluator's marks
// (FrameTargets.h) and this pass only tests them: testing before the shader
// runs changes no result, and spares the shader on the other leaves' pixels
// (llvmpipe tests late, after the shader, in a shader that may discard,
// unless told otherwise). Two variants: TRUST_MARKS (below) for convex
// leaves whose marks are their own, and the checking one.
//
// LIT (frames without the outline, which alone needs a pixel's
// neighbours): the fragment writes the lit colour into the image instead,
// as the shade pass would from the same normal and base colour
// (light.glsl), and the frame needs no shade pass.
layout(early_fragment_tests) in;

#include "csg/interface.glsl"
#include "csg/surface.glsl"

#include "csg/surface-depth.glsl"
layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit
#ifdef LIT
#include "csg/light.glsl"
layout(location = 0) out vec4 outColor;
#else
layout(location = 0) out vec4 outNormal;
#endif

layout(binding = kTextureResultDepth) uniform sampler2D uResultDepth;  // tagged depth, +inf on a miss
layout(binding = kTextureResultLeaf) uniform isampler2D uResultLeaf;   // leafCode (interface.glsl)

layout(location = kNormalLeaf) uniform int uLeaf;  // the leaf being drawn
// The leaf's packed base colours (ShadePass::baseColors): x its own surface, y cut.
layout(location = kNormalBaseColor) uniform vec2 uBaseColor;

// The visible surface: its outward normal and packed base colour, for the
// shade pass, or (LIT) lit.
void writeSurface(vec3 normal, float baseColor) {
#ifdef LIT
    outColor = vec4(lightSurface(unpackBaseColor(baseColor), normal), 1.0);
#else
    outNormal = vec4(normal, baseColor);
#endif
}

#ifdef TRUST_MARKS
// A convex leaf whose marks no other leaf shares in its rectangle
// (NormalPass.cpp: marksOwnedInRect): the stencil test this draw passes
// already says that the pixel shows this leaf, this facing and this flip,
// and a convex leaf has one fragment of each facing on a ray, so the checks
// below could only agree. The draw's flip is a uniform.
layout(location = kNormalFlip) uniform int uFlip;

void main() {
    bool cut = uFlip != 0;
    writeSurface(cut ? -vFaceNormal : vFaceNormal, cut ? uBaseColor.y : uBaseColor.x);
}
#else
// 1 where the leaf is convex: it has one fragment of each facing on a ray,
// so the leaf and the facing name the visible surface's fragment.
layout(location = kNormalConvex) uniform int uConvex;
// Where the peel drew this tile through a viewport offset from the frame's
// (NormalPass.cpp): how far, in the depth's change across the pixel, the
// depth this pass computes may lie from the peel's; 0 where the two
// viewports are one.
layout(location = kNormalSlack) uniform float uSlack;

void main() {
    // The depth, and how much it changes across the pixel, before any
    // fragment leaves (derivatives need the whole quad).
    float depth = surfaceDepth();
    float across = fwidth(depth);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int code = texelFetch(uResultLeaf, pixel, 0).r;
    if (leafOfCode(code) != uLeaf) discard;
    float result = texelFetch(uResultDepth, pixel, 0).r;
    float t = taggedDepth(depth, gl_FrontFacing);
    if (isExit(t) != isExit(result)) discard;
    // Else the depth names it among the leaf's fragments of this facing:
    // the vertex stage is the peel pass's, so the depth is the same to a
    // few ulps (another fragment shader may round a little differently).
    // Where the peel drew this tile through an offset viewport, the two
    // round window positions a little apart, which moves the depth of a
    // face seen nearly edge on, fast-changing across a pixel, by far more.
    if (uConvex == 0 && abs(t - result) > max(1.0e-6 * result, uSlack * across)) discard;
    bool cut = flipOfCode(code);
    writeSurface(cut ? -vFaceNormal : vFaceNormal, cut ? uBaseColor.y : uBaseColor.x);
}
#endif
