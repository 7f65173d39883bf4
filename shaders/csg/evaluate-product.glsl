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
// Depths here are untagged: every surface at one depth takes effect before
// the tree is asked again, as in the other forms. The leaves written are
// those of the lowest slot with an entry (exit) at the chosen depth, the
// register form's choice.
//
// Cost: n literal visits when the answer is the first surface, up to n per
// move otherwise (the slots of one pixel that move d in slot order cost one
// round in all: a stack of subtracted solids listed front to back).

const float kNone = -kInfinity;  // d before every surface

// An operand's surfaces along the ray from its one layer: `first` and
// `second` (untagged; +inf where missing) and its membership before the
// first, between them and after the second. An operand whose first surface is
// a back face was inside from the ray's start.
struct Steps {
    float first, second;
    bool before, between, after;
};

Steps stepsOf(uint layer) {
    vec2 texel = texelFetch(uLayers, ivec3(pixel, int(layer)), 0).rg;
    float near = -texel.r;
    bool hit = near < kClearedDepth;
    bool two = hit && texel.g > near;
    Steps s;
    s.first = hit ? untagged(near) : kInfinity;
    s.second = two ? untagged(texel.g) : kInfinity;
    s.before = hit && isExit(near);
    s.between = hit && !isExit(near);
    s.after = two ? !isExit(texel.g) : s.between;
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

// The first step where membership stops being `want` (it is `want` before
// every surface); +inf for none.
float leave(Steps s, bool want) {
    return stateAt(s, s.first) != want ? s.first : (s.after != want ? s.second : kInfinity);
}

int entrySlot, exitSlot;  // the lowest slot with an entry / an exit at the chosen depth

void noteSurfacesAt(Steps s, float d, int slot) {
    bool entry = (s.first == d && s.between) || (s.second == d && s.after);
    bool exit = (s.first == d && s.before) || (s.second == d && !s.after);
    if (entry && slot < entrySlot) entrySlot = slot;
    if (exit && slot < exitSlot) exitSlot = slot;
}

int leafOfSlot(uvec4 block, int slot) {
    return slot < int(block.y) ? int(blockOperands[block.x + uint(slot)].z) : -1;
}

void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    uvec4 block = vRecord;
    uint n = block.y;
    budget = uLoopBudget;
    entrySlot = exitSlot = int(n);

    // P false before every surface: where does it turn true?
    float d = kNone;
    uint content = 0u;  // literals content at d in a row
    uint i = 0u;
    while (content < n && d != kInfinity) {
        if (--budget < 0) {
            writeUnresolved();
            return;
        }
        uvec4 literal = blockOperands[block.x + i];
        Steps s = stepsOf(literal.x);
        float moved = seek(s, d, literal.w != 0u);
        if (moved != d) {
            d = moved;
            content = 1u;
            entrySlot = exitSlot = int(n);
        } else {
            ++content;
        }
        noteSurfacesAt(s, d, int(i));
        i = i + 1u == n ? 0u : i + 1u;
    }
    bool startsTrue = d == kNone;
    // P true before every surface: where does it turn false?
    if (startsTrue) {
        d = kInfinity;
        for (uint j = 0u; j < n; ++j) {
            uvec4 literal = blockOperands[block.x + j];
            d = min(d, leave(stepsOf(literal.x), literal.w != 0u));
        }
        for (uint j = 0u; d != kInfinity && j < n; ++j) noteSurfacesAt(stepsOf(blockOperands[block.x + j].x), d, int(j));
    }
    if (d == kInfinity) discard;
    // The result is P for an AND, !P for an OR; it is entered where it turns true.
    bool isOr = block.z != 0u;
    writeSurface(d, startsTrue == isOr, leafOfSlot(block, entrySlot), leafOfSlot(block, exitSlot));
}
