// '%' (background) and '#' (highlight) leaves, drawn translucent over the
// shaded result: front faces only, alpha-blended, hidden where they lie
// behind the result's visible surface.
//
// WINDOW_DEPTH (a plain frame that is only shown, PlainPass.h): the
// visible surface's depth is read from the plain pass's own depth image,
// the reversed window depth of surface.vert's REVERSED_DEPTH, and turned
// back into a view depth: near / w in perspective (uFromWindow (near, 0,
// 0)), far - w (far - near) orthographic ((0, far, far - near)). 0 is the
// cleared value, a miss. Else the evaluator's depth image, +inf on a miss.
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit (surface.vert's FACE_NORMAL)
layout(location = 0) out vec4 outColor;

#ifdef WINDOW_DEPTH
layout(binding = kTextureWindowDepth) uniform sampler2D uWindowDepth;
layout(location = kTranslucentFromWindow) uniform vec3 uFromWindow;

float resultDepth() {
    float w = texelFetch(uWindowDepth, ivec2(gl_FragCoord.xy), 0).r;
    if (w <= 0.0) return kInfinity;
    return uFromWindow.z == 0.0 ? uFromWindow.x / w : uFromWindow.y - w * uFromWindow.z;
}
#else
layout(binding = kTextureResultDepth) uniform sampler2D uResultDepth;  // tagged view depth, +inf on a miss

float resultDepth() {
    return untagged(texelFetch(uResultDepth, ivec2(gl_FragCoord.xy), 0).r);
}
#endif

layout(location = kTranslucentColor) uniform vec4 uColor;    // straight alpha
layout(location = kTranslucentToLight) uniform vec3 uToLight;  // unit, world space

void main() {
    float result = resultDepth();
    if (vViewDepth > result * (1.0 + 1.0e-5)) discard;
    float light = 0.45 + 0.55 * max(dot(vFaceNormal, uToLight), 0.0);
    outColor = vec4(uColor.rgb * light, uColor.a);
}
