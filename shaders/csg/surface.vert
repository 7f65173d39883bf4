// Vertex stage of every pass that rasterizes the leaves (peel, normal,
// translucent). The peel and normal passes must compute bit-identical depths
// for one fragment, so both use this file and the depth is invariant.
//
// Inputs: world-space positions (float, location 0) and the face plane of
// the triangle that ends on the vertex (location 1, SceneBuffers.h: its unit
// normal n and offset n . P). GL takes a flat varying from a triangle's last
// vertex, and every triangle ends on a vertex of its own, so each fragment
// gets its own triangle's plane with no lookup by gl_PrimitiveID. With
// FACE_NORMAL (the normal, translucent and plain passes) n is handed on.
//
// A fragment's depth (surface-depth.glsl): the view depth s where its ray
// P = O + s D (kSurfaceOrigin, kSurfaceRay: affine in gl_FragCoord.xy) meets
// the plane, s = (w - n.O) / (n.D). The terms that do not depend on the
// pixel are worked out here, from the plane alone, so two triangles in one
// plane (bit-identical planes: FacePlanes) give one depth at a pixel, where
// interpolating each triangle's vertex depths rounds each its own way.
// Uniforms: the view-projection matrix, the eye and the unit view direction f.
//
// GROUP_MEMBERS (GroupPeel's passes: one multi-draw over a group's members,
// SceneBuffers::memberVertexArray): each draw's one instance carries the
// member's index in its group (attribute 2, per instance; draw m has base
// instance m), handed on flat.
//
// REVERSED_DEPTH (the plain path, PlainPass.h): the clip depth is
// x + y * depth + z * w of uReversedDepth, with the view depth and clip w:
// in perspective (near, 0, pull) gives the window depth near / depth (clip
// control zero to one), which keeps a float's relative precision at every
// depth; orthographic, (far / (far - near), -1 / (far - near), pull). Both
// put the near plane at 1, and `pull` moves every depth that much toward it. x, y and w are as in
// every other pass, so the same pixels are covered.
//
// LAYERED (the peel pass's batch of convex operands, one multi-draw with one
// draw per operand): each draw's triangles go to the array layer
// drawLayers[gl_DrawID] of a layered framebuffer.
#ifdef LAYERED
#extension GL_ARB_shader_draw_parameters : require
#extension GL_ARB_shader_viewport_layer_array : require
#endif
#include "csg/interface.glsl"

#ifdef LAYERED
layout(std430, binding = kBufferDrawLayers) readonly buffer DrawLayers {
    uint drawLayers[];
};
#endif

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aFacePlane;
#ifdef FACE_NORMAL
layout(location = 1) flat out vec3 vFaceNormal;
#endif
// s = (x + X y + Y z) / (x' + X y' + Y z') at gl_FragCoord (X, Y); w' = 0:
// a plane of one leaf alone (FacePlanes: offset kOwnPlane), whose
// fragments take the interpolated depth.
layout(location = 3) flat out vec3 vDepthNumerator;
layout(location = 4) flat out vec4 vDepthDenominator;
#ifdef GROUP_MEMBERS
layout(location = 2) in float aMember;
layout(location = 2) flat out float vMember;
#endif

layout(location = kSurfaceViewProjection) uniform mat4 uViewProjection;
layout(location = kSurfaceEye) uniform vec3 uEye;
layout(location = kSurfaceForward) uniform vec3 uForward;
#ifdef REVERSED_DEPTH
layout(location = kSurfaceReversedDepth) uniform vec3 uReversedDepth;
#endif
layout(location = kSurfaceOrigin) uniform vec3 uOrigin[3];
layout(location = kSurfaceRay) uniform vec3 uRay[3];

// Linear view depth dot(P - eye, f): an affine function of P, so perspective-
// correct interpolation gives its exact value at every fragment.
layout(location = 0) invariant out float vViewDepth;

void main() {
    vViewDepth = dot(aPosition - uEye, uForward);
    vec3 n = aFacePlane.xyz;
#ifdef FACE_NORMAL
    vFaceNormal = n;
#endif
    bool onSharedPlane = aFacePlane.w < kOwnPlane;
    vDepthNumerator = onSharedPlane ? vec3(aFacePlane.w - dot(n, uOrigin[0]), -dot(n, uOrigin[1]), -dot(n, uOrigin[2])) : vec3(0.0);
    vDepthDenominator = vec4(dot(n, uRay[0]), dot(n, uRay[1]), dot(n, uRay[2]), onSharedPlane ? 1.0 : 0.0);
#ifdef GROUP_MEMBERS
    vMember = aMember;
#endif
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
#ifdef REVERSED_DEPTH
    gl_Position.z = uReversedDepth.x + uReversedDepth.y * vViewDepth + uReversedDepth.z * gl_Position.w;
#endif
#ifdef LAYERED
    gl_Layer = int(drawLayers[gl_DrawIDARB]);
#endif
}
