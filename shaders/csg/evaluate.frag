// The CSG evaluator: one draw per shader variant over the tile's blocks
// (evaluate.vert) whose tree is not constant.
//
// Per pixel, every operand's peeled layers give its surfaces in depth order:
//   near_0 < near_1 < ... < near_{n-1} <= far_{n-1} < ... < far_0
// (layer l holds (-near_l, far_l); near == far when the last layer caught a
// single surface). The evaluator merges all operands' lists front to back
// with a binary min-heap of their next surfaces, keeps each operand's
// inside/outside state (a front face enters, a back face leaves; an operand
// whose first surface is a back face was inside from the near plane on), and
// stops at the first depth where the result's membership changes.
//
// The tree is kept up to date incrementally instead of being rerun after each
// surface: it is n-ary AND/OR over literals (engine/render/TreeProgram.h), so
// each inner node keeps a count of its children that are true (AND is true
// when all are, OR when any is). An operand's change adds or removes one from
// its parent's count and climbs only while the node's own value changes. A
// pixel with S surfaces and L live operands costs O(S log L) steps, not
// O(S * L) as a rerun of the whole program would.
//
// Two forms of the walk, by MAX_LIVE (the most slots, literals or nodes a
// block of this draw has): up to eight peeled layers of the block's
// operands, every per-pixel value is one component of a vector and the walk
// runs in registers; else
// per-pixel arrays of MAX_LIVE heap entries, live-operand slots and node
// counts. On llvmpipe each array access is a gather or scatter per lane,
// several times the cost of the register form, so the renderer draws each
// block with the smallest form that holds it (EvaluatePass.cpp).
//
// Output: the visible surface's tagged depth and leaf * 2 + flip, flip = 1
// where the leaf's own membership changes against the result's (it acts as a
// subtracted operand there). Pixels with no surface are discarded: the
// targets were cleared to "miss", and the stencil marks only pixels written.
// LEAF_MARKS: the mark names the leaf's mark slot (FrameTargets::mark).
#ifdef LEAF_MARKS
#extension GL_ARB_shader_stencil_export : require
#endif
#include "csg/surface.glsl"

#ifndef MAX_LIVE
#define MAX_LIVE 64
#endif
#ifndef BLOCK
#define BLOCK 16
#endif

const float kInfinity = uintBitsToFloat(0x7f800000u);
const float kCleared = 3.0e38;  // |clear value| of an unwritten layer is FLT_MAX

layout(binding = 0) uniform sampler2DArray uLayers;

#include "csg/blocks.glsl"

layout(location = 2) uniform ivec2 uTileOrigin;  // the tile's lower-left pixel in the frame
// Per tree leaf: bit 0 set where the evaluator reported one of its front
// faces, bit 1 where a back face, bits 2 and 3 the same where the leaf acts
// subtracted (flipped), in this tile. The normal pass draws only those faces
// of each operand.
layout(std430, binding = 5) buffer ShownFaces {
    uint shownFaces[];
};

#ifdef LEAF_MARKS
// Per tree leaf: its mark slot (FrameTargets::assignMarkSlots).
layout(std430, binding = 1) readonly buffer MarkSlots {
    int markSlots[];
};
#endif

layout(location = 0) out float outDepth;
layout(location = 1) out int outLeaf;

ivec2 pixel;

// Groups of convex operands (ConvexGroups.h, GroupPeel.h): the tree has one
// operand for a group, named by its lowest member, and the group's peel kept
// which member makes its entry and its exit at each pixel. The leaf written,
// marked and reported shown is that member. groupTable[leaf]: -1, or where
// the leaf's group record starts: its layer of uGroupIds, then its members.
// GROUPS: the program has groups (the lookup costs every written pixel).
#ifdef GROUPS
layout(binding = 3) uniform usampler2DArray uGroupIds;  // tile pixels: entry | exit << 8
layout(std430, binding = 6) readonly buffer GroupTable {
    int groupTable[];
};

bool isGroup(int leaf) {
    return groupTable[leaf] >= 0;
}

