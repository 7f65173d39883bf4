// strata's light, one definition for every pass that lights a surface
// (shade.frag, alpha.frag): ambient 0.35 plus 0.65 times Lambert, from a
// light a little above and left of the eye, so faces square to the view are
// not all equally bright.
#ifndef STRATA_LIGHT
#define STRATA_LIGHT

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

#endif
