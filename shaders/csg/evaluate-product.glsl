// The product form of evaluate.frag, for blocks whose tree is a single AND
// (a CSG product: intersections and subtractions) or a single OR (a union)
// of literals, each operand with one peeled layer here (a convex operand,
// say). The counting tree, heap and per-pixel arrays of the array form are
// not needed: with at most two surfaces, an operand's membership along the
// ray is a step function with at most two steps.
//
// Each literal wants its operand inside or outside (blockOperands[].w); P is
// "every literal gets what it wants". For an AND the result is P; for an OR
// (blocks[b].z = 1) the CPU stores the opposite wishes, so the result is !P
// (De Morgan). Either way the result changes exactly where P does:
// - P false before every surface: P turns true at the least depth d where
//   every literal is content. From d = "before every surface", visit the
//   literals in turn; one that is not content at d moves d to its own
//   first step after d where it would be (+inf: never). A move only goes as
//   far as the mover forces, so d never passes the answer; after n
//   consecutive content literals, d is it.
// - P true before every surface: P turns false at the earliest step where
//   some literal stops being content, one pass.
// With coincident surfaces (evaluate.frag) the result is asked only after
// whole clusters: the answer is the first cluster after which P differs
// from its start. The seek finds the first depth X where P differs at all;
// the cluster holding X runs from the surfaces before X while each lies
// within the tolerance of the next, to those after X while each lies within
// the tolerance of the one before; if P at that cluster's end is back to its
// start (X lay on a sliver thinner than the tolerance), the seek goes on
// from the next cluster. The surface written is chosen among the cluster's
// by the rule of evaluate.frag.
//
// Cost: n literal visits when the answer is the first surface, up to n per
// move otherwise (the slots of one pixel that move d in slot order cost one
// round in all: a stack of subtracted solids listed front to back), and one
// more round for the surfaces next to the answer and at it: where none lies
// within the tolerance (most pixels), the answer is a cluster of one depth.
// A real cluster costs a few rounds more, to gather it and walk it.

const float kNone = -kInfinity;  // d before every surface

// An operand's surfaces along the ray from its one layer: `first` and
// `second` (untagged; +inf where missing) and its membership before the
// first, between them and after the second. An operand with one surface
// here was inside from the ray's start (evaluate.frag, "inside at the start").
struct Steps {
    float first, second;              // untagged
    float firstTagged, secondTagged;  // as peeled
    bool before, between, after;
};

Steps stepsOf(uint layer) {
    vec2 texel = texelFetch(uLayers, ivec3(pixel, int(layer)), 0).rg;
    float near = -texel.r;
    bool hit = near < kClearedDepth && !grazesOutside(texel);  // evaluate.frag
    bool two = hit && texel.g > near;
    Steps s;
    s.firstTagged = hit ? near : kInfinity;
    s.secondTagged = two ? texel.g : kInfinity;
    s.first = untagged(s.firstTagged);
    s.second = untagged(s.secondTagged);
    s.before = hit && !two;
    s.between = two;
    s.after = false;
    return s;
}

// Membership after every surface at depths <= d.
bool stateAt(Steps s, float d) {
    return d < s.first ? s.before : (d < s.second ? s.between : s.after);
}

// The least depth >= d (d itself or one of the steps) with membership
// `want`; +inf for none.
float seek(Steps s, float d, bool want) {
    if (stateAt(s, d) == want) return d;
    if (d < s.first && stateAt(s, s.first) == want) return s.first;
    if (d < s.second && s.after == want) return s.second;
    return kInfinity;
}

bool spent() {
    if (--budget >= 0) return false;
    writeUnresolved();
    return true;
}

// P after every surface at depths <= d (d may be kNone).
bool productAt(uvec4 block, float d) {
    for (uint j = 0u; j < block.y; ++j) {
        uvec4 literal = blockOperands[block.x + j];
        if (stateAt(stepsOf(literal.x), d) != (literal.w != 0u)) return false;
    }
    return true;
}

// The least surface depth above d (+inf for none), or the greatest below
// d (kNone for none), over every literal.
// A literal's least surface above d (+inf for none) and greatest below d
// (kNone for none).
float stepAbove(Steps s, float d) {
    return s.first > d ? s.first : (s.second > d ? s.second : kInfinity);
}

float stepBelow(Steps s, float d) {
    return s.second < d && s.second != kInfinity ? s.second : (s.first < d ? s.first : kNone);
}

// The same over every literal.
float surfaceAbove(uvec4 block, float d) {
    float best = kInfinity;
    for (uint j = 0u; j < block.y; ++j) best = min(best, stepAbove(stepsOf(blockOperands[block.x + j].x), d));
    return best;
}

float surfaceBelow(uvec4 block, float d) {
    float best = kNone;
    for (uint j = 0u; j < block.y; ++j) best = max(best, stepBelow(stepsOf(blockOperands[block.x + j].x), d));
    return best;
}

// A literal's surfaces at depth x, considered for the surface shown (evaluate.frag).
void considerStepsAt(Steps s, int leaf, float x, bool resultInside) {
    if (s.first == x) considerSurface(s.firstTagged, leaf, resultInside);
    if (s.second == x) considerSurface(s.secondTagged, leaf, resultInside);
}

int leafOfSlot(uvec4 block, uint slot) {
    return int(blockOperands[block.x + slot].z);
}

