#pragma once
// The plain path: a frame whose tree is a union of leaves (no difference,
// no intersection, no complement once compiled), every leaf a solid with
// volume, and every ray starting outside all of them (the scene beyond the
// near plane). The result's first surface is then the nearest entry into
// any leaf, so the frame needs no peel, no evaluator and no normal pass:
// the leaves' front faces are drawn depth-tested straight into the G-buffer
// (FrameTargets: depth, leaf code, normal and base colour), and the stencil
// marks every pixel written, for the shade pass (shaders/csg/plain.frag).
//
// Where the frame has no outline (RenderSettings::outline), which alone needs
// the G-buffer around a pixel, the same draws also light each fragment and
// write its colour (plain.frag's LIT): the frame then needs no shade pass.
//
// Two geometry passes at most, each one multi-draw over the leaves
// (SceneBuffers::leafVertexArray: each fragment knows its leaf), with the
// depth reversed (near / depth: a float's relative precision at every
// depth; surface.vert's REVERSED_DEPTH) so that the depth test orders
// surfaces as finely as their view depths do:
//   - nearest: every leaf in ascending order, depth test GREATER: the
//     nearest surface, the lowest leaf among exactly equal ones;
//   - ties: only the leaves whose boxes come within the tolerance of
//     another leaf's (mayTie), in descending order, pulled toward the eye
//     and tested GEQUAL against the nearest depths without writing them, so
//     that the test lets through, before the shader runs, every fragment
//     that may tie; the shader keeps a front face within a quarter of the
//     coincidence tolerance of the nearest (a copy of the nearest depths),
//     which is that surface as far as rounding can tell, and the last
//     written, the lowest such leaf, is the one shown, with its own depth and
//     normal. This is the rule the evaluator applies to a face that several
//     leaves share (evaluate.frag, "the surface shown"), and the one
//     GroupPeel's union groups apply. Where no two leaves' boxes meet, no
//     pixel can tie and the pass is left out.
// Beside CSG (Output::beside): where the root is a union of such leaves and
// of a rest with CSG in it, the same draws put the plain leaves' surfaces
// into the G-buffer first, every pixel they write marked kMarkPlain, and the
// rest is peeled and evaluated after them; the evaluator keeps their
// surface where it is shown before the rest's (evaluate.frag,
// PLAIN_BESIDE; docs/algorithm.md, "Plain leaves beside CSG").
//
// What the full pipeline does otherwise: a leaf thinner than the tolerance
// along a ray (a sheet, a ray grazing an edge or a cone's tip) is entered
// and left in one cluster there and shows nothing, where the plain path
// shows its front face; the union groups' one layer behaves as the plain
// path does.
//
// GL state: sets the viewport to the frame, the framebuffer, depth, stencil,
// cull and scissor state, and leaves depth test, stencil test, culling and
// the scissor test off, the depth function LESS and clip control GL's
// default; expects blending off. Leaves the scene's
// vertexArray() bound.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "FrameTargets.h"
#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/csg/CompiledTree.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"
#include "strata/gpu/VertexArray.h"
#include "strata/render/ColorScheme.h"

namespace strata::render {

class PlainPass {
public:
    PlainPass();  // compiles nothing: each program at its first use (a current context then)

    // The leaves a plain frame of `compiled` draws (its operands' leaves, a
    // leaf identical to a lower one standing for both), or nothing when the
    // tree cannot be drawn plainly: code other than a union of plain
    // literals, a group, or an operand with a shell of no volume.
    static std::vector<int> plainLeaves(const csg::CompiledTree& compiled, const SceneBuffers& scene);

    // The leaves the next frames draw (plainLeaves), and the scene's boxes.
    void setLeaves(const SceneBuffers& scene, std::vector<int> leaves);

    // What a frame writes.
    struct Output {
        // Also the colour lit by this light into targets.color, cleared to
        // `background` first (the frame then needs no shade pass).
        std::optional<Lighting> litAs;
        // Only what the image needs (FrameTargets::plainShownTarget and
        // plainShownLitTarget): no leaf codes and no marks, and the depth
        // only where the tie pass reads it. Not lit, the pass clears the
        // normals inside `drawn` grown by a pixel, all the shade pass's
        // outline reads.
        bool shownOnly = false;
        glm::vec4 background{0.0f};
        // Drawn beside the CSG (FrameTargets::plainBeside): the leaves are
        // the union's plain part, and the evaluator runs after on the rest.
        // The renderer asks shownOnly and keepResult with it: the depths
        // and leaf codes the evaluator reads, cleared inside `drawn` only.
        // Where marked (not lit), every pixel written is marked kMarkPlain,
        // which no leaf's mark equals, so the normal pass leaves the pixels
        // the plain leaves keep as they are.
        bool beside = false;
        // Shown only, and a pass blends over the image after by leaf
        // (translucent colours, AlphaPass.h): the depths and leaf codes of
        // the whole frame too, which it reads (a miss where nothing is
        // drawn).
        bool keepResult = false;
        // Shown only, and the '%' and '#' leaves drawn over the image after
        // (TranslucentPass.h), which read this pass's own depth image (the
        // shown target's: shownDepth lit, plainDepth else) beyond the
        // leaves' pixels: cleared over the whole frame.
        bool depthRead = false;
    };
    // Draws setLeaves' leaves into `targets` (its plain target, made here if
    // need be) inside `drawn`, which holds every pixel they cover.
    // `baseColors`: ShadePass::baseColors of this frame's colour scheme.
    void run(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& drawn,
             const std::vector<glm::vec2>& baseColors, const Output& output);

