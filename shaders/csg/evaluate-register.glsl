// The register form of evaluate.frag, for blocks of at most eight operands
// with at most sixteen peeled layers in all (eight convex operands, say, or
// a mesh of three layers and five spheres, or three extruded letters of
// three layers each and two blocks): a slot per layer, each holding at most
// two surfaces here, the layer's near and far, and the block's tree is a
// truth table over the operands' inside bits. No arrays and no loops but
// the walk over surfaces: every slot is one component of a vector (bank A
// holds slots 0-3, bank B slots 4-7, banks C and D slots 8-15). Compiled for
// 4, 8 and 16 slots (MAX_LIVE).
//
// An operand's inside bit follows its surfaces as the array form's walk
// does: each surface of a cluster (evaluate.frag) toggles it, so a pair
// within one cluster (its layers meet there, or a ray grazes its edge)
// changes nothing. An operand with an odd number of surfaces starts inside.
//
// blocks[b]: x first slot in blockOperands, y slot count, z the truth table
// (bit m: the result when operand i is inside exactly for the bits i of m)
// for 4 slots, or for 8 and 16 the index in blockNodes of its 256 bits (two uvec4,
// bit m in word m / 32). blockOperands[x + i]: x the slot's layer in
// uLayers, y its operand's bit in the table (kSlotOperandMask), z its tree
// leaf. The vertex stage hands the fragments the slots packed (blocks.glsl).

// Slot c of a bank (slot i of the block): its layer's near and far surface,
// where the layer caught any.
#define LOAD_SLOT(nearSide, farSide, layers, c, i)                                          \
    if (block.y > uint(i)) {                                                                \
        vec2 layer = texelFetch(uLayers, ivec3(pixel, layers[c] & kSlotLayerMask), 0).rg;   \
        if (-layer.r < kClearedDepth) {                                                     \
            nearSide[c] = -layer.r;                                                         \
            if (layer.g > -layer.r) farSide[c] = layer.g;                                   \
        }                                                                                   \
    }

#if MAX_LIVE > 4
#define RESULT(bits) ((((bits) < 128u ? tableLow : tableHigh)[((bits) >> 5) & 3u] >> ((bits) & 31u)) & 1u) != 0u
#else
#define RESULT(bits) ((block.z >> (bits)) & 1u) != 0u
#endif

// The block, its truth table, the slots and the operands' inside bits after
// the depths taken so far: main's, here for the face's questions.
uvec4 block = uvec4(0u);
uint insideBits = 0u;
vec4 nearA = vec4(kInfinity), farA = vec4(kInfinity), headA;
ivec4 leafA = ivec4(0);
uvec4 bitA = uvec4(0u);
#if MAX_LIVE > 4
uvec4 tableLow = uvec4(0u), tableHigh = uvec4(0u);
vec4 nearB = vec4(kInfinity), farB = vec4(kInfinity), headB;
ivec4 leafB = ivec4(0);
uvec4 bitB = uvec4(0u);
#endif
#if MAX_LIVE > 8
vec4 nearC = vec4(kInfinity), farC = vec4(kInfinity);
vec4 nearD = vec4(kInfinity), farD = vec4(kInfinity);
vec4 headC, headD;  // each slot's next surface on the walk
ivec4 leafC = ivec4(0), leafD = ivec4(0);
uvec4 bitC = uvec4(0u), bitD = uvec4(0u);
#endif

// A bank's depths with the facing bit cleared (surface.glsl's untagged).
vec4 untaggedBank(vec4 tagged) {
    return uintBitsToFloat(floatBitsToUint(tagged) & uvec4(~1u));
}

// evaluate.frag's: the inside bits after the face, and the operand of bit
// `handle` set the other way alone in them.
uint faceBits = 0u;

void keepFaceState() {
    faceBits = insideBits;
}

bool restoreFaceState() {
    return true;
}

bool operandDecides(int handle) {
    return (RESULT(faceBits ^ uint(handle))) != (RESULT(faceBits));
}

// evaluate.frag's: every slot's surfaces in the face.
void weighBank(vec4 nearSide, vec4 farSide, ivec4 leaf, uvec4 bits) {
    for (int c = 0; c < 4; ++c) {
        float near = untagged(nearSide[c]), far = untagged(farSide[c]);
        if (near >= faceStart && near <= faceEnd) weighSurface(nearSide[c], leaf[c], int(bits[c]));
        if (farSide[c] != kInfinity && far >= faceStart && far <= faceEnd)
            weighSurface(farSide[c], leaf[c], int(bits[c]));
    }
}

