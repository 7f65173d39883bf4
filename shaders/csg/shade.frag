// Deferred shading of the evaluated result (fullscreen, whole frame).
//
// Colour: the leaf's color() where it has one, else the scheme's face colour,
// or its cut-face colour where the leaf acts subtracted. Light: Lambert from a
// light beside the eye, plus ambient. A Sobel filter on the normal buffer
// darkens creases and silhouettes (the look of the original image-space CSG
// papers). Empty pixels get the scheme's background, opaque.

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

layout(binding = 0) uniform sampler2D uResultDepth;  // tagged view depth, +inf on a miss
layout(binding = 1) uniform isampler2D uResultLeaf;  // leaf * 2 + flip, -1 on a miss
layout(binding = 2) uniform sampler2D uNormal;       // world-space outward normal, 0 on a miss

// Per tree leaf: its color() in rgb, a < 0 when it has none.
layout(std430, binding = 0) readonly buffer LeafColors {
    vec4 leafColors[];
};

layout(location = 0) uniform vec4 uBackground;
layout(location = 1) uniform vec4 uFaceFront;
layout(location = 2) uniform vec4 uFaceBack;
layout(location = 3) uniform vec3 uForward;
layout(location = 4) uniform vec3 uRight;
layout(location = 5) uniform vec3 uUp;
layout(location = 6) uniform vec2 uHalfExtent;   // tan(fov/2) * (aspect, 1): perspective ray slopes
layout(location = 7) uniform int uOrthographic;
layout(location = 8) uniform ivec2 uSize;

const float kAmbient = 0.35;
const float kDiffuse = 0.65;

vec3 normalAt(ivec2 p) {
    return texelFetch(uNormal, clamp(p, ivec2(0), uSize - 1), 0).xyz;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int code = texelFetch(uResultLeaf, pixel, 0).r;
    if (code < 0) {
        outColor = vec4(uBackground.rgb, 1.0);
        return;
    }
    int leaf = code >> 1;
    bool cut = (code & 1) != 0;
    vec4 own = leafColors[leaf];
    vec3 base = own.a >= 0.0 ? own.rgb : (cut ? uFaceBack.rgb : uFaceFront.rgb);

    // The contract's ray through this pixel centre (GL rows count from the bottom).
    vec2 ndc = 2.0 * gl_FragCoord.xy / vec2(uSize) - 1.0;
    vec3 rayDir = uOrthographic != 0
        ? uForward
        : normalize(uForward + ndc.x * uHalfExtent.x * uRight + ndc.y * uHalfExtent.y * uUp);
    // The light sits a little above and left of the eye, so faces square to
    // the view are not all equally bright.
    vec3 toLight = normalize(-rayDir + 0.25 * (uUp - uRight));
    vec3 n = texelFetch(uNormal, pixel, 0).xyz;
    float lambert = max(dot(n, toLight), 0.0);
    vec3 color = base * (kAmbient + kDiffuse * lambert);

    // Sobel on the normals: |G| is about 4 |dn| across a sharp crease, so
    // creases sharper than ~30 degrees (|dn| > 0.5) and silhouettes (|dn| = 1
    // against the empty 0) get the outline; a 32-gon's facets do not.
    vec3 gx = vec3(0.0), gy = vec3(0.0);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            vec3 s = normalAt(pixel + ivec2(dx, dy));
            float wx = float(dx) * (dy == 0 ? 2.0 : 1.0);
            float wy = float(dy) * (dx == 0 ? 2.0 : 1.0);
            gx += wx * s;
            gy += wy * s;
        }
    }
    float edge = smoothstep(1.6, 2.6, sqrt(dot(gx, gx) + dot(gy, gy)));
    color = mix(color, color * 0.3, edge);
    outColor = vec4(color, 1.0);
}
