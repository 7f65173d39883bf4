#include "RendererImpl.h"

namespace strata::render {

using camera::Camera;

void Renderer::Impl::peelResultRounds(const TileInputs& in, const PixelRect& tile,
                                      const std::vector<OperandLayers>& layers, Frame& frame) {
    FrameStats& stats = frame.stats;
    const csg::CompiledTree& compiled = current->tree;
    const std::vector<int> groups = EvaluatePass::groupTable(leafCount, compiled, layers);
    const float before = -std::numeric_limits<float>::infinity();
    glClearTexSubImage(resultStart.id(), 0, tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED, GL_FLOAT, &before);
    const std::size_t n = static_cast<std::size_t>(tile.width) * static_cast<std::size_t>(tile.height);
    std::vector<float> depth(n), normal(n * 4);
    std::vector<std::int32_t> leaf(n);
    std::vector<glm::vec3> outward(n);
    for (int round = 0;; ++round) {
        auto start = Clock::now();
        targets.clearRegion(tile);
        evaluate->runResultRound(targets, peel->layers(), tile, layers, in.rects, in.hulls, groups, peel->groupIds(), resultStart,
                                round > 0, in.view.coincidence, stats);
        const std::vector<std::uint32_t> shown = evaluate->shownFaces();  // waits for the evaluator
        stats.evaluateMs += msSince(start);
        start = Clock::now();
        normals->run(targets, scene, in.view, tile, compiled, in.rects, shown, in.baseColors, in.markLeaves,
                     in.markRects, std::nullopt);  // the normals are read back
        glFinish();
        stats.normalMs += msSince(start);

        start = Clock::now();
        targets.resultLeaf.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED_INTEGER, GL_INT,
                                          std::as_writable_bytes(std::span(leaf)));
        ResultRound out{round, tile.x, frame.height - (tile.y + tile.height), tile.width, tile.height, {}, {}, 0};
        std::size_t found = 0;
        for (std::int32_t code : leaf) {
            found += code >= 0 ? 1 : 0;
            out.unresolved += code == shader::kLeafUnresolved ? 1 : 0;
        }
        stats.unresolvedPixels += out.unresolved;
        if (found == 0) {
            stats.readbackMs += msSince(start);
            return;
        }
        stats.coveredPixels += found;
        targets.resultDepth.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RED, GL_FLOAT,
                                           std::as_writable_bytes(std::span(depth)));
        targets.normal.downloadRegion(tile.x, tile.y, 0, tile.width, tile.height, 1, GL_RGBA, GL_FLOAT,
                                      std::as_writable_bytes(std::span(normal)));
        // The next round walks on from each pixel's change (+inf: none left).
        glCopyImageSubData(targets.resultDepth.id(), GL_TEXTURE_2D, 0, tile.x, tile.y, 0, resultStart.id(),
                           GL_TEXTURE_2D, 0, tile.x, tile.y, 0, tile.width, tile.height, 1);
        flipRows(std::span(depth), tile.width, tile.height, 1);
        flipRows(std::span(normal), tile.width, tile.height, 4);
        flipRows(std::span(leaf), tile.width, tile.height, 1);
        for (std::size_t i = 0; i < n; ++i) {
            if (leaf[i] < 0) depth[i] = std::numeric_limits<float>::infinity();
            outward[i] = {normal[i * 4], normal[i * 4 + 1], normal[i * 4 + 2]};
        }
        out.depth = depth;
        out.normal = outward;
        stats.readbackMs += msSince(start);
        (*roundSink)(out);
    }
}

FrameStats Renderer::sampleResult(const Camera& camera, const RenderSettings& settings,
                                  const std::function<void(const ResultRound&)>& onRound) {
    Impl& impl = *impl_;
    if (camera.width <= 0 || camera.height <= 0) throw Error("renderer: sampleResult() needs a positive image size");
    if (impl.resultStart.id() == 0 || impl.resultStart.width() != camera.width ||
        impl.resultStart.height() != camera.height) {
        impl.resultStart = gpu::Texture::create2D("result peel start", GL_R32F, camera.width, camera.height);
    }
    RenderSettings peeled = settings;
    peeled.keepPeelLayers = false;
    peeled.keepBlockForms = false;
    impl.roundSink = &onRound;
    Frame frame;
    try {
        impl.drawFrame(camera, peeled, frame, true);
    } catch (...) {
        impl.roundSink = nullptr;
        throw;
    }
    impl.roundSink = nullptr;
    return frame.stats;
}

}  // namespace strata::render