    // Leaves whose tie pass ran in the last frame (0: none could tie), and
    // of how many of their triangles (0: all).
    std::size_t tiedLeaves() const { return tieCount_; }
    std::size_t tiedTriangles() const { return tieTriangles_; }

    // Of `leaves`, those whose world boxes, grown by `margin`, meet another's
    // of them, ascending (and possibly a few more, never fewer: where many
    // boxes crowd one place); every one of them past `budget` box
    // comparisons.
    static std::vector<int> mayTie(const SceneBuffers& scene, std::span<const int> leaves, double margin,
                                   std::size_t budget);

    // The tie pass's draws over leafVertexArrayOver(indices): the lowest
    // leaf last, each leaf's triangles that may tie.
    struct TieDraws {
        std::vector<std::uint32_t> indices;
        std::vector<DrawElementsIndirectCommand> commands;  // base instance: the leaf
        std::size_t triangles = 0;
        bool allOf = false;  // commands draw whole leaves, over leafVertexArray()
    };
    // Of `leaves` (ascending), the triangles that come within `margin` of
    // a triangle of another of them (and possibly a few more, never fewer:
    // where many crowd one place), as the tie pass draws them; nothing
    // past kMostTieTriangles triangles or `budget` comparisons.
    static std::optional<TieDraws> tyingTriangles(const SceneBuffers& scene, std::span<const int> leaves,
                                                  double margin, std::size_t budget);
    static constexpr std::size_t kMostTieTriangles = std::size_t(1) << 19;  // about 100 MB at most

private:
    // plain.frag, each compiled at its first use: [shown][ties][shading],
    // shown the SHOWN variant (Output::shownOnly), ties the TIE variant (the
    // lowest leaf tying with the nearest), shading 0 the G-buffer alone, 1
    // and 2 also lit by strata's and OpenSCAD's light.
    std::array<std::array<std::array<std::optional<gpu::Program>, 3>, 2>, 2> programs_;
    gpu::Program& program(bool ties, const Output& output, const ViewSetup& view);
    // The tie pass's draws for this view, found again when the view needs a
    // wider margin, and sorted by triangle at the second frame.
    void findTies(const SceneBuffers& scene, const ViewSetup& view);
    // The target's depth to the farthest reversed depth, 0, and its marks
    // (where `marked`: a stencil) to none.
    static void clearDepth(const gpu::Framebuffer& target, bool marked);
    // A shown frame's draw buffers (only what is read after) and clears.
    void prepareShown(const gpu::Framebuffer& target, const ViewSetup& view, const PixelRect& drawn,
                      const Output& output);
    // The reversed depth's terms for the view (surface.vert), those pulled
    // nearer for the tie pass, and the tie pass's tolerance.
    struct ReversedDepth {
        glm::vec3 terms{0.0f}, pulled{0.0f};
        double reach = 0.0;
    };
    static ReversedDepth reversedDepth(const ViewSetup& view);
    // The second draw of the triangles that can tie with the nearest.
    void drawTies(FrameTargets& targets, const SceneBuffers& scene, const ViewSetup& view, const PixelRect& drawn,
                  const Output& output, const ReversedDepth& depth);
    std::vector<int> leaves_;
    gpu::Buffer nearestCommands_, tieCommands_;  // SceneBuffers::leafCommands, TieDraws::commands
    GLsizei nearestDraws_ = 0, tieDraws_ = 0;
    std::size_t tieCount_ = 0, tieTriangles_ = 0;
    gpu::Buffer tieIndices_;         // TieDraws::indices
    gpu::VertexArray tieVertexArray_;  // over tieIndices_
    bool tieAllOf_ = false;
    std::size_t framesDrawn_ = 0;  // since setLeaves
    bool tieRefined_ = false;      // tyingTriangles has been asked since setLeaves
    double tieMargin_ = -1.0;  // the margin tieCommands_ was found with (-1: none yet)
    gpu::Buffer colors_;       // baseColors, as last uploaded
    std::vector<glm::vec2> uploadedColors_;
    gpu::Texture nearestCopy_;  // R32F, the frame's size: the tie pass's input
};

}  // namespace strata::render
