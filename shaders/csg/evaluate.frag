// The CSG evaluator: one draw per shader variant over the tile's blocks
// (evaluate.vert) whose tree is not constant.
//
// Per pixel, every operand's peeled layers give its surfaces in depth order:
//   near_0 < near_1 < ... < near_{n-1} <= far_{n-1} < ... < far_0
// (layer l holds (-near_l, far_l); near == far when the last layer caught a
// single surface). The evaluator walks all operands' surfaces front to back,
// keeps each operand's inside/outside state (a front face enters, a back
// face leaves; an operand whose first surface is a back face was inside from
// the near plane on), and stops at the first depth where the result's
// membership changes. Every surface at one depth, of any operand, takes
// effect before the tree is asked again: coincident faces cancel as the
// solids say (a cube minus an equal cube leaves nothing).
//
// Four forms of the walk, one per file, each for the blocks it holds most
// cheaply (EvaluatePass.cpp picks a block's form; every instruction of a
// variant runs for every pixel on llvmpipe, used or not):
//   evaluate-first-surface.glsl  the block's tree is one operand of one layer
//   evaluate-register.glsl       up to eight peeled layers in all: a slot per
//                                layer in vector components, the tree as a
//                                truth table (MAX_LIVE 4 or 8 slots)
//   evaluate-product.glsl        one AND or OR of operands of one layer each
//   evaluate-array.glsl          anything else: a heap of surfaces and a
//                                counting tree in per-pixel arrays of MAX_LIVE
// This file holds what they share: the inputs, the outputs and how a surface
// is written.
//
// Output: the visible surface's tagged depth and its leaf code (leafCode in
// interface.glsl: the leaf, flipped where its own membership changes against
// the result's, as a subtracted operand's does). Pixels with no surface are
// discarded: the targets were cleared to "miss", and the stencil marks only
// pixels written. LEAF_MARKS: the mark names the leaf's mark slot
// (stencilMark in interface.glsl).
#ifdef LEAF_MARKS
#extension GL_ARB_shader_stencil_export : require
#endif
#include "csg/interface.glsl"
#include "csg/surface.glsl"

layout(binding = kTextureLayers) uniform sampler2DArray uLayers;

#include "csg/blocks.glsl"

layout(location = kEvaluateTileOrigin) uniform ivec2 uTileOrigin;  // the tile's lower-left pixel in the frame
// Per tree leaf: bit faceBit(exit, flip) set where the evaluator reported
// such a face of the leaf in this tile. The normal pass draws only those
// faces of each operand.
layout(std430, binding = kBufferShownFaces) buffer ShownFaces {
    uint shownFaces[];
};

