// Leaves whose color() is translucent (alpha a < 1), as OpenSCAD's preview
// draws them (AlphaPass.h). The shade pass has written every pixel's lit
// colour F opaque; where the visible surface is this leaf's (its leaf code
// is one of uCodes), this draw blends over F what OpenSCAD's preview shows
// behind the surface, U, with alpha 1 - a: the image becomes a F + (1 - a) U,
// which is U with F blended over it at alpha a.
//
// Without REAR (a fullscreen triangle scissored to the leaf's rectangle):
// U is the scheme's background.
// REAR (surface.vert with FACE_NORMAL; the leaf's back faces, the nearest on
// each pixel only, by a depth pre-pass): U is the leaf's back face, lit as
// shade.frag lights a surface facing the eye, over the background at alpha a.
#include "csg/interface.glsl"
#ifdef REAR
#include "csg/light.glsl"

layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit (surface.vert's FACE_NORMAL)
#endif
layout(location = 0) out vec4 outColor;

layout(binding = kTextureResultLeaf) uniform isampler2D uResultLeaf;  // leafCode (interface.glsl)

layout(location = kAlphaCodes) uniform ivec2 uCodes;
layout(location = kAlphaColor) uniform vec4 uColor;  // straight alpha
layout(location = kAlphaBackground) uniform vec3 uBackground;

void main() {
    int code = texelFetch(uResultLeaf, ivec2(gl_FragCoord.xy), 0).r;
    if (code != uCodes.x && code != uCodes.y) discard;
    vec3 behind = uBackground;
#ifdef REAR
    // A back face's outward normal points away from the eye; OpenSCAD lights
    // both sides of a face alike, so it is lit here as the face seen from inside.
    behind = mix(uBackground, lightSurface(uColor.rgb, -vFaceNormal), uColor.a);
#endif
    outColor = vec4(behind, 1.0 - uColor.a);
}
