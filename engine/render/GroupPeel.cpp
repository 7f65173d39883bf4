#include "GroupPeel.h"

#include <algorithm>
#include <cstring>

#include "ShaderInterface.h"
#include "strata/gpu/ShaderSource.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

gpu::Program tiesProgram(bool unite) {
    std::vector<gpu::ShaderDefine> defines{{"PEEL_FIRST", ""}, {"GROUP_TIE", ""}, {"GROUP_MEMBERS", ""}};
    if (unite) defines.push_back({"UNION", ""});
    return gpu::Program::fromFiles(unite ? "peel union ties" : "peel group ties", {"csg/surface.vert", "csg/peel.frag"},
                                   defines);
}

}  // namespace

GroupPeel::GroupPeel()
    : draw_(gpu::Program::fromFiles("peel group", {"csg/surface.vert", "csg/peel.frag"},
                                    {{"PEEL_FIRST", ""}, {"GROUP", ""}, {"GROUP_MEMBERS", ""}})),
      ties_(tiesProgram(false)),
      resolve_(gpu::Program::fromFiles("peel group resolve", {"common/fullscreen.vert", "csg/group.frag"})),
      target_("peel group"),
      layerTarget_("peel group layer") {
    target_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    layerTarget_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
}

std::size_t GroupPeel::bytes() const {
    return (scratch_.id() ? scratch_.byteSize() + winners_.byteSize() : 0) +
           (depthStencil_.id() ? depthStencil_.byteSize() : 0) +
           (ids_.id() ? ids_.byteSize() : 0);
}

void GroupPeel::release() {
    if (!scratch_.id()) return;
    // Attached, a deleted texture would live on.
    target_.detach(GL_COLOR_ATTACHMENT0);
    target_.detach(GL_DEPTH_STENCIL_ATTACHMENT);
    layerTarget_.detach(GL_DEPTH_STENCIL_ATTACHMENT);
    scratch_ = {};
    winners_ = {};
    depthStencil_ = {};
    ids_ = {};
}

void GroupPeel::begin(const ViewSetup& view, const PixelRect& tile, int groups) {
    if (!scratch_.id() || scratch_.width() != tile.width || scratch_.height() != tile.height) {
        scratch_ = gpu::Texture::create2D("peel group scratch", GL_RGBA32F, tile.width, tile.height);
        winners_ = gpu::Texture::create2D("peel group winners", GL_RGBA32F, tile.width, tile.height);
        depthStencil_ = gpu::Texture::create2D("peel group depth", GL_DEPTH32F_STENCIL8, tile.width, tile.height);
        target_.attachTexture(GL_COLOR_ATTACHMENT0, scratch_);
        target_.attachTexture(GL_DEPTH_STENCIL_ATTACHMENT, depthStencil_);
        layerTarget_.attachTexture(GL_DEPTH_STENCIL_ATTACHMENT, depthStencil_);
        ids_ = {};
    }
    if (!ids_.id() || ids_.layers() < groups) {
        ids_ = gpu::Texture::create2DArray("peel group ids", GL_R32UI, tile.width, tile.height, std::max(groups, 1));
    }

    view_ = view;
    tileOrigin_ = {tile.x, tile.y};
    setSurfaceView(draw_, view, tileOrigin_);
    for (gpu::Program* ties : {&ties_, unionTies_ ? &*unionTies_ : nullptr}) {
        if (ties == nullptr) continue;
        setSurfaceView(*ties, view, tileOrigin_);
        ties->setUniform(shader::kPeelTieTolerance, static_cast<float>(view.coincidence * 0.25));
    }
    // Tagged depths from half the near plane's on map into [0, 1) in order
    // (peel.frag: orderKey); every fragment lies beyond the near plane.
    const float base = static_cast<float>(view.nearPlane * 0.5);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &base, sizeof bits);
    draw_.setUniform(shader::kPeelKeyBase, bits);
}

void GroupPeel::drawMembers() const {
    glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, nullptr, drawCount_, 0);
}

