// The lights, one definition for every pass that lights a surface
// (shade.frag, plain.frag, alpha.frag), chosen by RenderSettings::lighting:
// the uniforms each needs (interface.glsl's kLight*, which
// ShadePass::setLight sets) and lightSurface, which lights a fragment.
//
// strata's (lit): ambient 0.35 plus 0.65 times Lambert, from a light a
// little above and left of the eye, so faces square to the view are not all
// equally bright. It follows each pixel's view ray.
//
// OpenSCAD's preview (litAsOpenScad, programs built with OPENSCAD_LIGHT):
// 0.2 plus |n . l| for one light l, the unit direction (-1, 1, 1) in view
// space, which the caller turns into world space once a frame. No ray: every
// pixel of a flat face gets one colour, and both sides of a face are lit
// alike (OpenSCAD's shaders take the absolute value; its fixed-function path
// has a second light opposite the first, which comes to the same).
#ifndef STRATA_LIGHT
#define STRATA_LIGHT

#ifdef OPENSCAD_LIGHT
layout(location = kLightToLight) uniform vec3 uToLight;  // unit, world space
#else
layout(location = kSurfaceForward) uniform vec3 uForward;  // the unit view direction, as surface.vert's
layout(location = kLightRight) uniform vec3 uRight;
layout(location = kLightUp) uniform vec3 uUp;
layout(location = kLightHalfExtent) uniform vec2 uHalfExtent;  // tan(fov/2) * (aspect, 1): perspective ray slopes
layout(location = kLightOrthographic) uniform int uOrthographic;
layout(location = kLightSize) uniform ivec2 uSize;
#endif

const float kAmbient = 0.35;
const float kDiffuse = 0.65;

// The contract's ray through the pixel centre `fragCoord` (gl_FragCoord.xy:
// GL rows count from the bottom) of a frame of `size` pixels.
vec3 viewRay(vec2 fragCoord, ivec2 size, vec3 forward, vec3 right, vec3 up, vec2 halfExtent, bool orthographic) {
    vec2 ndc = 2.0 * fragCoord / vec2(size) - 1.0;
    return orthographic ? forward : normalize(forward + ndc.x * halfExtent.x * right + ndc.y * halfExtent.y * up);
}

// `base` lit on a surface of unit normal `normal` seen along `rayDir`.
vec3 lit(vec3 base, vec3 normal, vec3 rayDir, vec3 right, vec3 up) {
    vec3 toLight = normalize(-rayDir + 0.25 * (up - right));
    float lambert = max(dot(normal, toLight), 0.0);
    return base * (kAmbient + kDiffuse * lambert);
}

// The 8-bit RGB of a base colour as the G-buffer packs it
// (ShadePass::packBaseColor: 1 + r * 65536 + g * 256 + b, exact in a float).
vec3 unpackBaseColor(float packedColor) {
    uint bits = uint(packedColor) - 1u;
    return vec3((uvec3(bits) >> uvec3(16u, 8u, 0u)) & 255u) / 255.0;
}

// `base` lit as OpenSCAD's preview lights it, `toLight` the light's unit
// direction in world space (ShadePass::openScadToLight).
vec3 litAsOpenScad(vec3 base, vec3 normal, vec3 toLight) {
    return base * (0.2 + abs(dot(normal, toLight)));
}

// `base` on a surface of unit normal `normal` at this fragment, in the
// program's light.
vec3 lightSurface(vec3 base, vec3 normal) {
#ifdef OPENSCAD_LIGHT
    return litAsOpenScad(base, normal, uToLight);
#else
    vec3 rayDir = viewRay(gl_FragCoord.xy, uSize, uForward, uRight, uUp, uHalfExtent, uOrthographic != 0);
    return lit(base, normal, rayDir, uRight, uUp);
#endif
}

#endif
