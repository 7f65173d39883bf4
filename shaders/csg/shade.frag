// Deferred shading of the evaluated result (fullscreen, whole frame).
//
// Colour: the base colour the normal pass stored in the normal's w (the
// leaf's color() where it has one, else the scheme's face colour, or its
// cut-face colour where the leaf acts subtracted: ShadePass::baseColors).
// Light (light.glsl): strata's Lambert from a light beside the eye plus
// ambient, or with OPENSCAD_LIGHT OpenSCAD's preview light. With OUTLINE a
// Sobel filter on the normal buffer darkens creases and silhouettes (the look
// of the original image-space CSG papers). Empty pixels get the scheme's
// background, opaque.
#include "csg/interface.glsl"
#include "csg/light.glsl"

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

// World-space outward normal in xyz; w the packed base colour
// (ShadePass::packBaseColor), 0 on a miss. Nearest, clamped to the edge.
layout(binding = kTextureNormal) uniform sampler2D uNormal;

layout(location = kShadeBackground) uniform vec4 uBackground;

// The normal (dx, dy) pixels away, the edge pixel's beyond the frame. The
// sampler's offset and clamp cost llvmpipe less than clamping the
// coordinates for texelFetch.
#define NORMAL_AT(dx, dy) textureOffset(uNormal, vUv, ivec2(dx, dy)).xyz

void main() {
    vec4 centre = texelFetch(uNormal, ivec2(gl_FragCoord.xy), 0);
    if (centre.w == 0.0) {
        outColor = vec4(uBackground.rgb, 1.0);
        return;
    }
    vec3 base = unpackBaseColor(centre.w);

    vec3 color = lightSurface(base, centre.xyz);

#ifdef OUTLINE
    // Sobel on the normals: |G| is about 4 |dn| across a sharp crease, so
    // creases sharper than ~30 degrees (|dn| > 0.5) and silhouettes (|dn| = 1
    // against the empty 0) get the outline; a 32-gon's facets do not.
    vec3 lowLeft = NORMAL_AT(-1, -1), lowRight = NORMAL_AT(1, -1);
    vec3 highLeft = NORMAL_AT(-1, 1), highRight = NORMAL_AT(1, 1);
    vec3 gx = (lowRight + 2.0 * NORMAL_AT(1, 0) + highRight) - (lowLeft + 2.0 * NORMAL_AT(-1, 0) + highLeft);
    vec3 gy = (highLeft + 2.0 * NORMAL_AT(0, 1) + highRight) - (lowLeft + 2.0 * NORMAL_AT(0, -1) + lowRight);
    float edge = smoothstep(1.6, 2.6, sqrt(dot(gx, gx) + dot(gy, gy)));
    color = mix(color, color * 0.3, edge);
#endif
    outColor = vec4(color, 1.0);
}
