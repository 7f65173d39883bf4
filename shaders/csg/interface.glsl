// What the C++ passes (engine/render/) and the shaders under shaders/csg/
// agree on: uniform locations, binding points, and the encodings of the
// values that cross between them. Each is written here once.
//
// The file is GLSL and C++ at once: the shaders #include it, and
// engine/render/ShaderInterface.h includes it inside the namespace
// strata::render::shader. So it holds only what both languages read alike:
// `SHARED` constants of int, uint and float, and `SHARED_FUNCTION`s on
// them. A constant a layout qualifier names must be an int.
#ifndef STRATA_SHADER_INTERFACE
#define STRATA_SHADER_INTERFACE

#ifdef __cplusplus
#define SHARED inline constexpr
#define SHARED_FUNCTION inline constexpr
#else
#define SHARED const
#define SHARED_FUNCTION
#endif

// --- Uniform locations, per stage ---

// surface.vert: every pass that draws the leaves (peel, group peel, normal, translucent).
SHARED int kSurfaceViewProjection = 0;
SHARED int kSurfaceEye = 1;
SHARED int kSurfaceForward = 2;  // the unit view direction f
SHARED int kSurfaceReversedDepth = 12;  // REVERSED_DEPTH: the clip depth's terms, above every fragment stage's
// A fragment's ray P = O + s D (s its view depth), O and D affine in
// gl_FragCoord.xy: the constant term at +0, the x and y terms at +1 and +2
// (setSurfaceView). Above every fragment stage's.
SHARED int kSurfaceOrigin = 20;
SHARED int kSurfaceRay = 23;
// A face plane's offset (surface.vert's attribute 1) that says: one leaf
// alone has this plane (FacePlanes); far beyond any coordinate strata takes.
SHARED float kOwnPlane = 1.0e37;

// peel.frag (after surface.vert's).
SHARED int kPeelPreviousLayer = 3;  // the layer the next pass reads
SHARED int kPeelKeyBase = 4;        // GROUP: the bits below every fragment's tagged depth
SHARED int kPeelTieTolerance = 6;   // GROUP_TIE: the depth within which a member ties with the winner

// light.glsl, in every program that lights a surface (shade.frag, plain.frag's
// LIT, alpha.frag's REAR), above every fragment stage's own; its view
// direction is surface.vert's kSurfaceForward. Strata's light: the view;
// OPENSCAD_LIGHT: the light's unit direction, world space.
SHARED int kLightRight = 13;
SHARED int kLightUp = 14;
SHARED int kLightHalfExtent = 15;  // tan(fov/2) * (aspect, 1)
SHARED int kLightOrthographic = 16;
SHARED int kLightSize = 17;        // the frame, pixels
SHARED int kLightToLight = 18;

// plain.frag (after surface.vert's).
SHARED int kPlainTieTolerance = 3;  // TIE: the depth within which a leaf ties with the nearest

// resolve.frag.
SHARED int kResolveFirstLayer = 0;
SHARED int kResolveLayerCount = 1;

// group.frag.
SHARED int kGroupIdsLayer = 0;  // the group's layer of the ids image

// evaluate.vert and evaluate.frag.
SHARED int kEvaluateTileOrigin = 2;  // the tile's lower-left pixel in the frame
SHARED int kEvaluateLoopBudget = 4;  // the array and product forms
SHARED int kEvaluateFirstBlock = 5;  // this draw's first run of blocks in drawnBlocks
SHARED int kEvaluateTileSize = 6;    // pixels
SHARED int kEvaluateBlocksX = 7;     // blocks per row of the tile
SHARED int kEvaluateCoincidence = 8;  // the coincidence tolerance, a view depth

// normal.frag (after surface.vert's).
SHARED int kNormalLeaf = 3;
SHARED int kNormalBaseColor = 5;
SHARED int kNormalFlip = 6;  // TRUST_MARKS only
SHARED int kNormalConvex = 7;  // the checking variant: 1 where the leaf is convex
SHARED int kNormalSlack = 8;   // the checking variant: the depth's slack, in its change across a pixel

// translucent.frag (after surface.vert's).
SHARED int kTranslucentColor = 3;
SHARED int kTranslucentToLight = 5;
SHARED int kTranslucentFromWindow = 6;  // WINDOW_DEPTH: the plain pass's window depth back to a view depth

// alpha.frag (the REAR variant after surface.vert's).
SHARED int kAlphaCodes = 3;        // the leaf codes whose pixels this draw blends over
SHARED int kAlphaColor = 4;        // the leaf's colour, straight alpha
SHARED int kAlphaBackground = 5;   // the scheme's background

// shade.frag.
SHARED int kShadeBackground = 0;

// --- Binding points ---

// Shader storage buffers.
SHARED int kBufferBlockNodes = 0;     // evaluate: the blocks' inner nodes (blocks.glsl)
SHARED int kBufferMarkSlots = 1;      // evaluate: each leaf's mark slot
SHARED int kBufferBlocks = 2;         // evaluate: each block's record
SHARED int kBufferBlockOperands = 3;  // evaluate: the blocks' literals or slots
SHARED int kBufferDrawnBlocks = 4;    // evaluate: runs of blocks to draw
SHARED int kBufferShownFaces = 5;     // evaluate: per leaf, the faces the result shows
SHARED int kBufferGroupTable = 6;     // evaluate: groups of convex operands and their members
SHARED int kBufferDrawLayers = 6;     // peel's convex batch (surface.vert LAYERED): each draw's layer
SHARED int kBufferResolveStats = 7;   // resolve: the most layers, and overflow
SHARED int kBufferPlainColors = 0;    // plain: each leaf's packed base colours

