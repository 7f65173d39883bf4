// The CSG evaluator: one fullscreen pass over a tile.
//
// Per pixel, every operand's peeled layers give its surfaces in depth order:
//   near_0 < near_1 < ... < near_{n-1} <= far_{n-1} < ... < far_0
// (layer l holds (-near_l, far_l); near == far when the last layer caught a
// single surface). The evaluator merges all operands' lists, walks the
// surfaces front to back, keeps each operand's inside/outside state (a front
// face enters, a back face leaves; an operand whose first surface is a back
// face was inside from the near plane on), runs the compiled tree program
// (engine/render/TreeProgram.h) after each group of surfaces at one depth, and
// stops at the first depth where the result's membership changes.
//
// Memory per pixel: MAX_LIVE heads (depth, cursor, operand: enough for the
// longest block list) and one state bit per operand (MAX_OPERANDS); the tree
// itself costs one 32-bit stack word at any depth.
//
// Output: the visible surface's tagged depth (+inf on a miss) and
// leaf * 2 + flip (-1 on a miss), flip = 1 where the leaf's own membership
// changes against the result's (it acts as a subtracted operand there).
#include "csg/surface.glsl"

#ifndef MAX_OPERANDS
#define MAX_OPERANDS 64
#endif
#ifndef MAX_LIVE
#define MAX_LIVE MAX_OPERANDS
#endif
#ifndef BLOCK
#define BLOCK 16
#endif

const uint kOpPush = 0u;
const uint kOpAnd = 1u;
const uint kOpOr = 2u;
const uint kOpFromStack = 4u;
const uint kOpNegate = 8u;
const float kInfinity = uintBitsToFloat(0x7f800000u);
const float kCleared = 3.0e38;  // |clear value| of an unwritten layer is FLT_MAX

layout(binding = 0) uniform sampler2DArray uLayers;

layout(std430, binding = 0) readonly buffer TreeCode {
    uint code[];
};
// Per operand: x first layer in uLayers, y layers peeled in this tile (0: the
// operand misses the tile), z its tree leaf index.
layout(std430, binding = 1) readonly buffer OperandTable {
    uvec4 operands[];
};
// The tile is cut into BLOCK x BLOCK pixel blocks; block b lists the operands
// whose screen rectangle meets it: blockOperands[blocks[b].x + i] for
// i < blocks[b].y. Every other operand has no surface in the block, so the
// block runs its own program, code[blocks[b].z ..] of length blocks[b].w: the
// tree with those operands folded away (TreeProgram.h, specializeProgram).
layout(std430, binding = 2) readonly buffer Blocks {
    uvec4 blocks[];
};
layout(std430, binding = 3) readonly buffer BlockOperands {
    uint blockOperands[];
};

layout(location = 2) uniform ivec2 uTileOrigin;  // the tile's lower-left pixel in the frame
layout(location = 3) uniform int uBlocksX;       // blocks per row of the tile
// Loop iterations this invocation may spend. llvmpipe ends every loop of a
// shader invocation once 65535 iterations have run in all (gallivm's loop
// limiter), which would leave a deep pixel half-evaluated and wrong. A pixel
// whose walk would overrun the budget is marked unresolved (leaf code -2, no
// surface) instead, and the renderer reports how many there were. Real GPUs
// have no such limit: the renderer passes a budget no pixel reaches.
layout(location = 4) uniform int uLoopBudget;

layout(location = 0) out float outDepth;
layout(location = 1) out int outLeaf;

uint state[(MAX_OPERANDS + 31) / 32];

uint codeStart;
uint codeEnd;

bool runProgram() {
    uint stack = 0u;
    for (uint pc = codeStart; pc < codeEnd; ++pc) {
        uint instruction = code[pc];
        uint value;
        if ((instruction & kOpFromStack) != 0u) {
            value = stack & 1u;
            stack >>= 1;
        } else {
            uint operand = instruction >> 4;
            value = ((state[operand >> 5] >> (operand & 31u)) & 1u) ^ ((instruction >> 3) & 1u);
        }
        uint op = instruction & 3u;
        if (op == kOpPush) {
            stack = (stack << 1) | value;
        } else if (op == kOpAnd) {
            stack &= ~1u | value;
        } else {
            stack |= value;
        }
    }
    return (stack & 1u) != 0u;
}