int surfaceLeaf(int leaf, bool exit) {
    int at = groupTable[leaf];
    if (at < 0) return leaf;
    uint ids = texelFetch(uGroupIds, ivec3(pixel, groupTable[at]), 0).r;
    return groupTable[at + 1 + int(exit ? ids >> 8u : ids & 0xffu)];
}
#else
bool isGroup(int leaf) {
    return false;
}

int surfaceLeaf(int leaf, bool exit) {
    return leaf;
}
#endif

// The result changes at `group` (untagged depth): entered (now true) or left.
// entryLeaf / exitLeaf: the tree leaf of the first operand that
// entered / left there, -1 for none. Prefer a surface whose operand changes
// the same way as the result: it is the result's own face.
void writeSurface(float group, bool entered, int entryLeaf, int exitLeaf) {
    bool operandEntered = entered ? entryLeaf >= 0 : exitLeaf < 0;
    int leaf = surfaceLeaf(operandEntered ? entryLeaf : exitLeaf, !operandEntered);
    outDepth = uintBitsToFloat(floatBitsToUint(group) | (operandEntered ? 0u : 1u));
    outLeaf = leaf * 2 + (operandEntered != entered ? 1 : 0);
    // exit + 2 flip: the bit in shownFaces, and the mark's offset
    // (FrameTargets::mark: 1 + 4 slot + exit + 2 flip).
    int faceBit = (operandEntered ? 0 : 1) + (operandEntered != entered ? 2 : 0);
    atomicOr(shownFaces[leaf], 1u << faceBit);
#ifdef LEAF_MARKS
    gl_FragStencilRefARB = 1 + markSlots[leaf] * 4 + faceBit;
#endif
}

#if !REGISTER_FORM && !defined(FIRST_SURFACE_FORM)
// Loop iterations this invocation may spend. llvmpipe ends every loop of a
// shader invocation once 65535 iterations have run in all (gallivm's loop
// limiter), which would leave a deep pixel half-evaluated and wrong. A pixel
// whose walk would overrun the budget is marked unresolved (leaf code -2, no
// surface) instead, and the renderer reports how many there were. Real GPUs
// have no such limit: the renderer passes a budget no pixel reaches.
layout(location = 4) uniform int uLoopBudget;

int budget;

void writeUnresolved() {
    outDepth = kInfinity;
    outLeaf = -2;
#ifdef LEAF_MARKS
    gl_FragStencilRefARB = 0;  // no surface: no later pass needs the pixel
#endif
}

#endif

#if defined(FIRST_SURFACE_FORM)

// The first-surface form, for blocks whose tree is one operand, not negated,
// of one peeled layer (a cheese's cube where no hole reaches, one tooth of a
// union of teeth): the result is the operand, so its first surface is the
// result's. A front face there enters both; a back face (the eye inside the
// operand) leaves both. Where the layer's two surfaces lie at one depth (a
// ray grazing an edge, a flat sheet) the operand is entered and left at once
// and the result shows nothing. This is the register form's walk for one
// slot, step for step. Nothing to flip.
// The renderer marks the leaf's front faces shown for every such block
// (EvaluatePass::run), so only the rare back face needs the atomic; a
// group's member is known here only, so it always does.
void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    vec2 layer = texelFetch(uLayers, ivec3(pixel, vRecord.x), 0).rg;
    float first = -layer.r;
    if (first >= kCleared || (layer.g > first && untagged(layer.g) == untagged(first))) discard;
    int faceBit = isExit(first) ? 1 : 0;
    bool grouped = isGroup(int(vRecord.y));
    int leaf = surfaceLeaf(int(vRecord.y), faceBit != 0);
    outDepth = first;
    outLeaf = leaf * 2;
    if (faceBit != 0 || grouped) atomicOr(shownFaces[leaf], 1u << faceBit);
#ifdef LEAF_MARKS
    // The record carries 1 + 4 slot, but not a group member's.
    gl_FragStencilRefARB = (grouped ? 1 + markSlots[leaf] * 4 : int(vRecord.z)) + faceBit;