// Texture units.
SHARED int kTextureLayers = 0;        // peel (the previous layer), evaluate: the peeled layers
SHARED int kTextureGroupIds = 3;      // evaluate: a group's entry and exit members
SHARED int kTextureResultStart = 4;   // evaluate RESULT_PEEL: the surface the round before reported
SHARED int kTextureGroupScratch = 0;  // group: the winning entry and exit
SHARED int kTextureGroupWinners = 1;  // peel GROUP_TIE: a copy of the winning entry and exit
SHARED int kTextureResultDepth = 0;   // normal, translucent: the evaluator's depth
SHARED int kTextureWindowDepth = 0;   // translucent WINDOW_DEPTH: the plain frame's own depth image
SHARED int kTextureResultLeaf = 1;    // normal, alpha: the evaluator's leaf code
SHARED int kTextureNormal = 0;        // shade: normal and base colour
SHARED int kTexturePlainNearest = 0;  // plain TIE: a copy of the nearest pass's depths
SHARED int kTexturePlainDepth = 5;    // evaluate PLAIN_BESIDE: the plain leaves' depth (resultDepth)
SHARED int kTexturePlainLeaf = 6;     // evaluate PLAIN_BESIDE: and their leaf codes (resultLeaf)

// Image units.
SHARED int kImageFragmentCounts = 1;  // peel COLLECT, resolve
SHARED int kImageFragments = 2;       // peel COLLECT, resolve
SHARED int kImageLayers = 3;          // resolve: the layers it writes
SHARED int kImageGroupIds = 3;        // group: the ids it writes

// --- Peeled layers ---

// A layer texel no surface reached holds (-FLT_MAX, -FLT_MAX); any depth of
// at least this size is such a texel, never a surface.
SHARED float kClearedDepth = 3.0e38f;

// Fragments a pixel's list holds when collecting; resolve.frag reads them
// as two vec4s, so it is written for exactly this many.
SHARED int kCollectCapacity = 8;

// A group's ids (GroupPeel.h): entry member | exit member << kMemberBits,
// kNoMember in the entry where no member had one.
SHARED uint kMemberBits = 16u;
SHARED uint kNoMember = 0xffffu;

// --- The evaluator's blocks (blocks.glsl) ---

SHARED int kBlock = 16;  // pixels on a side of a block

// The register form's slots: the layer in the low kSlotLayerBits bits, and
// above them the slot's operand's bit in the truth table (kSlotOperandMask).
SHARED uint kSlotLayerBits = 16u;
SHARED uint kSlotLayerMask = (1u << kSlotLayerBits) - 1u;
SHARED uint kSlotOperandMask = 7u;

// The array form's literals: y holds the operand's layer count below
// kRunShift, and on an operand's first literal the number of its literals
// (which follow each other) above; w its parent node, | kNegate where the
// literal is complemented.
SHARED uint kRunShift = 16u;
SHARED uint kLayerCountMask = (1u << kRunShift) - 1u;
SHARED uint kNegate = 0x80000000u;
// The array form's inner nodes: x the parent, kNoParent for the root; y
// kNodeAnd for AND, 0 for OR.
SHARED uint kNoParent = 0xffffffffu;
SHARED uint kNodeAnd = 1u;

// --- What the evaluator writes ---

// The face bit of a surface: 0 for a front face (the ray enters the leaf),
// 1 for a back face, plus 2 where the leaf acts subtracted there (flipped).
// Bit faceBit of shownFaces[leaf] says the result shows such a face.
SHARED_FUNCTION int faceBit(bool exit, bool flip) {
    return (exit ? 1 : 0) + (flip ? 2 : 0);
}

// The stencil mark of a pixel that shows a leaf of mark slot `slot`
// (FrameTargets.h): four marks per slot, one per face bit. 0 is no mark.
SHARED int kMarkSlots = 63;  // 4 * 63 + 1 < 256
SHARED_FUNCTION int stencilMark(int slot, int face) {
    return 1 + 4 * slot + face;
}
// The one mark for every written pixel where marks do not name leaves.
SHARED int kMarkWritten = 2;
// The mark of a pixel that a plain leaf drawn beside the CSG shows
// (PlainPass.h): above every leaf's mark, so no normal-pass draw takes it.
SHARED int kMarkPlain = 255;

// The leaf code (FrameTargets::resultLeaf): the leaf of the visible surface
// and whether it is flipped there; kLeafMiss where the result has no
// surface, kLeafUnresolved where the evaluator ran out of loop budget.
SHARED int kLeafMiss = -1;
SHARED int kLeafUnresolved = -2;
SHARED_FUNCTION int leafCode(int leaf, bool flip) {
    return leaf * 2 + (flip ? 1 : 0);
}
SHARED_FUNCTION int leafOfCode(int code) {
    return code < 0 ? kLeafMiss : code >> 1;
}
SHARED_FUNCTION bool flipOfCode(int code) {
    return (code & 1) != 0;
}

#undef SHARED
#undef SHARED_FUNCTION
#endif
