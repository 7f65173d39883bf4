// The overlay's depth test is against the frame's own AOVs (the depth and
// leaf images read back from strata's frame), not a depth buffer: strata's
// image has no rasterized depth to test against.
//   axes and ticks  hidden where they lie behind the visible surface;
//   edges           drawn only where their own leaf is the visible surface,
//                   at the same depth, so only the result's visible surfaces
//                   show their triangles.
in float viewDepth;
in vec3 color;
flat in float lineKind;

layout(location = 0) out vec4 fragColor;

uniform sampler2D sceneDepth;   // view depth of the visible surface, +inf where none; row 0 at the top
uniform isampler2D sceneLeaf;   // the visible surface's tree leaf, -1 where none
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
            if (texelFetch(sceneLeaf, texel, 0).r != int(lineKind + 0.5)) discard;
            if (abs(viewDepth - surface) > kEdgeDepthTolerance * abs(surface) + kEdgePixels * pixel) discard;
            // Blended as (1, alpha): half-way from the surface's colour to white,
            // as OpenSCAD's preview lightens a face's colour for its edges.
            fragColor = vec4(0.5, 0.5, 0.5, 0.5);
            return;
        }
        // Lines lying on a surface stay visible, as OpenSCAD's axes drawn before the model do.
        if (viewDepth > surface + 1e-4 * abs(surface) + pixel) discard;
        if (lineKind == kDashed && mod(floor(distance(gl_FragCoord.xy, originPixel) / kDash), 2.0) == 1.0) discard;
    }
    fragColor = vec4(color, 1.0);
}