#ifdef LEAF_MARKS
// Per tree leaf: its mark slot (FrameTargets::assignMarkSlots).
layout(std430, binding = kBufferMarkSlots) readonly buffer MarkSlots {
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
// GROUPS: the compiled tree has groups (the lookup costs every written pixel).
#ifdef GROUPS
layout(binding = kTextureGroupIds) uniform usampler2DArray uGroupIds;  // tile pixels: entry | exit << kMemberBits
layout(std430, binding = kBufferGroupTable) readonly buffer GroupTable {
    int groupTable[];
};

bool isGroup(int leaf) {
    return groupTable[leaf] >= 0;
}

int surfaceLeaf(int leaf, bool exit) {
    int at = groupTable[leaf];
    if (at < 0) return leaf;
    uint ids = texelFetch(uGroupIds, ivec3(pixel, groupTable[at]), 0).r;
    return groupTable[at + 1 + int(exit ? ids >> kMemberBits : ids & kNoMember)];
}
#else
bool isGroup(int leaf) {
    return false;
}

int surfaceLeaf(int leaf, bool exit) {
    return leaf;
}
#endif

// Inside at the start: an operand is inside where the ray starts when an
// odd number of its surfaces lie ahead, as the reference counts crossings.
// The facing of its first surface would say the same in exact arithmetic,
// but where a ray grazes an operand's silhouette, rounding can put its exit
// a hair before its entry, and the operand would then read as inside all
// along: a pinhole through the surface in front of it.
//
// A ray that passes a hair outside an operand's silhouette edge: the
// rasterizer snaps vertices to its subpixel grid, so it may give the pixel
// to both faces of the edge, and their planes, extended past the edge, meet
// the ray in reverse order: the back face (an exit) before the front face
// (an entry), as far apart as the back face is steep there. Exact arithmetic
// sees neither. Taken as they come, the two would leave the operand inside
// over a sliver that is not there, shown as the back face flipped: a speck
// where the edge lies on another solid's face. So an operand whose only
// surfaces at a pixel are one layer's exit and then entry has none there. A
// closed solid never gives that order to an exact ray that starts outside
// it; the reference drops such a pair too.
//
// exitThenEntry takes a layer's two tagged surfaces as the forms hold them
// (`far` +inf or equal to `near` where the layer caught one surface);
// grazesOutside a layer as peeled.
bool exitThenEntry(float near, float far) {
    return far != kInfinity && far > near && isExit(near) && !isExit(far);
}

bool grazesOutside(vec2 layer) {
    return -layer.r < kClearedDepth && exitThenEntry(-layer.r, layer.g);
}

// Coincident surfaces (docs/algorithm.md): surfaces of any operands that
// follow each other along the ray with untagged depths no more than
// uCoincidence apart are one place, a cluster (a chain: each surface within
// the tolerance of the one before it, so two surfaces that rounding alone
// parts are never split). Each surface of a cluster toggles its operand (a
// pair of one operand's surfaces cancels: a sliver thinner than the
// tolerance is no solid), and only then is the tree asked again. The CPU
// reference clusters the same way.
layout(location = kEvaluateCoincidence) uniform float uCoincidence;

// The surface shown where the result changes, chosen among the cluster's.
// Its surfaces are taken in depth order, the tree asked after each depth:
// the first surface after which the result differs from its start is
// where exact arithmetic would see it change (at the seam of two touching
// blocks, the outer face; at the rim of an intersection, the member
// entered last). Surfaces within a quarter of the tolerance of each other
// are one face as far as rounding can tell (a chain again). Of the face
// holding that first change, the surface shown is one whose operand decides
// the result there: with every operand as it is after the face, setting
// that one operand back alone would undo the change. Where a surface of
// another solid only crosses the face (a tooth's side through a cut face, a
// hair in front of it or behind), its operand decides nothing there, and
// it is not shown. Where every surface of the face decides, or none does
// (the top shared by the blocks of a union: no one block alone makes it),
// any may be shown. Among those: one whose facing changes its operand as
// the result changes (the result's own face), else one facing the other
// way (a subtracted face, flipped); the lowest tree leaf, then the nearest.
// So a face that several leaves share shows one leaf and one colour from
// every view, and a face that one leaf makes shows that leaf. The
// reference's rule too.
//
// Each form says what "decides" means for its own state and where a face's
// surfaces are: operandDecides, asked with the form's handle of an operand
// (a truth-table bit, a heap slot, a layer) while every operand is as it is
// after the face, and forEachFaceSurface, which hands weighSurface every
// surface whose untagged depth lies in [faceStart, faceEnd] (the face: its
// surfaces were walked in depth order, each within a quarter of the
// tolerance of the one before). The forms consider a surface before they
// apply it; once the face of the first change is complete (settleDue, set by
// the first surface of the next face) they call keepFaceState at one place
// of their walk, before they apply that surface, and writeChosenSurface
// calls it where the face ends with the cluster. keepFaceState keeps what
// operandDecides will need (the register form its inside bits; the array
// form starts a list of the operands it sets afterwards, which
// restoreFaceState sets back; the product form needs nothing, its state is
// a function of depth), and writeChosenSurface settles the face. The
// register and array forms write after their walk's loop: on llvmpipe every
// instruction inside the loop runs on every pass, taken or not, so the
// asking stays out of it.
bool operandDecides(int handle);
void forEachFaceSurface();
void keepFaceState();
bool restoreFaceState();  // false: the state after the face is lost, do not ask
bool faceSettled = false;  // settleFace has run for the face of the first change

const int kNoLeaf = 0x7fffffff;
bool changed;           // the result has differed from its start in this cluster
bool chosen;            // the face of the first change has ended: pick is final
bool settleDue = false; // chosen, and the face's surfaces not yet asked
float faceStart = -kInfinity;  // untagged depth of the current face's first surface
float faceEnd = -kInfinity;    // and of its last
int faceCount = 0;             // its surfaces
bool faceResultInside = false; // the result's membership before the cluster (writeChosenSurface's)
int pickLeaf;           // the current face's best surface so far
float pickSurface;      // its tagged depth
bool pickSame;          // it changes its operand as the result changes

void startFace(float depth) {
    pickLeaf = kNoLeaf;
    faceStart = depth;
    faceCount = 0;
}

void startCluster() {
    settleDue = false;
    faceSettled = false;
    changed = false;
    chosen = false;
    faceEnd = -kInfinity;
    pickSurface = kInfinity;
    pickSame = false;
    startFace(-kInfinity);
}

// Whether a surface (leaf, tagged, same) is shown before another (kNoLeaf:
// none yet): the result's own face first, then the lowest leaf, then the nearest.
bool shownBefore(int leaf, float tagged, bool same, int otherLeaf, float otherTagged, bool otherSame) {
    return otherLeaf == kNoLeaf || (same && !otherSame) ||
           (same == otherSame && (leaf < otherLeaf || (leaf == otherLeaf && tagged < otherTagged)));
}

// While settleFace asks: the face's surfaces handed over, those whose
// operand decides, and the first of those.
int weighed = 0, deciding = 0;
int decidingLeaf = kNoLeaf;
float decidingSurface = kInfinity;
bool decidingSame = false;

// A surface of the face (forEachFaceSurface), as considerSurface takes it.
void weighSurface(float tagged, int leaf, int handle) {
    ++weighed;
    if (!operandDecides(handle)) return;
    ++deciding;
    leaf = surfaceLeaf(leaf, isExit(tagged));
    bool same = isExit(tagged) == faceResultInside;
    if (shownBefore(leaf, tagged, same, decidingLeaf, decidingSurface, decidingSame)) {
        decidingLeaf = leaf;
        decidingSurface = tagged;
        decidingSame = same;
    }
}

// The face is complete, every operand as it is after it: where some of its
// surfaces' operands decide the result and some do not, the pick is the
// first of those that do.
void settleFace() {
    faceSettled = true;
    if (faceCount < 2 || !restoreFaceState()) return;
    weighed = 0;
    deciding = 0;
    decidingLeaf = kNoLeaf;
    forEachFaceSurface();
    if (deciding == 0 || deciding == weighed) return;
    pickLeaf = decidingLeaf;
    pickSurface = decidingSurface;
    pickSame = decidingSame;
}

// A surface of the cluster, in depth order, considered before the form
// applies it: `tagged` its tagged depth, `leaf` its operand's tree leaf (a
// group's: the member that makes the surface is the leaf compared and
// kept); `resultInside` the result's membership before the cluster.
void considerSurface(float tagged, int leaf, bool resultInside) {
    if (chosen) return;
    leaf = surfaceLeaf(leaf, isExit(tagged));
    float depth = untagged(tagged);
    if (depth - faceEnd > uCoincidence * 0.25) {
        if (changed) {  // the face of the first change is complete
            settleDue = true;
            chosen = true;
            return;
        }
        startFace(depth);
    }
    faceEnd = depth;
    ++faceCount;
    bool same = isExit(tagged) == resultInside;
    if (shownBefore(leaf, tagged, same, pickLeaf, pickSurface, pickSame)) {
        pickLeaf = leaf;
        pickSurface = tagged;
        pickSame = same;
    }
}

// After the surfaces at one depth: the result's membership now.
void noteResult(bool now, bool resultInside) {
    if (now != resultInside) changed = true;
}

#ifdef PLAIN_BESIDE
// Plain leaves beside the CSG (PlainPass.h): the root is a union of those
// leaves and of this tree, and every ray starts outside, so the result's
// first surface is the nearer of the plain leaves' nearest front face,
// drawn into resultDepth and resultLeaf before this pass, and this tree's
// first surface. This pass reads those two images at its own pixel and
// writes it only where its surface is shown: where it lies nearer by more
// than a quarter of the tolerance (one face as far as rounding can tell,
// "the surface shown" above), or lies in one face with the plain surface
// and comes before it by that rule (its own face before a flipped one,
// then the lowest leaf, then the nearest). Elsewhere the pixel keeps the
// plain leaf's surface, its normal and its mark. Each pixel is read and
// written once, by its own invocation, after a texture barrier.
layout(binding = kTexturePlainDepth) uniform sampler2D uPlainDepth;
layout(binding = kTexturePlainLeaf) uniform isampler2D uPlainLeaf;

bool plainShownBefore(float tagged, int leaf, bool same) {
    int code = texelFetch(uPlainLeaf, ivec2(gl_FragCoord.xy), 0).r;
    if (code < 0) return false;
    float plain = texelFetch(uPlainDepth, ivec2(gl_FragCoord.xy), 0).r;
    float reach = uCoincidence * 0.25;
    if (untagged(plain) < untagged(tagged) - reach) return true;
    if (untagged(tagged) < untagged(plain) - reach) return false;
    return !shownBefore(leaf, tagged, same, leafOfCode(code), plain, true);
}
#else
bool plainShownBefore(float tagged, int leaf, bool same) {
    return false;
}
#endif

// Writes the chosen surface where the result was entered (`entered`) or
// left: its own tagged depth (the normal pass finds its fragment by it) and
// its leaf code (leafCode in interface.glsl: flipped where its operand
// changes against the result, as a subtracted one does).
void writeChosenSurface(bool entered) {
    faceResultInside = !entered;
    if (!chosen) keepFaceState();  // the face ends with the cluster
    if (!faceSettled) settleFace();
    bool exit = isExit(pickSurface);
    bool flip = exit == entered;
    int leaf = pickLeaf;
    if (plainShownBefore(pickSurface, leaf, !flip)) discard;
    outDepth = pickSurface;
    outLeaf = leafCode(leaf, flip);
    int face = faceBit(exit, flip);
    // A plain read first: the first pixels of a face set its bit, and the
    // rest find it set, where an atomic per pixel costs llvmpipe a locked
    // operation per lane. A stale read costs only an atomic more.
    if ((shownFaces[leaf] & (1u << face)) == 0u) atomicOr(shownFaces[leaf], 1u << face);
#ifdef LEAF_MARKS
    gl_FragStencilRefARB = stencilMark(markSlots[leaf], face);
#endif
}

// The walk's clusters, for the forms that take surfaces one depth at a time
// (register and array): call with the nearest surface left (tagged, +inf
// for none) and the result's membership now, before taking the surfaces at
// that depth. A surface beyond the open cluster's reach (the tolerance past
// its last surface) closes it; if the result then differs from `inside`
// (its membership at the start), the chosen surface is to be written, after
// the walk: writeChosenSurface(walkEntered).
const int kWalkOn = 0;       // take the surfaces at `nearest`
const int kWalkWritten = 1;  // the surface is chosen: stop, and write it
bool walkEntered = false;
const int kWalkDone = 2;     // no surface left and no change: discard
bool clusterOpen = false;
float clusterReach = -kInfinity;

#ifdef RESULT_PEEL
// Peeling the result (Renderer::sampleResult): each round reports the next
// place along the ray where the result changes, after the one the round
// before reported (uResultStart: its tagged depth; -inf before the first
// round, +inf once a ray has no more). The surfaces up to it, and those
// chained to it within the tolerance (the rest of its cluster), are taken
// without a look; the result's membership after them is where the walk
// starts, so the change found next is an entry or an exit of the result.
layout(binding = kTextureResultStart) uniform sampler2D uResultStart;  // frame pixels
bool skipping = true;
float skipReach = -kInfinity;

void startSkipping() {
    skipReach = untagged(texelFetch(uResultStart, ivec2(gl_FragCoord.xy), 0).r);
}
#endif

// Whether the walk ends here with the chosen surface written: the
// surface next (`nearest`, +inf for none) lies beyond the open cluster's
// reach, and the result (`now`) differs from `inside`, its membership at
// the cluster's start.
bool closesChangedCluster(float nearest, bool now, bool inside) {
    if (!clusterOpen || now == inside || (nearest != kInfinity && untagged(nearest) <= clusterReach)) return false;
    walkEntered = !inside;
    return true;
}

// walkTo's test, asked by the forms at the end of the step that took a
// surface rather than at the next step's walkTo: the step that takes a
// cluster's last surface ends the walk. The result peel's walk keeps to
// walkTo, whose start skips surfaces first.
bool walkEndsAfterStep(float nearest, bool now, bool inside) {
#ifdef RESULT_PEEL
    return false;
#else
    return closesChangedCluster(nearest, now, inside);
#endif
}

// `inside`: the result's membership at the walk's start (inout for the
// result peel, which moves the start past the surfaces already reported).
int walkTo(float nearest, bool now, inout bool inside) {
#ifdef RESULT_PEEL
    if (skipping) {
        if (nearest == kInfinity) return kWalkDone;
        float depth = untagged(nearest);
        if (depth <= skipReach) {
            skipReach = max(skipReach, depth + uCoincidence);
            return kWalkOn;
        }
        skipping = false;
        inside = now;
    }
#endif
    if (closesChangedCluster(nearest, now, inside)) return kWalkWritten;
    if (nearest == kInfinity || untagged(nearest) > clusterReach) {
        if (nearest == kInfinity) return kWalkDone;
        startCluster();
        clusterOpen = true;
    }
    clusterReach = untagged(nearest) + uCoincidence;
    return kWalkOn;
}

#if defined(PRODUCT_FORM) || defined(ARRAY_FORM)
// Loop iterations this invocation may spend. llvmpipe ends every loop of a
// shader invocation once 65535 iterations have run in all (gallivm's loop
// limiter), which would leave a deep pixel half-evaluated and wrong. A pixel
// whose walk would overrun the budget is marked unresolved (kLeafUnresolved,
// no surface) instead, and the renderer reports how many there were. Real
// GPUs have no such limit: the renderer passes a budget no pixel reaches.
layout(location = kEvaluateLoopBudget) uniform int uLoopBudget;

int budget;

void writeUnresolved() {
    outDepth = kInfinity;
    outLeaf = kLeafUnresolved;
#ifdef LEAF_MARKS
    gl_FragStencilRefARB = 0;  // no surface: no later pass needs the pixel
#endif
}
#endif

#if defined(FIRST_SURFACE_FORM)
#include "csg/evaluate-first-surface.glsl"
#elif defined(REGISTER_FORM)
#include "csg/evaluate-register.glsl"
#elif defined(PRODUCT_FORM)
#include "csg/evaluate-product.glsl"
#else
#include "csg/evaluate-array.glsl"
#endif
