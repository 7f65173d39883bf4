// A fragment's view depth, in the passes whose fragments name a surface by
// it (peel, normal, plain). On a plane that two leaves share: where its ray
// through the pixel centre meets the plane (surface.vert), so that faces of
// one plane give one depth whatever their leaf and triangles. Elsewhere,
// and where the plane's is ill-conditioned (seen nearly edge on), the
// interpolated depth.
#ifndef STRATA_SURFACE_DEPTH
#define STRATA_SURFACE_DEPTH

layout(location = 0) in float vViewDepth;  // interpolated (invariant)
layout(location = 3) flat in vec3 vDepthNumerator;
layout(location = 4) flat in vec4 vDepthDenominator;  // w: 1 on a shared plane

float surfaceDepth() {
    if (vDepthDenominator.w == 0.0) return vViewDepth;
    vec2 p = gl_FragCoord.xy;
    precise float numerator = vDepthNumerator.x + p.x * vDepthNumerator.y + p.y * vDepthNumerator.z;
    precise float denominator = vDepthDenominator.x + p.x * vDepthDenominator.y + p.y * vDepthDenominator.z;
    precise float s = numerator / denominator;
    // The two agree to rounding on a plane seen at any usable angle; a
    // thousandth of the depth apart, the plane's is not to be trusted.
    return abs(s - vViewDepth) <= 1.0e-3 * abs(vViewDepth) ? s : vViewDepth;
}

#endif