void setInside(uint operand, bool inside) {
    uint bit = 1u << (operand & 31u);
    if (inside) {
        state[operand >> 5] |= bit;
    } else {
        state[operand >> 5] &= ~bit;
    }
}

// The operand's next surface at or after list position `cursor` (0..2n-1:
// near side, then far side backwards), or +inf. Moves `cursor` past it.
float nextSurface(uvec4 operand, ivec2 pixel, inout int cursor) {
    int first = int(operand.x);
    int n = int(operand.y);
    while (cursor < 2 * n) {
        int j = cursor;
        if (j < n) {
            vec2 layer = texelFetch(uLayers, ivec3(pixel, first + j), 0).rg;
            if (-layer.r >= kCleared) {
                // Layer j caught nothing, nor will any later one: go to the far
                // side of layer j - 1.
                cursor = 2 * n - j;
                continue;
            }
            cursor = j + 1;
            return -layer.r;
        }
        int l = 2 * n - 1 - j;
        vec2 layer = texelFetch(uLayers, ivec3(pixel, first + l), 0).rg;
        cursor = j + 1;
        // far == near: the layer caught a single surface, already walked.
        if (layer.g > -layer.r) return layer.g;
    }
    return kInfinity;
}

float headDepth[MAX_LIVE];
int headCursor[MAX_LIVE];
int headOperand[MAX_LIVE];

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    // Only the block's operands are read by its program, and each is set below.

    // Each operand's first surface; a back face first means inside from the start.
    int live = 0;
    ivec2 blockXY = pixel / BLOCK;
    uvec4 block = blocks[blockXY.y * uBlocksX + blockXY.x];
    codeStart = block.z;
    codeEnd = block.z + block.w;
    for (uint i = block.x; i < block.x + block.y; ++i) {
        int o = int(blockOperands[i]);
        uvec4 operand = operands[o];
        int cursor = 0;
        float d = nextSurface(operand, pixel, cursor);
        setInside(uint(o), d != kInfinity && isExit(d));
        if (d == kInfinity) continue;
        headDepth[live] = d;
        headCursor[live] = cursor;
        headOperand[live] = o;
        ++live;
    }

    outDepth = kInfinity;
    outLeaf = -1;
    // What each walk step costs in loop iterations, counted generously: the
    // two loops over the live heads, the program, and the surface fetches.
    int budget = uLoopBudget - 3 * int(block.y) - int(codeEnd - codeStart);
    bool inside = runProgram();
    while (live > 0) {
        budget -= 2 * live + int(codeEnd - codeStart) + 8;
        if (budget < 0) {
            outLeaf = -2;
            return;
        }
        float nearest = kInfinity;
        for (int a = 0; a < live; ++a) nearest = min(nearest, headDepth[a]);
        float group = untagged(nearest);

        // Every surface at this depth, of any operand, changes its operand's
        // state before the tree is asked again: coincident faces cancel as
        // the solids say (a cube minus an equal cube leaves nothing).
        int firstEntry = -1;  // operand of the first entry surface in the group
        int firstExit = -1;
        for (int a = 0; a < live;) {
            int o = headOperand[a];
            while (untagged(headDepth[a]) == group) {
                bool exit = isExit(headDepth[a]);
                setInside(uint(o), !exit);
                if (exit) {
                    if (firstExit < 0) firstExit = o;
                } else {
                    if (firstEntry < 0) firstEntry = o;
                }
                int cursor = headCursor[a];
                headDepth[a] = nextSurface(operands[o], pixel, cursor);
                headCursor[a] = cursor;
            }
            if (headDepth[a] == kInfinity) {  // operand done: drop it
                --live;
                headDepth[a] = headDepth[live];
                headCursor[a] = headCursor[live];
                headOperand[a] = headOperand[live];
            } else {
                ++a;
            }
        }

        bool now = runProgram();
        if (now != inside) {
            // The result enters (now) or leaves (!now) here. Prefer a surface
            // whose operand changes the same way: it is the result's own face.
            bool entered = now;
            bool operandEntered = entered ? firstEntry >= 0 : firstExit < 0;
            int o = operandEntered ? firstEntry : firstExit;
            outDepth = uintBitsToFloat(floatBitsToUint(group) | (operandEntered ? 0u : 1u));
            outLeaf = int(operands[o].z) * 2 + (operandEntered != entered ? 1 : 0);
            return;
        }
        inside = now;
    }
}