void GroupPeel::peel(const SceneBuffers& scene, const std::vector<int>& members, const PixelRect& valid,
                     const gpu::Texture& layers, int layer, int idsLayer, bool ties, bool unite) {
    if (unite && !unionTies_) {
        unionTies_ = tiesProgram(true);
        setSurfaceView(*unionTies_, view_, tileOrigin_);
        unionTies_->setUniform(shader::kPeelTieTolerance, static_cast<float>(view_.coincidence * 0.25));
        unionResolve_ = gpu::Program::fromFiles("peel union resolve", {"common/fullscreen.vert", "csg/group.frag"},
                                                {{"UNION", ""}});
    }
    const std::vector<DrawElementsIndirectCommand> commands = scene.memberCommands(members);
    gpu::Buffer::uploadGrowing(commands_, "peel group commands", commands);
    drawCount_ = static_cast<GLsizei>(commands.size());
    scene.memberVertexArray().bind();
    commands_.bind(GL_DRAW_INDIRECT_BUFFER);

    glScissor(valid.x, valid.y, valid.width, valid.height);
    target_.bindForDraw();
    const float none[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
    target_.clearColor(0, none);
    const GLint zero = 0;
    glClearNamedFramebufferiv(target_.id(), GL_STENCIL, 0, &zero);

    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    draw_.use();
    // Entries: front faces, the farthest wins (a union's: the nearest); then
    // exits: back faces, the nearest wins (a union's: the farthest), and each
    // one counts its member.
    for (int exits = 0; exits < 2; ++exits) {
        const bool farthest = exits == (unite ? 1 : 0);
        target_.clearDepth(farthest ? 0.0f : 1.0f);
        glDepthFunc(farthest ? GL_GREATER : GL_LESS);
        glCullFace(exits ? GL_FRONT : GL_BACK);
        glColorMask(!exits, exits, !exits, exits);
        if (exits) {
            glEnable(GL_STENCIL_TEST);
            glStencilFunc(GL_ALWAYS, 0, 0xff);
            glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
        }
        drawMembers();
    }
    // Ties: the winners copied aside, the lowest member within the
    // tolerance of each, front faces then back faces (GroupPeel.h).
    glDisable(GL_STENCIL_TEST);
    if (ties) {
        glCopyImageSubData(scratch_.id(), GL_TEXTURE_2D, 0, valid.x, valid.y, 0, winners_.id(), GL_TEXTURE_2D, 0,
                           valid.x, valid.y, 0, valid.width, valid.height, 1);
        winners_.bindUnit(shader::kTextureGroupWinners);
        (unite ? *unionTies_ : ties_).use();
        glDepthFunc(GL_LESS);
    }
    for (int exits = 0; ties && exits < 2; ++exits) {
        target_.clearDepth(1.0f);
        glCullFace(exits ? GL_FRONT : GL_BACK);
        glColorMask(!exits, exits, !exits, exits);
        drawMembers();
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    scene.vertexArray().bind();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);

    // Where every member was hit (an intersection), or some member was
    // entered (a union): the layer and the ids.
    layerTarget_.attachLayer(GL_COLOR_ATTACHMENT0, layers, layer);
    layerTarget_.bindForDraw();
    if (!unite) {
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_EQUAL, static_cast<GLint>(members.size()), 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    }
    scratch_.bindUnit(shader::kTextureGroupScratch);
    ids_.bindImage(shader::kImageGroupIds, GL_WRITE_ONLY);
    gpu::Program& resolve = unite ? *unionResolve_ : resolve_;
    resolve.use();
    resolve.setUniform(shader::kGroupIdsLayer, idsLayer);
    glDrawArrays(GL_TRIANGLES, 0, 3);  // reads no attribute: any vertex array does
    glDisable(GL_STENCIL_TEST);
    // The evaluator samples the layer and the ids.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    layerTarget_.detach(GL_COLOR_ATTACHMENT0);
    gpu::checkErrors();
}

bool GroupPeel::tiesWanted(const SceneBuffers& scene, const std::vector<int>& members, bool unite) {
    return unite || members.size() <= kMostTieMembers || scene.shareAPlane(members);
}

}  // namespace strata::render
