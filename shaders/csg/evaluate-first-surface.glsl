// The first-surface form of evaluate.frag, for blocks whose tree is one
// operand, not negated, of one peeled layer (a cheese's cube where no hole
// reaches, one tooth of a union of teeth): the result is the operand, so its
// first surface is the result's. A front face there enters both; a back face
// (the eye inside the operand) leaves both. Where the layer's two surfaces
// lie in one cluster (evaluate.frag: a ray grazing an edge, a sheet thinner
// than the tolerance) the operand is entered and left at once and the
// result shows nothing. This is the
// register form's walk for one slot, step for step.
//
// blocks[b]: x the operand's layer in uLayers, y its tree leaf, z (with leaf
// marks) the leaf's stencilMark for a front face; nothing in blockOperands.
// The renderer marks the leaf's front faces shown for every such block
// (EvaluatePass.cpp), so only the rare back face needs the atomic; a
// group's member is known here only, so it always does.
void main() {
    pixel = ivec2(gl_FragCoord.xy) - uTileOrigin;
    vec2 layer = texelFetch(uLayers, ivec3(pixel, vRecord.x), 0).rg;
    float first = -layer.r;
    bool two = layer.g > first;
    if (first >= kClearedDepth || grazesOutside(layer) || (two && untagged(layer.g) <= untagged(first) + uCoincidence))
        discard;
    // Two surfaces: the ray starts outside and enters here; one: it starts
    // inside and leaves (evaluate.frag, "inside at the start"). A surface
    // whose facing says otherwise (rounding on a sliver triangle) is the
    // result's face flipped, as the other forms have it.
    bool exit = isExit(first);
    bool flip = exit == two;
    int face = faceBit(exit, flip);
    bool grouped = isGroup(int(vRecord.y));
    int leaf = surfaceLeaf(int(vRecord.y), exit);
    if (plainShownBefore(first, leaf, !flip)) discard;
    outDepth = first;
    outLeaf = leafCode(leaf, flip);
    if (face != 0 || grouped) atomicOr(shownFaces[leaf], 1u << face);
#ifdef LEAF_MARKS
    // The record carries the leaf's mark, but not a group member's.
    gl_FragStencilRefARB = grouped ? stencilMark(markSlots[leaf], face) : int(vRecord.z) + face;
#endif
}

// evaluate.frag's: never asked, one operand has no face to share.
bool operandDecides(int handle) {
    return true;
}

void forEachFaceSurface() {}
void keepFaceState() {}

bool restoreFaceState() {
    return false;
}
