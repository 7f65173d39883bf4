// '%' (background) and '#' (highlight) leaves, drawn translucent over the
// shaded result: front faces only, alpha-blended, hidden where they lie
// behind the result's visible surface.
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
layout(location = 1) flat in vec3 vFaceNormal;  // outward, unit (surface.vert's FACE_NORMAL)
layout(location = 0) out vec4 outColor;

layout(binding = kTextureResultDepth) uniform sampler2D uResultDepth;  // tagged view depth, +inf on a miss

layout(location = kTranslucentColor) uniform vec4 uColor;    // straight alpha
layout(location = kTranslucentToLight) uniform vec3 uToLight;  // unit, world space

void main() {
    float result = untagged(texelFetch(uResultDepth, ivec2(gl_FragCoord.xy), 0).r);
    if (vViewDepth > result * (1.0 + 1.0e-5)) discard;
    float light = 0.45 + 0.55 * max(dot(vFaceNormal, uToLight), 0.0);
    outColor = vec4(uColor.rgb * light, uColor.a);
}