void forEachFaceSurface() {
    weighBank(nearA, farA, leafA, bitA);
#if MAX_LIVE > 4
    weighBank(nearB, farB, leafB, bitB);
#endif
#if MAX_LIVE > 8
    weighBank(nearC, farC, leafC, bitC);
    weighBank(nearD, farD, leafD, bitD);
#endif
}

// Grazes (evaluate.frag, grazesOutside): the operands with surfaces in
// more than one slot here, and the slots of the others that hold an exit and
// then an entry, emptied.
void noteSlots(vec4 nearSide, uvec4 bits, inout uint seen, inout uint several) {
    for (int c = 0; c < 4; ++c) {
        if (nearSide[c] == kInfinity) continue;
        several |= seen & bits[c];
        seen |= bits[c];
    }
}

void dropGrazes(inout vec4 nearSide, inout vec4 farSide, uvec4 bits, uint several) {
    for (int c = 0; c < 4; ++c) {
        if ((several & bits[c]) == 0u && exitThenEntry(nearSide[c], farSide[c])) {
            nearSide[c] = kInfinity;
            farSide[c] = kInfinity;
        }
    }
}

// The nearest surface not yet taken, of any slot.
float nearestHead() {
    float nearest = min(min(headA.x, headA.y), min(headA.z, headA.w));
#if MAX_LIVE > 4
    nearest = min(nearest, min(min(headB.x, headB.y), min(headB.z, headB.w)));
#endif
#if MAX_LIVE > 8
    nearest = min(nearest, min(min(min(headC.x, headC.y), min(headC.z, headC.w)),
                               min(min(headD.x, headD.y), min(headD.z, headD.w))));
#endif
    return nearest;
}

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    block = vRecord;
    leafA = ivec4(vLeafA);
    bitA = uvec4(1u) << ((vLayerA >> kSlotLayerBits) & kSlotOperandMask);  // the slot's operand in the table
#if MAX_LIVE > 4
    leafB = ivec4(vLeafB);
    bitB = uvec4(1u) << ((vLayerB >> kSlotLayerBits) & kSlotOperandMask);
    tableLow = vTableLow;
    tableHigh = vTableHigh;
#endif
#if MAX_LIVE > 8
    leafC = ivec4(vLeafC);
    leafD = ivec4(vLeafD);
    bitC = uvec4(1u) << ((vLayerC >> kSlotLayerBits) & kSlotOperandMask);
    bitD = uvec4(1u) << ((vLayerD >> kSlotLayerBits) & kSlotOperandMask);
#endif
    LOAD_SLOT(nearA, farA, vLayerA, 0, 0) LOAD_SLOT(nearA, farA, vLayerA, 1, 1)
    LOAD_SLOT(nearA, farA, vLayerA, 2, 2) LOAD_SLOT(nearA, farA, vLayerA, 3, 3)
#if MAX_LIVE > 4
    LOAD_SLOT(nearB, farB, vLayerB, 0, 4) LOAD_SLOT(nearB, farB, vLayerB, 1, 5)
    LOAD_SLOT(nearB, farB, vLayerB, 2, 6) LOAD_SLOT(nearB, farB, vLayerB, 3, 7)
#endif
#if MAX_LIVE > 8
    LOAD_SLOT(nearC, farC, vLayerC, 0, 8) LOAD_SLOT(nearC, farC, vLayerC, 1, 9)
    LOAD_SLOT(nearC, farC, vLayerC, 2, 10) LOAD_SLOT(nearC, farC, vLayerC, 3, 11)
    LOAD_SLOT(nearD, farD, vLayerD, 0, 12) LOAD_SLOT(nearD, farD, vLayerD, 1, 13)
    LOAD_SLOT(nearD, farD, vLayerD, 2, 14) LOAD_SLOT(nearD, farD, vLayerD, 3, 15)
#endif

    uint seen = 0u, several = 0u;
    noteSlots(nearA, bitA, seen, several);
#if MAX_LIVE > 4
    noteSlots(nearB, bitB, seen, several);
#endif
#if MAX_LIVE > 8
    noteSlots(nearC, bitC, seen, several);
    noteSlots(nearD, bitD, seen, several);
#endif
    dropGrazes(nearA, farA, bitA, several);
#if MAX_LIVE > 4
    dropGrazes(nearB, farB, bitB, several);
#endif
#if MAX_LIVE > 8
    dropGrazes(nearC, farC, bitC, several);
    dropGrazes(nearD, farD, bitD, several);
