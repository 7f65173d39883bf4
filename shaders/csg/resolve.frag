// Fragment lists to peeled layers (PeelPass::peelThroughLists), fullscreen over one
// operand's rectangle in the tile.
//
// peel.frag's COLLECT pass appended every fragment's tagged depth to its
// pixel's list, in whatever order the rasterizer produced them. Layer l is
// made by the rule of dual depth peeling's pass l: of the depths strictly
// between layer l-1's near and far (layer 0: all), the nearest and the
// farthest. Equal depths collapse into one surface, as they do in a pass,
// so the layers equal the passes' bit for bit. No sort: a list holds at most
// eight depths, kept in two vectors, and each layer is a min and a max over
// them.
//
// Writes layers uFirstLayer .. uFirstLayer + uLayerCount - 1 where the pixel
// has them (the caller cleared them all before), and records the most
// layers any pixel has. A pixel whose list overflowed writes nothing but its
// count, and the caller peels the operand pass by pass instead.
// Counts are left at 0 for the next operand: the lists' region is the
// operand's rectangle, and this pass visits all of it.
// The loads below are written for lists of kCollectCapacity = 8 (PeelPass.cpp
// checks that).
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(binding = kImageFragmentCounts, r32ui) uniform uimage2D uFragmentCounts;
layout(binding = kImageFragments, r32f) uniform readonly image2DArray uFragments;
layout(binding = kImageLayers, rg32f) uniform writeonly image2DArray uLayers;

layout(std430, binding = kBufferResolveStats) buffer ResolveStats {
    uint mostLayers;
    uint overflowed;  // the most fragments of a pixel whose list overflowed, else 0
};

layout(location = kResolveFirstLayer) uniform int uFirstLayer;
layout(location = kResolveLayerCount) uniform int uLayerCount;  // at most 4

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint count = imageLoad(uFragmentCounts, pixel).r;
    if (count == 0u) return;
    imageStore(uFragmentCounts, pixel, uvec4(0u));
    if (count > uint(kCollectCapacity)) {
        atomicMax(overflowed, count);
        return;
    }
    // Unused entries hold +inf, which is never strictly below a far depth.
    vec4 low = vec4(kInfinity), high = vec4(kInfinity);
#define LOAD(v, c, i) \
    if (count > uint(i)) v[c] = imageLoad(uFragments, ivec3(pixel, i)).r;
    LOAD(low, 0, 0) LOAD(low, 1, 1) LOAD(low, 2, 2) LOAD(low, 3, 3)
    LOAD(high, 0, 4) LOAD(high, 1, 5) LOAD(high, 2, 6) LOAD(high, 3, 7)

    float near = -kInfinity, far = kInfinity;
    int layers = 0;
    for (int l = 0; l < uLayerCount; ++l) {
        bvec4 inLow = bvec4(uvec4(greaterThan(low, vec4(near))) & uvec4(lessThan(low, vec4(far))));
        bvec4 inHigh = bvec4(uvec4(greaterThan(high, vec4(near))) & uvec4(lessThan(high, vec4(far))));
        vec4 nearest = min(mix(vec4(kInfinity), low, inLow), mix(vec4(kInfinity), high, inHigh));
        vec4 farthest = max(mix(vec4(-kInfinity), low, inLow), mix(vec4(-kInfinity), high, inHigh));
        float layerNear = min(min(nearest.x, nearest.y), min(nearest.z, nearest.w));
        if (layerNear == kInfinity) break;
        near = layerNear;
        far = max(max(farthest.x, farthest.y), max(farthest.z, farthest.w));
        imageStore(uLayers, ivec3(pixel, uFirstLayer + l), vec4(-near, far, 0.0, 0.0));
        layers = l + 1;
    }
    atomicMax(mostLayers, uint(layers));
}
