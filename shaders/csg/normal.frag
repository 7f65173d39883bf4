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
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int code = texelFetch(uResultLeaf, pixel, 0).r;
    if (leafOfCode(code) != uLeaf) discard;
    float result = texelFetch(uResultDepth, pixel, 0).r;
    float t = taggedDepth(surfaceDepth(), gl_FrontFacing);
    if (isExit(t) != isExit(result)) discard;
    // The same vertex stage as the peel pass; its viewport is the frame's
    // where the peel pass's was one tile's. A few ulps of slack cover the
    // rounding that an offset viewport or another fragment shader may bring.
    if (abs(t - result) > 1.0e-6 * result) discard;
    bool cut = flipOfCode(code);
    writeSurface(cut ? -vFaceNormal : vFaceNormal, cut ? uBaseColor.y : uBaseColor.x);
}
#endif