#endif
}

#elif REGISTER_FORM

// The register form, for blocks whose operands have at most eight peeled
// layers in all (eight convex operands, say, or a mesh of three layers and
// five spheres): a slot per layer, each holding at most two surfaces here,
// the layer's near and far, and the block's tree is a truth table over the
// operands' inside bits. No arrays and no loops but the walk over depths:
// every slot is one component of a vector (bank A holds slots 0-3, bank B
// slots 4-7). Compiled for 4 and 8 slots (MAX_LIVE): every instruction runs
// for every pixel on llvmpipe, used or not.
//
// An operand's inside bit follows its surfaces as the array form's walk
// does: a front face enters, a back face leaves, and where one depth holds
// several of its surfaces (its layers meet there, or a ray grazes its edge)
// a back face among them wins, as it comes last in tagged order. An operand
// whose first layer's near surface is a back face starts inside.
//
// blocks[b]: x first slot in blockOperands, y slot count, z the truth table
// (bit m: the result when operand i is inside exactly for the bits i of m)
// for 4 slots, or for 8 the index in blockNodes of its 256 bits (two uvec4,
// bit m in word m / 32). blockOperands[x + i]: x the slot's layer in
// uLayers, y its operand's bit in the table | 8 on the operand's first
// layer, z its tree leaf.

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    uvec4 block = vRecord;
    vec4 nearA = vec4(kInfinity), farA = vec4(kInfinity);
    ivec4 leafA = ivec4(vLeafA);
    uvec4 bitA = uvec4(1u) << ((vLayerA >> 16) & 7u);  // the slot's operand in the table
#if MAX_LIVE > 4
    vec4 nearB = vec4(kInfinity), farB = vec4(kInfinity);
    ivec4 leafB = ivec4(vLeafB);
    uvec4 bitB = uvec4(1u) << ((vLayerB >> 16) & 7u);
    uvec4 tableLow = vTableLow, tableHigh = vTableHigh;
#endif
#define LOAD_SLOT(nearSide, farSide, layers, c, i)                                  \
    if (block.y > uint(i)) {                                                        \
        vec2 layer = texelFetch(uLayers, ivec3(pixel, layers[c] & 0xffffu), 0).rg;  \
        if (-layer.r < kCleared) {                                                  \
            nearSide[c] = -layer.r;                                                 \
            if (layer.g > -layer.r) farSide[c] = layer.g;                           \
        }                                                                           \
    }
    LOAD_SLOT(nearA, farA, vLayerA, 0, 0) LOAD_SLOT(nearA, farA, vLayerA, 1, 1)
    LOAD_SLOT(nearA, farA, vLayerA, 2, 2) LOAD_SLOT(nearA, farA, vLayerA, 3, 3)
#if MAX_LIVE > 4
    LOAD_SLOT(nearB, farB, vLayerB, 0, 4) LOAD_SLOT(nearB, farB, vLayerB, 1, 5)
    LOAD_SLOT(nearB, farB, vLayerB, 2, 6) LOAD_SLOT(nearB, farB, vLayerB, 3, 7)
#endif

    // An operand whose first surface is a back face is inside from the start
    // (the near side of its first layer, flagged 8 in the slot's info).
    uvec4 starts = bitA * (floatBitsToUint(nearA) & (vLayerA >> 19) & 1u);
    uint insideBits = starts.x | starts.y | starts.z | starts.w;
    vec4 headA = nearA;
#if MAX_LIVE > 4
    starts = bitB * (floatBitsToUint(nearB) & (vLayerB >> 19) & 1u);
    insideBits |= starts.x | starts.y | starts.z | starts.w;
    vec4 headB = nearB;
