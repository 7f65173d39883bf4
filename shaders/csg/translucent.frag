// '%' (background) and '#' (highlight) leaves, drawn translucent over the
// shaded result: front faces only, alpha-blended, hidden where they lie
// behind the result's visible surface.
#include "csg/surface.glsl"

layout(location = 0) in float vViewDepth;
layout(location = 0) out vec4 outColor;

layout(binding = 0) uniform sampler2D uResultDepth;  // tagged view depth, +inf on a miss

layout(std430, binding = 2) readonly buffer FaceNormals {
    vec4 faceNormals[];
};

layout(location = 3) uniform vec4 uColor;         // straight alpha
layout(location = 4) uniform int uFirstTriangle;
layout(location = 5) uniform vec3 uToLight;       // unit, world space

void main() {
    float result = untagged(texelFetch(uResultDepth, ivec2(gl_FragCoord.xy), 0).r);
    if (vViewDepth > result * (1.0 + 1.0e-5)) discard;
    vec3 n = faceNormals[uFirstTriangle + gl_PrimitiveID].xyz;
    float light = 0.45 + 0.55 * max(dot(n, uToLight), 0.0);
    outColor = vec4(uColor.rgb * light, uColor.a);
}