// The least depth >= from where P == target (+inf for none).
float seekProduct(uvec4 block, float from, bool target) {
    uint n = block.y;
    float d = from;
    if (target) {
        // Visit the literals in turn; one that is not content at d moves d
        // to its own first step after d where it would be.
        uint content = 0u;  // literals content at d in a row
        uint i = 0u;
        while (content < n && d != kInfinity) {
            if (--budget < 0) return kInfinity;
            uvec4 literal = blockOperands[block.x + i];
            float moved = seek(stepsOf(literal.x), d, literal.w != 0u);
            if (moved != d) {
                d = moved;
                content = 1u;
            } else {
                ++content;
            }
            i = i + 1u == n ? 0u : i + 1u;
        }
        return d;
    }
    // The first literal to stop being content.
    float least = kInfinity;
    for (uint j = 0u; j < n; ++j) {
        uvec4 literal = blockOperands[block.x + j];
        least = min(least, seek(stepsOf(literal.x), d, literal.w == 0u));
    }
    return least;
}

uvec4 productBlock = uvec4(0u);  // main's block, for the face's questions

// After every surface up to the face's end (faceEnd, which stays put once
// the face is complete, so the questions may wait for writeChosenSurface):
// the literals not content there, and the layer they all share (-1: none
// yet, -2: several). P is true where no literal is discontent; setting one
// operand the other way alone changes P where P is true (its literals turn
// discontent), or where every discontent literal is its own.
int discontent = 0;
int discontentLayer = -1;

void keepFaceState() {}

bool restoreFaceState() {
    return true;
}

// evaluate.frag's: the operand of layer `handle` set the other way alone.
bool operandDecides(int handle) {
    return discontent == 0 || discontentLayer == handle;
}

// evaluate.frag's: every literal's surfaces in the face, its operand named
// by its layer, once the literals' states there are counted.
void forEachFaceSurface() {
    discontent = 0;
    discontentLayer = -1;
    for (uint j = 0u; j < productBlock.y; ++j) {
        uvec4 literal = blockOperands[productBlock.x + j];
        if (stateAt(stepsOf(literal.x), faceEnd) == (literal.w != 0u)) continue;
        discontentLayer = discontent == 0 || discontentLayer == int(literal.x) ? int(literal.x) : -2;
        ++discontent;
    }
    for (uint j = 0u; j < productBlock.y; ++j) {
        uvec4 literal = blockOperands[productBlock.x + j];
        Steps s = stepsOf(literal.x);
        int leaf = int(literal.z);
        if (s.first >= faceStart && s.first <= faceEnd) weighSurface(s.firstTagged, leaf, int(literal.x));
        if (s.second != kInfinity && s.second >= faceStart && s.second <= faceEnd)
            weighSurface(s.secondTagged, leaf, int(literal.x));
    }
}

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    uvec4 block = vRecord;
    productBlock = block;
    uint n = block.y;
    budget = uLoopBudget;
    float tolerance = uCoincidence;
    bool isOr = block.z != 0u;

    // P before every surface: the seek for "P turns true" from before every
    // surface stays there exactly when P is true there already.
    float d = seekProduct(block, kNone, true);
    bool startsTrue = d == kNone;
    bool target = !startsTrue;
    if (startsTrue) d = seekProduct(block, kNone, false);
    // The result is P for an AND, !P for an OR; it is entered where it turns true.
    bool resultInside = startsTrue != isOr;
    while (true) {
        if (budget < 0) {
            writeUnresolved();
            return;
        }
        if (d == kInfinity) discard;
        // One round: the surfaces next to d, and those at d for the surface shown.
        startCluster();
        float below = kNone, above = kInfinity;
        for (uint j = 0u; j < n; ++j) {
            Steps s = stepsOf(blockOperands[block.x + j].x);
            below = max(below, stepBelow(s, d));
            above = min(above, stepAbove(s, d));
            considerStepsAt(s, leafOfSlot(block, j), d, resultInside);
        }
        if ((below == kNone || d - below > tolerance) && (above == kInfinity || above - d > tolerance)) {
            // A cluster of one depth, where P == target: the answer.
            break;
        }
        // The cluster holding d: its chain of close surfaces both ways.
        float anchor = d;
        while (below != kNone && anchor - below <= tolerance) {
            if (spent()) return;
            anchor = below;
            below = surfaceBelow(block, anchor);
        }
        float end = d;
        while (above != kInfinity && above - end <= tolerance) {
            if (spent()) return;
            end = above;
            above = surfaceAbove(block, end);
        }
        if (productAt(block, end) == target) {
            // The cluster's depths in order, P asked after each (evaluate.frag).
            startCluster();
            for (float x = anchor; x <= end; x = surfaceAbove(block, x)) {
                if (spent()) return;
                for (uint j = 0u; j < n; ++j) {
                    considerStepsAt(stepsOf(blockOperands[block.x + j].x), leafOfSlot(block, j), x, resultInside);
                }
                noteResult(productAt(block, x) != isOr, resultInside);
            }
            break;
        }
        // d lay on a sliver: seek on from the next cluster.
        d = above == kInfinity ? kInfinity : seekProduct(block, above, target);
    }
    // Written out of the loop, so that its work runs once (evaluate.frag).
    writeChosenSurface(!resultInside);
}