#define RESULT(bits) ((((bits) < 128u ? tableLow : tableHigh)[((bits) >> 5) & 3u] >> ((bits) & 31u)) & 1u) != 0u
#else
#define RESULT(bits) ((block.z >> (bits)) & 1u) != 0u
#endif
    bool inside = RESULT(insideBits);
    while (true) {
        float nearest = min(min(headA.x, headA.y), min(headA.z, headA.w));
#if MAX_LIVE > 4
        nearest = min(nearest, min(min(headB.x, headB.y), min(headB.z, headB.w)));
#endif
        if (nearest == kInfinity) break;
        float group = untagged(nearest);
        // Every surface at this depth, of any operand, changes its operand's
        // state before the tree is asked again: coincident faces cancel as
        // the solids say (a cube minus an equal cube leaves nothing). An
        // operand can have both its surfaces here (a ray grazing its edge).
        int entryLeaf = -1, exitLeaf = -1;
        uint entered = 0u, left = 0u;  // operand bits
#define TAKE_SURFACE(head, nearSide, farSide, leaf, bits, c)                     \
        if (head[c] != kInfinity && untagged(head[c]) == group) {                \
            if (isExit(head[c])) {                                               \
                left |= bits[c];                                                 \
                if (exitLeaf < 0) exitLeaf = leaf[c];                            \
            } else {                                                             \
                entered |= bits[c];                                              \
                if (entryLeaf < 0) entryLeaf = leaf[c];                          \
            }                                                                    \
            head[c] = head[c] == nearSide[c] ? farSide[c] : kInfinity;           \
        }
#define TAKE_SLOT(head, nearSide, farSide, leaf, bits, c)    \
        TAKE_SURFACE(head, nearSide, farSide, leaf, bits, c) \
        TAKE_SURFACE(head, nearSide, farSide, leaf, bits, c)
        TAKE_SLOT(headA, nearA, farA, leafA, bitA, 0) TAKE_SLOT(headA, nearA, farA, leafA, bitA, 1)
        TAKE_SLOT(headA, nearA, farA, leafA, bitA, 2) TAKE_SLOT(headA, nearA, farA, leafA, bitA, 3)
#if MAX_LIVE > 4
        TAKE_SLOT(headB, nearB, farB, leafB, bitB, 0) TAKE_SLOT(headB, nearB, farB, leafB, bitB, 1)
        TAKE_SLOT(headB, nearB, farB, leafB, bitB, 2) TAKE_SLOT(headB, nearB, farB, leafB, bitB, 3)
#endif
        insideBits = (insideBits | entered) & ~left;  // a back face wins, as in the array form
        bool now = RESULT(insideBits);
        if (now != inside) {
            writeSurface(group, now, entryLeaf, exitLeaf);
            return;
        }
    }
    discard;
}

#elif defined(PRODUCT_FORM)
#include "csg/product.glsl"
#else

// The array form.

const uint kNoParent = 0xffffffffu;
const uint kNegate = 0x80000000u;

uint nodeBase;