#endif

    // An operand is inside from the start when an odd number of its
    // surfaces lie ahead (evaluate.frag, "inside at the start").
    uvec4 odd = bitA * ((uvec4(lessThan(nearA, vec4(kInfinity))) + uvec4(lessThan(farA, vec4(kInfinity)))) & 1u);
    insideBits = odd.x ^ odd.y ^ odd.z ^ odd.w;
    headA = nearA;
#if MAX_LIVE > 4
    odd = bitB * ((uvec4(lessThan(nearB, vec4(kInfinity))) + uvec4(lessThan(farB, vec4(kInfinity)))) & 1u);
    insideBits ^= odd.x ^ odd.y ^ odd.z ^ odd.w;
    headB = nearB;
#endif
#if MAX_LIVE > 8
    odd = bitC * ((uvec4(lessThan(nearC, vec4(kInfinity))) + uvec4(lessThan(farC, vec4(kInfinity)))) & 1u);
    insideBits ^= odd.x ^ odd.y ^ odd.z ^ odd.w;
    odd = bitD * ((uvec4(lessThan(nearD, vec4(kInfinity))) + uvec4(lessThan(farD, vec4(kInfinity)))) & 1u);
    insideBits ^= odd.x ^ odd.y ^ odd.z ^ odd.w;
    headC = nearC;
    headD = nearD;
#endif
    bool inside = RESULT(insideBits);
#ifdef RESULT_PEEL
    startSkipping();
#endif
    // Surface by surface in depth order, in clusters (evaluate.frag:
    // walkTo). One surface a step: the loop's body holds one
    // considerSurface, whatever the number of slots (llvmpipe runs all of a
    // loop's body on every step). The surfaces at one depth are taken in
    // slot order, and the result is asked only once they all are.
    int step = kWalkOn;
    float depthTaken = -kInfinity;  // the depth whose surfaces are being taken
    bool depthOpen = false;
    float nearest = nearestHead();
    while (true) {
        float depth = untagged(nearest);
        if (depthOpen && depth != depthTaken) {
            noteResult(RESULT(insideBits), inside);
            depthOpen = false;
        }
        if (!depthOpen) {
            step = walkTo(nearest, RESULT(insideBits), inside);
            if (step != kWalkOn) break;
            depthOpen = true;
            depthTaken = depth;
        }
        // The first slot, in slot order, whose next surface lies at `depth`.
        vec4 head = headA, near = nearA, far = farA;
        ivec4 leaf = leafA;
        uvec4 bits = bitA;
        int bank = 0;
#if MAX_LIVE > 4
        if (!any(equal(untaggedBank(headA), vec4(depth)))) {
            head = headB; near = nearB; far = farB; leaf = leafB; bits = bitB; bank = 1;
        }
#endif
#if MAX_LIVE > 8
        if (bank == 1 && !any(equal(untaggedBank(headB), vec4(depth)))) {
            head = headC; near = nearC; far = farC; leaf = leafC; bits = bitC; bank = 2;
            if (!any(equal(untaggedBank(headC), vec4(depth)))) {
                head = headD; near = nearD; far = farD; leaf = leafD; bits = bitD; bank = 3;
            }
        }
#endif
        bvec4 at = equal(untaggedBank(head), vec4(depth));
        int c = at.x ? 0 : at.y ? 1 : at.z ? 2 : 3;
        float surface = head[c];
        considerSurface(surface, leaf[c], inside);
        if (settleDue) {  // before this depth's surfaces apply (evaluate.frag)
            keepFaceState();
            settleDue = false;
        }
        insideBits ^= bits[c];
        head[c] = surface == near[c] ? far[c] : kInfinity;
        if (bank == 0) headA = head;
#if MAX_LIVE > 4
        if (bank == 1) headB = head;
#endif
#if MAX_LIVE > 8
        if (bank == 2) headC = head;
        if (bank == 3) headD = head;
#endif
        nearest = nearestHead();
        // The step that takes a cluster's last surface also sees whether
        // the result changed there, rather than the next step (walkTo's
        // test, one step early): most pixels end at their first cluster,
        // which then takes one step a surface and no more.
        if (walkEndsAfterStep(nearest, RESULT(insideBits), inside)) {
            step = kWalkWritten;
            break;
        }
    }
    // The write is out of the loop, so that its work runs once (evaluate.frag).
    if (step != kWalkWritten) discard;
    writeChosenSurface(walkEntered);
}
