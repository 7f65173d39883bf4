// The evaluate pass's geometry: one quad per run of kBlock x kBlock blocks of
// the tile that share a tree to walk, instanced, carrying the blocks' data
// to their fragments (csg/blocks.glsl). Blocks whose result is constant (no
// operand the result can show meets them) are not drawn at all, and each draw
// takes the blocks of one size class, so each runs the cheapest form of
// evaluate.frag that holds it. The viewport is the tile.

#define EVALUATE_VERTEX
#include "csg/blocks.glsl"

// Runs of blocks to draw, this draw's from uFirstBlock on: x the first
// block's number (row-major in the tile), y how many blocks along its row
// share its record. One quad covers the run.
layout(std430, binding = kBufferDrawnBlocks) readonly buffer DrawnBlocks {
    uvec2 drawnBlocks[];
};

layout(location = kEvaluateFirstBlock) uniform int uFirstBlock;
layout(location = kEvaluateTileSize) uniform ivec2 uTileSize;  // pixels
layout(location = kEvaluateBlocksX) uniform int uBlocksX;      // blocks per row of the tile

void main() {
    uvec2 run = drawnBlocks[uFirstBlock + gl_InstanceID];
    uint block = run.x;
    // Two triangles: corners (0,0) (1,0) (0,1) and (1,0) (1,1) (0,1).
    int v = gl_VertexID;
    ivec2 corner = ivec2(v == 1 || v == 3 || v == 4 ? 1 : 0, v == 2 || v == 4 || v == 5 ? 1 : 0);
    ivec2 origin = ivec2(int(block) % uBlocksX, int(block) / uBlocksX) * kBlock;
    vec2 p = vec2(min(origin + corner * ivec2(kBlock * int(run.y), kBlock), uTileSize));
    gl_Position = vec4(p / vec2(uTileSize) * 2.0 - 1.0, 0.0, 1.0);
    vRecord = blocks[block];
#ifdef REGISTER_FORM
    // The register form's slots (unused ones are never read): the layer in
    // the low kSlotLayerBits bits, the operand's bit above.
    uvec4 slot;
#define SLOT(layers, leaves, c, i)                                  \
    slot = blockOperands[vRecord.x + min(uint(i), vRecord.y - 1u)]; \
    layers[c] = slot.x | (slot.y << kSlotLayerBits);                \
    leaves[c] = slot.z;
    SLOT(vLayerA, vLeafA, 0, 0) SLOT(vLayerA, vLeafA, 1, 1) SLOT(vLayerA, vLeafA, 2, 2) SLOT(vLayerA, vLeafA, 3, 3)
#if MAX_LIVE > 4
    SLOT(vLayerB, vLeafB, 0, 4) SLOT(vLayerB, vLeafB, 1, 5) SLOT(vLayerB, vLeafB, 2, 6) SLOT(vLayerB, vLeafB, 3, 7)
    vTableLow = blockNodes[vRecord.z];
    vTableHigh = blockNodes[vRecord.z + 1u];
#endif
#if MAX_LIVE > 8
    SLOT(vLayerC, vLeafC, 0, 8) SLOT(vLayerC, vLeafC, 1, 9) SLOT(vLayerC, vLeafC, 2, 10) SLOT(vLayerC, vLeafC, 3, 11)
    SLOT(vLayerD, vLeafD, 0, 12) SLOT(vLayerD, vLeafD, 1, 13) SLOT(vLayerD, vLeafD, 2, 14) SLOT(vLayerD, vLeafD, 3, 15)
#endif
#endif
}
