// The evaluator's per-block data (EvaluatePass.cpp), read by evaluate.vert
// and evaluate.frag.
//
// The tile is cut into kBlock x kBlock pixel blocks. Block b's tree is the
// tree specialised to the operands whose screen rectangle meets it. In the
// array form blockOperands[blocks[b].x + i], i < blocks[b].y, are its
// literals, blockNodes[blocks[b].z + n], n < blocks[b].w, its inner nodes,
// node 0 the root; each other form has its own layout (its file says).
//
// Which form a variant of evaluate.frag compiles (EvaluatePass::programFor)
// is the one of FIRST_SURFACE_FORM, REGISTER_FORM, PRODUCT_FORM and
// ARRAY_FORM defined; the register and array forms also get MAX_LIVE, the
// most slots (register) or live operands and nodes (array) a block of the
// variant has.
#include "csg/interface.glsl"

layout(std430, binding = kBufferBlocks) readonly buffer Blocks {
    uvec4 blocks[];
};

// Per literal (slot): x the operand's first layer in uLayers, y its layers in
// this tile, z its tree leaf, w (array form) its parent node, block-local,
// | kNegate, or (product form) 1 where the literal wants its operand inside.
// The array form keeps an operand's literals together, and its first literal
// has their number in y from kRunShift up (0 on the others).
layout(std430, binding = kBufferBlockOperands) readonly buffer BlockOperands {
    uvec4 blockOperands[];
};

// Per inner node: x its parent (block-local, kNoParent for the root), y
// kNodeAnd for AND and 0 for OR, z its child count, w how many children are
// true when every operand is outside.
layout(std430, binding = kBufferBlockNodes) readonly buffer BlockNodes {
    uvec4 blockNodes[];
};

// What the vertex stage hands every fragment of a block (flat): the block's
// record and, for the register form, its slots, so that no fragment gathers
// them from the buffers.
#ifdef EVALUATE_VERTEX
#define BLOCK_VARYING flat out
#else
#define BLOCK_VARYING flat in
#endif
BLOCK_VARYING uvec4 vRecord;          // blocks[b] of the fragment's block b
#ifdef REGISTER_FORM
BLOCK_VARYING uvec4 vLayerA, vLeafA;  // slots 0-3: layer in uLayers | operand info << kSlotLayerBits, tree leaf
#if MAX_LIVE > 4
BLOCK_VARYING uvec4 vLayerB, vLeafB;  // slots 4-7
BLOCK_VARYING uvec4 vTableLow, vTableHigh;
#endif
#if MAX_LIVE > 8
BLOCK_VARYING uvec4 vLayerC, vLeafC;  // slots 8-11
BLOCK_VARYING uvec4 vLayerD, vLeafD;  // slots 12-15
#endif
#endif
