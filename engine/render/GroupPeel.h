#pragma once
// The peel of a group (ConvexGroups.h): one layer for an intersection of
// convex leaves, or for a union of leaves whose first layer is all that
// matters, and which member makes each of its surfaces.
//
// On a ray through all members the group's interval runs from the farthest
// entry to the nearest exit. Two depth-tested passes over the members find
// both, with the member that makes them, into a scratch image the tile's
// size (RGBA32F: entry, exit, entry member, exit member):
//   - front faces, depth test GREATER: the farthest entry wins;
//   - back faces, depth test LESS: the nearest exit wins, and every back
//     face, passing or not, increments the stencil: a convex member hit by
//     a ray has exactly one back face on it (the far plane lies beyond the
//     scene; only front faces can be clipped, by the near plane, where the
//     eye is inside), so the count is the number of members hit.
// The depth each fragment writes is its tagged depth's bit pattern, shifted
// into [0, 1) (`orderKey`): it orders fragments exactly as their tagged
// depths do, so the winners are the depths that MAX and MIN over tagged
// depths would give, and at equal depths the lowest member wins (members
// are drawn in order, the tests are strict), as the CPU reference keeps the
// first operand's surface.
// Ties: rounding puts members that share a face (an intersection of solids
// with a face in common) a hair apart, and the strict tests would name
// whichever rounding put last; so do members whose surfaces cross, on the
// band of pixels where the two come within the tolerance. Where a group
// wants them (tiesWanted), two more passes over the members, the winners
// copied aside, take every front face within
// a quarter of the coincidence tolerance of the winning entry, and every
// back face within it of the winning exit, and keep the lowest such member,
// with its own tagged depth: the member the evaluator's rule names for the ungrouped operands
// (evaluate.frag, "the surface shown"), and a depth the normal pass finds
// in that member's faces.
// A fullscreen pass over the group's rectangle, stencil-tested for "count =
// members", then writes the group's layer as a convex operand with that
// interval would hold it: (-entry, exit), or (-exit, exit) where no member
// had an entry (the ray starts inside all of them), or nothing where the
// entry does not lie before the exit. It stores the two winning members per
// pixel in the group's layer of `ids()`, from which the evaluator writes the
// member that makes the surface it chooses (evaluate.frag: surfaceLeaf).
//
// A union (groupUnionOperands) runs the same passes with the tests turned:
// front faces with LESS (the nearest entry), back faces with GREATER (the
// farthest exit), ties within the tolerance beyond the nearest entry and
// before the farthest exit, and a resolve without the stencil test that
// writes (-entry, exit) wherever some member was entered. Every ray starts
// outside every member there, so a pixel with a back face has a front face.
//
// Each pass draws all members in one multi-draw over
// SceneBuffers::memberVertexArray, in order, so a union of 65 535 members
// costs as many calls as one of two.
//
// GL state: sets the viewport's framebuffer, depth, stencil and cull state
// and colour masks, and leaves depth test, stencil test and culling off,
// colour masks all on; expects blending off. Leaves the scene's
// vertexArray() bound.

#include <cstdint>
#include <optional>
#include <vector>

#include "SceneBuffers.h"
#include "ViewSetup.h"
#include "strata/gpu/Buffer.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Program.h"
#include "strata/gpu/Texture.h"

namespace strata::render {

class GroupPeel {
public:
    GroupPeel();  // compiles the shaders; needs a current context

    // An intersection's members are counted in the 8-bit stencil.
    static constexpr int kMostMembers = 255;
    // A union's are not counted; member numbers below shader::kNoMember.
    static constexpr int kMostUnionMembers = 65535;

    // Bytes per pixel of a tile for `groups` groups: scratch, its copy, depth-stencil, ids.
    static std::size_t bytesPerPixel(int groups) { return 16 + 16 + 8 + 4 * static_cast<std::size_t>(groups); }

    // Makes room for `groups` groups in `tile`. Call before the tile's first peel().
    void begin(const ViewSetup& view, const PixelRect& tile, int groups);
    // Peels a group: `members` (leaves, ascending) inside `valid` (tile
    // pixels), into layer `layer` of `layers`, and its members into layer
    // `idsLayer` (0 .. groups - 1 of begin()) of ids().
    // `ties`: look for ties (above); whether a group needs to: tiesWanted.
    // `unite`: the group is the union of its members, not their intersection.
    void peel(const SceneBuffers& scene, const std::vector<int>& members, const PixelRect& valid,
              const gpu::Texture& layers, int layer, int idsLayer, bool ties, bool unite);
    // Whether to look for ties among `members`. A union (`unite`) always
    // looks: its members are often parts that stand flush (a grid of blocks,
    // parts on a plate), and hashing the planes of a million members would
    // cost more memory than the two passes cost time. An intersection looks
    // where two members have faces in one plane (SceneBuffers::shareAPlane),
    // and, where their surfaces only cross, up to kMostTieMembers members.
    // Ties cost two geometry passes over every member (the group's peel 2.5
    // times as long on llvmpipe); in a larger intersection of crossing
    // surfaces, the pixels on the thin band where two come within the
    // tolerance name the member rounding puts last instead of the lowest
    // (the leaf and colour, not the depth).
    static bool tiesWanted(const SceneBuffers& scene, const std::vector<int>& members, bool unite);
    static constexpr std::size_t kMostTieMembers = 8;

    // R32UI, a layer per group, tile pixels: entry member | exit member <<
    // shader::kMemberBits where the group has a surface (shader::kNoMember:
    // no entry).
    const gpu::Texture& ids() const { return ids_; }
    std::size_t bytes() const;
    // Frees the images: a frame without groups keeps no memory outside the
    // budget's count.
    void release();

private:
    gpu::Program draw_;     // peel.frag's GROUP: a member's faces, depth = order key
    gpu::Program ties_;     // peel.frag's GROUP_TIE: the lowest member tying with a winner
    gpu::Program resolve_;  // group.frag: scratch to the layer and the ids
    // The UNION variants of ties_ and resolve_, compiled when a union comes.
    std::optional<gpu::Program> unionTies_, unionResolve_;
    gpu::Buffer commands_;  // the members' multi-draw (SceneBuffers::memberCommands)
    GLsizei drawCount_ = 0;
    ViewSetup view_;  // begin()'s, for the union programs compiled later
    glm::ivec2 tileOrigin_{0, 0};  // begin()'s tile: the frame pixel at gl_FragCoord (0, 0)
    void drawMembers() const;
    gpu::Framebuffer target_;   // scratch + depth-stencil
    gpu::Framebuffer layerTarget_;  // a layer of the layers + depth-stencil (for its stencil)
    gpu::Texture scratch_, winners_, depthStencil_, ids_;
};

}  // namespace strata::render
