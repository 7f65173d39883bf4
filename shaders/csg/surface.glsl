// Tagged depths: how the peel, evaluate and normal passes name one surface.
//
// A surface's linear view depth dot(P - eye, f) is > 0 beyond the near plane.
// Its lowest mantissa bit is replaced by its facing: 0 for a front face (the
// ray enters the operand there), 1 for a back face (the ray leaves it). For
// positive floats the bit pattern orders like the value, so MAX blending and
// sorting still order surfaces by depth (to within one ulp), and an entry and
// an exit at the same depth (a ray grazing a silhouette edge) stay two
// distinct values with the entry first: the operand is left outside after
// the pair, as it should be.

float taggedDepth(float viewDepth, bool frontFacing) {
    uint bits = (floatBitsToUint(viewDepth) & ~1u) | (frontFacing ? 0u : 1u);
    return uintBitsToFloat(bits);
}

bool isExit(float tagged) {
    return (floatBitsToUint(tagged) & 1u) != 0u;
}

// The depth with the facing bit cleared: equal for surfaces at one depth.
float untagged(float tagged) {
    return uintBitsToFloat(floatBitsToUint(tagged) & ~1u);
}

// A depth no surface has: a miss, or none left.
const float kInfinity = uintBitsToFloat(0x7f800000u);
