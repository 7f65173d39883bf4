// The array form of evaluate.frag, for every block the other forms do not
// hold. It merges all operands' surface lists front to back with a binary
// min-heap of their next surfaces, and keeps the tree up to date
// incrementally instead of rerunning it after each surface: the block's tree
// is n-ary AND/OR over literals (a counting tree, engine/csg/CompiledTree.h),
// so each inner node keeps a count of its children that are true (AND is
// true when all are, OR when any is). An operand's change adds or removes one
// from its parent's count and climbs only while the node's own value
// changes. A pixel with S surfaces and L live operands costs O(S log L)
// steps, not O(S * L) as a rerun of the whole tree would.
//
// Per-pixel arrays of MAX_LIVE heap entries, live-operand slots and node
// counts: on llvmpipe each array access is a gather or scatter per lane,
// several times the cost of the register form. blocks[b] and the buffers'
// layout: blocks.glsl.

uint nodeBase;

// The literal's operand's next surface at or after list position `cursor`
// (0..2n-1: near side, then far side backwards), or +inf. Moves `cursor`
// past it.
float nextSurface(uvec4 literal, inout int cursor) {
    int first = int(literal.x);
    int n = int(literal.y & kLayerCountMask);
    while (cursor < 2 * n) {
        --budget;
        int j = cursor;
        if (j < n) {
            vec2 layer = texelFetch(uLayers, ivec3(pixel, first + j), 0).rg;
            if (-layer.r >= kClearedDepth) {
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

// Whether the literal's operand has an odd number of surfaces here: a layer
// holds two, or one where its near and far sides are one surface, and the
// first empty layer ends the list.
bool surfaceCountIsOdd(uvec4 literal) {
    int first = int(literal.x);
    int n = int(literal.y & kLayerCountMask);
    bool odd = false;
    for (int j = 0; j < n; ++j) {
        --budget;
        vec2 layer = texelFetch(uLayers, ivec3(pixel, first + j), 0).rg;
        if (-layer.r >= kClearedDepth) break;
        if (!(layer.g > -layer.r)) odd = !odd;
    }
    return odd;
}

// Whether the literal's operand's only surfaces here are an exit and then
// an entry in its first layer (evaluate.frag, grazesOutside): it has none.
bool grazesOnly(uvec4 literal) {
    int first = int(literal.x);
    vec2 layer = texelFetch(uLayers, ivec3(pixel, first), 0).rg;
    if (!grazesOutside(layer)) return false;
    return int(literal.y & kLayerCountMask) == 1 || texelFetch(uLayers, ivec3(pixel, first + 1), 0).r <= -kClearedDepth;
}

uint trueChildren[MAX_LIVE];  // per inner node

// Live operands: slot s holds an operand that still has surfaces ahead.
// Slot s's state, one word: its position in its surface list (kCursorMask),
// the number of its literals (which follow each other from slotEntry[s]:
// above kLiteralsShift) and whether its operand is inside (kInsideBit). Few
// words per slot, so that drivers that keep these arrays in scarce storage
// (NVIDIA's) take large MAX_LIVE.
uint slotState[MAX_LIVE];
uint slotEntry[MAX_LIVE];  // its first literal in blockOperands
int slotCount = 0;         // slots startWalk made: every operand with a surface here
const uint kCursorMask = 0xffffu;
const uint kLiteralsShift = 16u;
const uint kInsideBit = 0x80000000u;

int slotCursor(int s) {
    return int(slotState[s] & kCursorMask);
}

uint slotLiterals(int s) {
    return (slotState[s] & ~kInsideBit) >> kLiteralsShift;
}

bool slotInside(int s) {
    return (slotState[s] & kInsideBit) != 0u;
}

// Min-heap of the slots' next surfaces (tagged depths), root at 0.
float heapDepth[MAX_LIVE];
int heapSlot[MAX_LIVE];
int heapSize;

bool nodeValue(uint node) {
    uvec4 n = blockNodes[nodeBase + node];
    return n.y == kNodeAnd ? trueChildren[node] == n.z : trueChildren[node] != 0u;
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
    if (slotInside(s) == inside) return;
    slotState[s] ^= kInsideBit;
    for (uint j = 0u; j < slotLiterals(s); ++j) {
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

// Every operand outside, then each operand that has a surface here in a
// slot of the heap at its first surface; an odd number of surfaces means
// inside from the start (evaluate.frag, "inside at the start").
void startWalk(uvec4 block) {
    // Every operand outside: the counts the CPU worked out for that.
    for (uint n = 0u; n < block.w; ++n) trueChildren[n] = blockNodes[nodeBase + n].w;

    heapSize = 0;
    for (uint i = 0u; i < block.y; ++i) {
        uvec4 literal = blockOperands[block.x + i];
        // An operand's literals follow each other, the first holding their
        // number (above kRunShift), the others 0: one slot each.
        // (Stepping i by that number instead lost surfaces on llvmpipe, Mesa
        // 22.3, though every value was right: keep the loop stepping by one.)
        uint run = literal.y >> kRunShift;
        if (run == 0u) continue;
        if (grazesOnly(literal)) continue;
        int cursor = 0;
        float d = nextSurface(literal, cursor);
        if (d == kInfinity) continue;
        int s = heapSize++;
        slotState[s] = uint(cursor) | run << kLiteralsShift;
        slotEntry[s] = block.x + i;
        if (surfaceCountIsOdd(literal)) setInside(s, true);
        heapDepth[s] = d;
        heapSlot[s] = s;
    }
    slotCount = heapSize;
    for (int i = heapSize / 2 - 1; i >= 0; --i) siftDown(i);
}

// evaluate.frag's: the counting tree is not copied; from the face's end on,
// the slots set afterwards are listed (up to four), and set back before
// the face is asked.
bool keepingSlots = false;
ivec4 slotsSince = ivec4(0);
int slotsSinceCount = 0;

void keepFaceState() {
    keepingSlots = true;
    slotsSinceCount = 0;
}

void noteSlotSet(int s) {
    if (slotsSinceCount < 4) slotsSince[slotsSinceCount] = s;
    ++slotsSinceCount;
}

bool restoreFaceState() {
    if (slotsSinceCount > 4) return false;
    for (int k = 0; k < slotsSinceCount; ++k) setInside(slotsSince[k], !slotInside(slotsSince[k]));
    slotsSinceCount = 0;
    return true;
}

// evaluate.frag's: slot `s`'s operand set the other way alone.
bool operandDecides(int s) {
    bool now = nodeValue(0u);
    setInside(s, !slotInside(s));
    bool other = nodeValue(0u);
    setInside(s, !slotInside(s));
    return other != now;
}

// evaluate.frag's: every slot's surfaces in the face, from its layers.
void forEachFaceSurface() {
    for (int s = 0; s < slotCount; ++s) {
        uvec4 literal = blockOperands[slotEntry[s]];
        int first = int(literal.x);
        int n = int(literal.y & kLayerCountMask);
        for (int j = 0; j < n; ++j) {
            --budget;
            vec2 layer = texelFetch(uLayers, ivec3(pixel, first + j), 0).rg;
            if (-layer.r >= kClearedDepth) break;
            float near = untagged(-layer.r), far = untagged(layer.g);
            if (near >= faceStart && near <= faceEnd) weighSurface(-layer.r, int(literal.z), s);
            if (layer.g > -layer.r && far >= faceStart && far <= faceEnd) weighSurface(layer.g, int(literal.z), s);
        }
    }
}

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    uvec4 block = vRecord;
    nodeBase = block.z;
    budget = uLoopBudget;
    startWalk(block);

    bool inside = block.y > 0u && nodeValue(0u);
#ifdef RESULT_PEEL
    startSkipping();
#endif
    // Depth by depth, the tree asked after each, in clusters (evaluate.frag:
    // walkTo).
    int step = kWalkOn;
    while (true) {
        if (budget < 0) {
            writeUnresolved();
            return;
        }
        float nearest = heapSize > 0 ? heapDepth[0] : kInfinity;
        bool askTree = clusterOpen;
#ifdef RESULT_PEEL
        askTree = askTree || skipping;
#endif
        step = walkTo(nearest, askTree && nodeValue(0u), inside);
        if (step != kWalkOn) break;
        float depth = untagged(nearest);
        while (heapSize > 0 && untagged(heapDepth[0]) == depth) {
            --budget;
            int s = heapSlot[0];
            uvec4 literal = blockOperands[slotEntry[s]];
            considerSurface(heapDepth[0], int(literal.z), inside);
            if (settleDue) {  // before this surface applies (evaluate.frag)
                keepFaceState();
                settleDue = false;
            }
            if (keepingSlots) noteSlotSet(s);
            setInside(s, !slotInside(s));
            int cursor = slotCursor(s);
            float next = nextSurface(literal, cursor);
            slotState[s] = (slotState[s] & ~kCursorMask) | uint(cursor);
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
        noteResult(now, inside);
        // walkTo's test one step early (evaluate.frag); a walk past its
        // budget ends as unresolved above instead.
        if (budget >= 0 && walkEndsAfterStep(heapSize > 0 ? heapDepth[0] : kInfinity, now, inside)) {
            step = kWalkWritten;
            break;
        }
    }
    // The write is out of the loop, so that its work runs once (evaluate.frag).
    if (step != kWalkWritten) discard;
    writeChosenSurface(walkEntered);
}