// The literal's operand's next surface at or after list position `cursor`
// (0..2n-1: near side, then far side backwards), or +inf. Moves `cursor`
// past it.
float nextSurface(uvec4 literal, inout int cursor) {
    int first = int(literal.x);
    int n = int(literal.y & 0xffffu);
    while (cursor < 2 * n) {
        --budget;
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

uint trueChildren[MAX_LIVE];  // per inner node

// Live operands: slot s holds an operand that still has surfaces ahead.
int slotCursor[MAX_LIVE];     // its position in its surface list
uint slotEntry[MAX_LIVE];     // its first literal in blockOperands
uint slotLiterals[MAX_LIVE];  // its literals there, one after the other
bool slotInside[MAX_LIVE];

// Min-heap of the slots' next surfaces (tagged depths), root at 0.
float heapDepth[MAX_LIVE];
int heapSlot[MAX_LIVE];
int heapSize;

bool nodeValue(uint node) {
    uvec4 n = blockNodes[nodeBase + node];
    return n.y != 0u ? trueChildren[node] == n.z : trueChildren[node] != 0u;
}

// A literal under `literal`'s parent turned true (or false): update the
// counts up the tree while values change. Node 0 is the root.
void literalChanged(uint literal, bool nowTrue) {
    uint node = literal & ~kNegate;
    bool rising = nowTrue;
    while (node != kNoParent) {
        --budget;
        bool before = nodeValue(node);
        if (rising) {
            ++trueChildren[node];
        } else {
            --trueChildren[node];
        }
        bool after = nodeValue(node);
        if (after == before) return;
        rising = after;
        node = blockNodes[nodeBase + node].x;
    }
}

// Sets slot s's operand inside or outside.
void setInside(int s, bool inside) {
    if (slotInside[s] == inside) return;
    slotInside[s] = inside;
    for (uint j = 0u; j < slotLiterals[s]; ++j) {
        uint literal = blockOperands[slotEntry[s] + j].w;
        literalChanged(literal, inside != ((literal & kNegate) != 0u));
    }
}

// Restores the heap order below position i after its depth grew.
void siftDown(int i) {
    float depth = heapDepth[i];
    int slot = heapSlot[i];
    while (true) {
        --budget;
        int child = 2 * i + 1;
        if (child >= heapSize) break;
        if (child + 1 < heapSize && heapDepth[child + 1] < heapDepth[child]) ++child;
        if (heapDepth[child] >= depth) break;
        heapDepth[i] = heapDepth[child];
        heapSlot[i] = heapSlot[child];
        i = child;
    }
    heapDepth[i] = depth;
    heapSlot[i] = slot;
}

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    uvec4 block = vRecord;
    nodeBase = block.z;
    budget = uLoopBudget;

    // Every operand outside: the counts the CPU worked out for that.
    for (uint n = 0u; n < block.w; ++n) trueChildren[n] = blockNodes[nodeBase + n].w;

    // Each operand's first surface; a back face first means inside from the start.
    heapSize = 0;
    for (uint i = 0u; i < block.y; ++i) {
        uvec4 literal = blockOperands[block.x + i];
        // An operand's literals follow each other, the first holding their
        // number (EvaluatePass.cpp: kRunShift), the others 0: one slot each.
        // (Stepping i by that number instead lost surfaces on llvmpipe, Mesa
        // 22.3, though every value was right: keep the loop stepping by one.)
        uint run = literal.y >> 16;
        if (run == 0u) continue;
        int cursor = 0;
        float d = nextSurface(literal, cursor);
        if (d == kInfinity) continue;
        int s = heapSize++;
        slotCursor[s] = cursor;
        slotEntry[s] = block.x + i;
        slotLiterals[s] = run;
        slotInside[s] = false;
        if (isExit(d)) setInside(s, true);
        heapDepth[s] = d;
        heapSlot[s] = s;
    }
    for (int i = heapSize / 2 - 1; i >= 0; --i) siftDown(i);

    bool inside = block.y > 0u && nodeValue(0u);
    while (heapSize > 0) {
        if (budget < 0) {
            writeUnresolved();
            return;
        }
        float group = untagged(heapDepth[0]);
        // Every surface at this depth, of any operand, changes its operand's
        // state before the tree is asked again: coincident faces cancel as
        // the solids say (a cube minus an equal cube leaves nothing).
        int entryLeaf = -1, exitLeaf = -1;
        while (heapSize > 0 && untagged(heapDepth[0]) == group) {
            --budget;
            int s = heapSlot[0];
            bool exit = isExit(heapDepth[0]);
            setInside(s, !exit);
            uvec4 literal = blockOperands[slotEntry[s]];
            int leaf = int(literal.z);
            if (exit) {
                if (exitLeaf < 0) exitLeaf = leaf;
            } else {
                if (entryLeaf < 0) entryLeaf = leaf;
            }
            int cursor = slotCursor[s];
            float next = nextSurface(literal, cursor);
            slotCursor[s] = cursor;
            if (next == kInfinity) {  // operand done: the last entry takes its place
                --heapSize;
                heapDepth[0] = heapDepth[heapSize];
                heapSlot[0] = heapSlot[heapSize];
            } else {
                heapDepth[0] = next;
            }
            siftDown(0);
        }

        bool now = nodeValue(0u);
        if (now != inside) {
            writeSurface(group, now, entryLeaf, exitLeaf);
            return;
        }
        inside = now;
    }
    discard;
}

#endif
