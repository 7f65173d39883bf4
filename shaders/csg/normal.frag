// Normal recovery: the visible leaves are drawn once more (vertex stage
// surface.vert and the peel pass's viewport, so depths match the peeled ones
// bit for bit), and the fragment that is the
// visible surface the evaluator chose (same leaf, same facing, same tagged
// depth) writes its triangle's world-space face normal, flipped where the
// leaf acts as a subtracted operand: the outward normal of the result.
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
layout(location = 0) out vec4 outNormal;

layout(binding = 0) uniform sampler2D uResultDepth;   // tagged depth, +inf on a miss
layout(binding = 1) uniform isampler2D uResultLeaf;   // leaf * 2 + flip, -1 on a miss

// Per triangle of all leaves: xyz the outward unit face normal.
layout(std430, binding = 2) readonly buffer FaceNormals {
    vec4 faceNormals[];
};

layout(location = 3) uniform int uLeaf;           // the leaf being drawn
layout(location = 4) uniform int uFirstTriangle;  // its first triangle in FaceNormals
layout(location = 5) uniform ivec2 uTileOrigin;   // the target is one tile; the results are the frame's

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) + uTileOrigin;
    int code = texelFetch(uResultLeaf, pixel, 0).r;
    if (code < 0 || (code >> 1) != uLeaf) discard;
    float result = texelFetch(uResultDepth, pixel, 0).r;
    float t = taggedDepth(vViewDepth, gl_FrontFacing);
    if (isExit(t) != isExit(result)) discard;
    // This pass draws with the peel pass's viewport and vertex stage, so the
    // same fragment gives the same bits; a few ulps of slack cover a driver
    // that interpolates differently in another fragment shader.
    if (abs(t - result) > 1.0e-6 * result) discard;
    vec3 n = faceNormals[uFirstTriangle + gl_PrimitiveID].xyz;
    outNormal = vec4((code & 1) != 0 ? -n : n, 1.0);
}
