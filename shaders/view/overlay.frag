// The overlay's depth test is against the frame's own AOVs (the depth and
// leaf images read back from strata's frame), not a depth buffer: strata's
// image has no rasterized depth to test against.
//   axes and ticks  hidden where they lie behind the visible surface;
//   edges           drawn where their own leaf is the visible surface, at
//                   the same depth, so only the result's visible surfaces
//                   show their triangles; and, at a silhouette, on the
//                   pixels just outside it (nothing, or something farther,
//                   seen there) when a neighbouring pixel shows the edge's
//                   surface at its depth, so a silhouette's edge is drawn
//                   whole and not only the half of it inside the surface.
in float viewDepth;
in vec3 color;
flat in float lineKind;

layout(location = 0) out vec4 fragColor;

uniform sampler2D sceneDepth;   // view depth of the visible surface, +inf where none; row 0 at the top
uniform isampler2D sceneLeaf;   // the visible surface's tree leaf, -1 where none
uniform sampler2D sceneColor;   // the image the lines are drawn over, rows as sceneDepth
uniform bool screenSpace;       // the corner cross: on top of everything
uniform int viewHeight;
uniform vec2 originPixel;       // where the world origin falls, for the dashes
// One pixel's width in world units at view depth z: footprint.x + footprint.y * z.
uniform vec2 footprint;

const float kSolid = -1.0;
const float kDashed = -2.0;
// Edges within this part of their depth (and a few pixels' worth for slanted
// faces) of the visible surface lie on it.
const float kEdgeDepthTolerance = 2e-3;
const float kEdgePixels = 4.0;
// OpenSCAD's glLineStipple(3, 0xAAAA): 3 pixels drawn, 3 left out.
const float kDash = 3.0;

void main() {
    if (!screenSpace) {
        ivec2 texel = ivec2(int(gl_FragCoord.x), viewHeight - 1 - int(gl_FragCoord.y));
        float surface = texelFetch(sceneDepth, texel, 0).r;
        float pixel = footprint.x + footprint.y * max(viewDepth, 0.0);
        if (lineKind >= 0.0) {
            int leaf = int(lineKind + 0.5);
            if (texelFetch(sceneLeaf, texel, 0).r == leaf &&
                abs(viewDepth - surface) <= kEdgeDepthTolerance * abs(surface) + kEdgePixels * pixel) {
                // Blended as (1, alpha): half-way from the surface's colour to white,
                // as OpenSCAD's preview lightens a face's colour for its edges.
                fragColor = vec4(0.5, 0.5, 0.5, 0.5);
                return;
            }
            // Hidden behind a nearer surface: not a silhouette.
            if (!(surface > viewDepth)) discard;
            // Just outside a silhouette: the colour the edge has on the
            // neighbouring pixel that shows its surface (alpha 0: replaces).
            ivec2 last = textureSize(sceneLeaf, 0) - 1;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec2 n = clamp(texel + ivec2(dx, dy), ivec2(0), last);
                    if (texelFetch(sceneLeaf, n, 0).r != leaf) continue;
                    float d = texelFetch(sceneDepth, n, 0).r;
                    if (abs(viewDepth - d) > kEdgeDepthTolerance * abs(d) + (kEdgePixels + 1.5) * pixel) continue;
                    fragColor = vec4(0.5 + 0.5 * texelFetch(sceneColor, n, 0).rgb, 0.0);
                    return;
                }
            discard;
        }
        // Lines lying on a surface stay visible, as OpenSCAD's axes drawn before the model do.
        if (viewDepth > surface + 1e-4 * abs(surface) + pixel) discard;
        if (lineKind == kDashed && mod(floor(distance(gl_FragCoord.xy, originPixel) / kDash), 2.0) == 1.0) discard;
    }
    fragColor = vec4(color, 1.0);
}
