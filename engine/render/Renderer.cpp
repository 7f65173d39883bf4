#include "RendererImpl.h"

namespace strata::render {

using camera::Camera;

namespace {

// Leaves to draw translucent: '#' leaves in the CSG, and every leaf of the
// '%' subtrees (or marked Background), with OpenSCAD's colours.
std::vector<TranslucentLeaf> translucentLeaves(const scene::Tree& tree, const SceneBuffers& scene) {
    std::vector<char> background(tree.leaves.size(), 0);
    std::vector<int> stack(tree.background.begin(), tree.background.end());
    std::vector<char> seen(tree.nodes.size(), 0);
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= tree.nodes.size() || seen[static_cast<std::size_t>(n)]) continue;
        seen[static_cast<std::size_t>(n)] = 1;
        const scene::Node& node = tree.nodes[static_cast<std::size_t>(n)];
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf >= 0 && static_cast<std::size_t>(node.leaf) < tree.leaves.size()) {
                background[static_cast<std::size_t>(node.leaf)] = 1;
            }
        }
        stack.insert(stack.end(), node.children.begin(), node.children.end());
    }
    std::vector<TranslucentLeaf> out;
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        if (scene.leaf(static_cast<int>(i)).indexCount == 0) continue;
        if (background[i] || leaf.display == scene::Display::Background) {
            glm::vec4 color = kBackgroundModifierColor;
            if (leaf.color) color = glm::vec4(glm::vec3(*leaf.color), kBackgroundModifierColor.a);
            out.push_back({static_cast<int>(i), color});
        } else if (leaf.display == scene::Display::Highlight) {
            out.push_back({static_cast<int>(i), kHighlightColor});
        }
    }
    return out;
}

// Leaves in the CSG whose color() is translucent (alpha below 1; an unset
// alpha is 1), and which of them are alone in their OpenSCAD product: only
// unions lead to them from the root, counting an intersection or difference
// of which only one child has triangles as a union of that child (OpenSCAD
// leaves a leaf without geometry out of a product).
std::vector<AlphaLeaf> alphaLeaves(const scene::Tree& tree, const SceneBuffers& scene) {
    std::vector<AlphaLeaf> out;
    if (tree.root < 0) return out;
    const std::size_t n = tree.nodes.size();
    auto inRange = [n](int node) { return node >= 0 && static_cast<std::size_t>(node) < n; };
    // Whether each node's subtree holds a leaf with triangles: children first,
    // on an explicit stack (trees can be deep).
    std::vector<char> solid(n, 0), state(n, 0);  // state: 0 new, 1 children pushed, 2 done
    std::vector<int> stack{tree.root};
    while (!stack.empty()) {
        const int v = stack.back();
        const auto i = static_cast<std::size_t>(v);
        const scene::Node& node = tree.nodes[i];
        if (state[i] == 0) {
            state[i] = 1;
            if (node.kind == scene::NodeKind::Leaf) continue;
            for (int c : node.children)
                if (inRange(c) && state[static_cast<std::size_t>(c)] == 0) stack.push_back(c);
            continue;
        }
        stack.pop_back();
        if (state[i] == 2) continue;
        state[i] = 2;
        if (node.kind == scene::NodeKind::Leaf) {
            solid[i] = node.leaf >= 0 && static_cast<std::size_t>(node.leaf) < tree.leaves.size() &&
                       scene.leaf(node.leaf).indexCount > 0;
        } else {
            for (int c : node.children) solid[i] = solid[i] || (inRange(c) && solid[static_cast<std::size_t>(c)]);
        }
    }
    // Down from the root: whether only unions lead there.
    std::vector<char> alone(tree.leaves.size(), 0), seen(n, 0);
    std::vector<char> reached(tree.leaves.size(), 0);
    std::vector<std::pair<int, bool>> walk{{tree.root, true}};
    while (!walk.empty()) {
        const auto [v, unionsOnly] = walk.back();
        walk.pop_back();
        const auto i = static_cast<std::size_t>(v);
        if (seen[i] & (unionsOnly ? 2 : 1)) continue;
        seen[i] |= unionsOnly ? 2 : 1;
        const scene::Node& node = tree.nodes[i];
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf < 0 || static_cast<std::size_t>(node.leaf) >= tree.leaves.size()) continue;
            reached[static_cast<std::size_t>(node.leaf)] = 1;
            alone[static_cast<std::size_t>(node.leaf)] |= unionsOnly ? 1 : 0;
            continue;
        }
        int solidChildren = 0;
        for (int c : node.children) solidChildren += inRange(c) && solid[static_cast<std::size_t>(c)] ? 1 : 0;
        const bool keeps = node.kind == scene::NodeKind::Union || solidChildren <= 1;
        for (int c : node.children)
            if (inRange(c)) walk.emplace_back(c, unionsOnly && keeps);
    }
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        const scene::Leaf& leaf = tree.leaves[i];
        if (!reached[i] || !leaf.color || scene.leaf(static_cast<int>(i)).indexCount == 0) continue;
        const glm::vec4 color(*leaf.color);
        if (color.a < 0.0f || color.a >= 1.0f) continue;
        out.push_back({static_cast<int>(i), color, alone[i] != 0});
    }
    return out;
}

// Per operand of `compiled`: whether only ORs lead from the result to its
// (not complemented) literal. The result is then true wherever the operand
// is: once a ray enters it, the result is entered, at the latest there. So
// where every ray starts outside every operand, its nearest surface (the
// first peeled layer) is all the result can show of it. Not for a leaf with
// a shell of no volume (SceneBuffers: solidShells): there the nearest entry
// can have an exit at its very depth, which the first layer would lose.
std::vector<char> reachedByUnionsOnly(const csg::CompiledTree& compiled, const SceneBuffers& scene) {
    std::vector<char> out(compiled.operandLeaf.size(), 0);
    if (compiled.code.empty()) return out;
    using Operands = std::vector<std::uint32_t>;
    auto literal = [](std::uint32_t instruction) {
        return instruction & csg::kOpNegate ? Operands{} : Operands{instruction >> csg::kOperandShift};
    };
    auto combine = [](std::uint32_t op, Operands& top, Operands&& source) {
        if (op == csg::kOpAnd) {
            top.clear();
        } else {
            top.insert(top.end(), source.begin(), source.end());
        }
    };
    for (std::uint32_t k : csg::foldCode<Operands>(compiled.code, literal, combine))
        out[k] = scene.leaf(compiled.operandLeaf[k]).solidShells ? 1 : 0;
    return out;
}

// Per operand of `compiled` (its own leaves, no groups yet): whether its leaf is convex.
std::vector<char> convexOperandsOf(const csg::CompiledTree& compiled, const SceneBuffers& scene) {
    std::vector<char> out(compiled.operandLeaf.size(), 0);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = scene.leaf(compiled.operandLeaf[k]).convex ? 1 : 0;
    return out;
}

}  // namespace

void resetDrawState() {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void Renderer::Impl::shadeFrame(const ViewSetup& view, const ColorScheme& scheme, const RenderSettings& settings,
                                const std::optional<PixelRect>& marked, bool lit, const gpu::Texture* windowDepth) {
    if (!lit) shade->run(targets, view, scheme, settings.lighting, settings.outline, marked);
    if (!alphaLeaves.empty()) alpha->run(targets, scene, view, scheme, settings.lighting, alphaLeaves);
    if (!translucentLeaves.empty()) translucent->run(targets, scene, view, translucentLeaves, windowDepth);
    passDone();
}

void Renderer::Impl::readColor(Frame& frame) {
    frame.rgba.resize(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 4);
    targets.color.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(frame.rgba)));
    flipRows(std::span(frame.rgba), frame.width, frame.height, 4);
}

Renderer::Impl::Impl() {
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
    const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = name != nullptr ? name : "";
    for (const char* software : {"llvmpipe", "softpipe", "SwiftShader", "swrast"})
        softwareRasterizer = softwareRasterizer || renderer.find(software) != std::string::npos;
    GLint kib[4] = {0, 0, 0, 0};
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX, kib);
    } else if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
        glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib);  // free, in the largest block and more
    }
    deviceMemory = static_cast<std::size_t>(std::max(kib[0], 0)) << 10;
}

RenderSettings Renderer::Impl::deviceSettings(const RenderSettings& settings) const {
    RenderSettings out = settings;
    if (!out.memoryBudget) {
        // An eighth of what the GPU has, so that the layers leave room for
        // the rest of the program and of the desktop.
        constexpr std::size_t kMostBudget = std::size_t(4) << 30;
        out.memoryBudget = softwareRasterizer || deviceMemory == 0
                               ? RenderSettings::kMemoryBudget
                               : std::clamp(deviceMemory / 8, RenderSettings::kMemoryBudget, kMostBudget);
    }
    // On a GPU a tile costs a wait for the evaluator's read-back and each
    // pass's fixed cost, and a new texture no zeroing: tiles only for the budget.
    if (!out.coverageTilingFrom)
        out.coverageTilingFrom = softwareRasterizer ? RenderSettings::kSoftwareCoverageTilingFrom : *out.memoryBudget;
    return out;
}

RenderSettings Renderer::deviceSettings(const RenderSettings& settings) const {
    return impl_->deviceSettings(settings);
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

void Renderer::setScene(const scene::Tree& tree, const model::Model& model) {
    impl_->setScene(tree, model, nullptr);
}

void Renderer::setScene(const scene::Tree& tree, model::Model&& model) {
    impl_->setScene(tree, model, &model);
    model = {};
}

void Renderer::Impl::setScene(const scene::Tree& tree, const model::Model& model, model::Model* release) {
    Impl& impl = *this;
    impl.scene.describe(tree, model);
    std::vector<bool> empty(model.leafMeshes.size());
    for (std::size_t i = 0; i < empty.size(); ++i) empty[i] = model.leafMeshes[i].triangles.empty();
    const std::vector<int> same = csg::identicalLeaves(tree, model);
    impl.copiedLeaves = 0;
    for (std::size_t i = 0; i < same.size(); ++i) impl.copiedLeaves += same[i] != static_cast<int>(i) ? 1 : 0;
    impl.separate.tree = csg::compileTree(tree, empty, same);
    impl.separate.unionsOnly = reachedByUnionsOnly(impl.separate.tree, impl.scene);
    impl.convexOperands = convexOperandsOf(impl.separate.tree, impl.scene);
    // The groups that ask whether their members share a plane
    // (GroupPeel::tiesWanted), made while the meshes are here: every group
    // any convexGroupFrom can make (groupTrees) is among these.
    const csg::CompiledTree everyGroup =
        csg::groupConvexProducts(impl.separate.tree, impl.convexOperands, PeelRequest::kMostGroupMembers);
    for (const std::vector<int>& members : everyGroup.operandGroups) {
        if (members.size() > GroupPeel::kMostTieMembers) impl.scene.hashPlanes(model, members);
    }
    impl.groupedFrom = -1;  // grouped at the first frame (groupTrees)
    // Last, once nothing above needs the meshes any more.
    impl.scene.fill(model, release);
    impl.plainLeaves = PlainPass::plainLeaves(impl.separate.tree, impl.scene);
    impl.besidePlain(tree, empty, same);
    impl.plainStale = true;
    // The evaluator takes its tree at the first frame that needs one.
    impl.current = nullptr;
    impl.translucentLeaves = render::translucentLeaves(tree, impl.scene);
    impl.alphaLeaves = render::alphaLeaves(tree, impl.scene);
    impl.leafCount = tree.leaves.size();
    impl.hasScene = true;
    gpu::checkErrors();
}

void Renderer::Impl::besidePlain(const scene::Tree& tree, const std::vector<bool>& empty, const std::vector<int>& same) {
    besideLeaves.clear();
    besideSeparate = {};
    besideGrouped = {};
    besideConvexOperands.clear();
    const csg::CompiledTree& whole = separate.tree;
    if (!plainLeaves.empty() || whole.kind != csg::CompiledTree::Kind::Code ||
        scene.leaves().size() > SceneBuffers::kMostLeafNumbers)
        return;
    // The plain leaves: operands that only unions lead to, solids with
    // volume (reachedByUnionsOnly). Where the root is a union of those and
    // of a rest R, the result is their union with R taken with them empty:
    // wherever one of them holds a point the result holds it either way, and
    // elsewhere they are empty already. So the result's first surface on a
    // ray that starts outside is the nearer of theirs and R's.
    std::vector<char> plainLeaf(tree.leaves.size(), 0);
    for (std::size_t k = 0; k < whole.operandLeaf.size(); ++k) {
        if (!separate.unionsOnly[k]) continue;
        plainLeaf[static_cast<std::size_t>(whole.operandLeaf[k])] = 1;
        besideLeaves.push_back(whole.operandLeaf[k]);
    }
    if (besideLeaves.empty() || besideLeaves.size() == whole.operandLeaf.size()) {
        besideLeaves.clear();
        return;
    }
    std::vector<bool> rest(empty);
    rest.resize(tree.leaves.size(), false);
    for (std::size_t i = 0; i < rest.size(); ++i) {
        const int operand = same.empty() ? static_cast<int>(i) : same[i];
        if (plainLeaf[static_cast<std::size_t>(operand)]) rest[i] = true;
    }
    besideSeparate.tree = csg::compileTree(tree, rest, same);
    if (besideSeparate.tree.kind != csg::CompiledTree::Kind::Code) {
        besideLeaves.clear();
        besideSeparate = {};
        return;
    }
    besideSeparate.unionsOnly = reachedByUnionsOnly(besideSeparate.tree, scene);
    besideConvexOperands = convexOperandsOf(besideSeparate.tree, scene);
}

void Renderer::Impl::readBack(Frame& frame, const RenderSettings& settings) {
    // Straight into the frame's own arrays, flipped in place: a 1024x768
    // frame's read-back then holds no copies beside them.
    const int w = frame.width, h = frame.height;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);

    readColor(frame);

    if (settings.readDepth) {
        frame.depth.resize(n);
        targets.resultDepth.download(GL_RED, GL_FLOAT, std::as_writable_bytes(std::span(frame.depth)));
        flipRows(std::span(frame.depth), w, h, 1);
    }

    frame.leaf.resize(n);
    targets.resultLeaf.download(GL_RED_INTEGER, GL_INT, std::as_writable_bytes(std::span(frame.leaf)));
    flipRows(std::span(frame.leaf), w, h, 1);
    for (std::int32_t& code : frame.leaf) {
        if (code >= 0) ++frame.stats.coveredPixels;
        if (code == shader::kLeafUnresolved) ++frame.stats.unresolvedPixels;
        code = shader::leafOfCode(code);
    }
    if (frame.stats.unresolvedPixels > 0) {
        frame.stats.notes.push_back(std::to_string(frame.stats.unresolvedPixels) +
                                    " pixels had more surfaces than this driver lets one shader walk "
                                    "(llvmpipe's loop limit); they are drawn empty");
    }

    if (settings.readNormal) {
        static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");
        frame.normal.resize(n);
        targets.normal.download(GL_RGB, GL_FLOAT, std::as_writable_bytes(std::span(frame.normal)));
        flipRows(std::span(frame.normal), w, h, 1);
    }
    gpu::checkErrors();
}

void Renderer::Impl::drawPlain(const ViewSetup& view, const PixelRect& drawn,
                               const std::vector<glm::vec2>& baseColors, const PlainPass::Output& output,
                               Frame& frame) {
    FrameStats& stats = frame.stats;
    const auto start = Clock::now();
    const std::vector<int>& leaves = plainPassLeaves();
    if (plainStale) {
        plain->setLeaves(scene, leaves);
        plainStale = false;
    }
    plain->run(targets, scene, view, drawn, baseColors, output);
    passDone();
    stats.plainMs = msSince(start);
    stats.tiedLeaves = plain->tiedLeaves();
    stats.tiedTriangles = plain->tiedTriangles();
    const std::string count = std::to_string(leaves.size()) + (leaves.size() == 1 ? " leaf" : " leaves");
    if (output.beside) {
        stats.plainBesideLeaves = leaves.size();
        stats.notes.push_back("drawn plainly beside the CSG: " + count +
                              " that only unions lead to, depth-tested with no peel, before the rest is evaluated");
        return;
    }
    stats.plain = true;
    stats.operands = static_cast<int>(leaves.size());
    stats.tiles = 1;
    stats.notes.push_back("drawn plainly: a union of " + count +
                          " seen from outside, depth-tested with no peel or evaluator");
}

ViewSetup Renderer::Impl::frameView(const Camera& camera, const RenderSettings& settings) const {
    if (!hasScene) throw Error("renderer: render() before setScene()");
    if (settings.layers < 0) throw Error("renderer: layers must be 0 (auto) or positive");
    const ViewSetup view = makeView(camera, scene.bounds());
    if (view.width > maxTextureSize || view.height > maxTextureSize) {
        throw Error("renderer: image size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                    " exceeds the GPU's largest texture, " + std::to_string(maxTextureSize));
    }
    return view;
}

Renderer::Impl::ScreenRects Renderer::Impl::screenRects(const csg::CompiledTree& compiled, const FramePlan& plan,
                                                        LeafRects& leafRects) const {
    // Each operand's screen rectangle: its surfaces, and so every pixel the
    // evaluator can mark, lie inside it.
    // Mark slots go to the operands, a group's to each of its members.
    ScreenRects out;
    if (plan.plainFrame) {
        // The rectangle of the leaves' boxes: a plain frame has nothing else
        // to project, and a model of a million leaves would spend more time
        // projecting their vertices than the GPU spends drawing them.
        mesh::Bounds box;
        for (int leaf : plainPassLeaves()) box.extend(scene.leaf(leaf).bounds);
        out.drawn = screenRect(leafRects.view(), box);
    } else if (plan.plainBeside) {
        for (int leaf : plainPassLeaves()) out.drawn = out.drawn.bounding(leafRects(leaf));
    }
    if (!plan.plainFrame && compiled.kind == csg::CompiledTree::Kind::Code) {
        out.rects.resize(compiled.operandLeaf.size());
        for (std::size_t k = 0; k < out.rects.size(); ++k) {
            // An intersection's surfaces lie where all its members' do, a
            // union's where any member's does.
            const std::span<const int> leaves = compiled.leavesOf(k);
            const bool unite = compiled.isUnionGroup(k);
            for (std::size_t i = 0; i < leaves.size(); ++i) {
                const PixelRect own = leafRects(leaves[i]);
                out.rects[k] = i == 0 ? own : unite ? out.rects[k].bounding(own) : out.rects[k].intersection(own);
                out.markLeaves.push_back(leaves[i]);
                out.markRects.push_back(own);
            }
            out.drawn = out.drawn.bounding(out.rects[k]);
        }
    }
    return out;
}

void Renderer::Impl::groupTrees(int convexGroupFrom) {
    const std::size_t least = static_cast<std::size_t>(std::max(convexGroupFrom, 2));
    grouped.tree = csg::groupConvexProducts(separate.tree, convexOperands, PeelRequest::kMostGroupMembers, least);
    grouped.unionsOnly = reachedByUnionsOnly(grouped.tree, scene);
    // Of those, the ones that only unions lead to, a group per run
    // (groupUnionOperands): right only where every ray starts outside.
    std::vector<char> unitable(grouped.unionsOnly);
    unionOnlyOperands = 0;
    for (std::size_t k = 0; k < unitable.size(); ++k) {
        if (grouped.tree.leavesOf(k).size() > 1) unitable[k] = 0;
        unionOnlyOperands += unitable[k] ? 1 : 0;
    }
    unionGrouped.tree = csg::groupUnionOperands(grouped.tree, unitable, PeelRequest::kMostUnionMembers);
    unionGrouped.unionsOnly = reachedByUnionsOnly(unionGrouped.tree, scene);
    if (!besideLeaves.empty()) {
        besideGrouped.tree = csg::groupConvexProducts(besideSeparate.tree, besideConvexOperands,
                                                      PeelRequest::kMostGroupMembers, least);
        besideGrouped.unionsOnly = reachedByUnionsOnly(besideGrouped.tree, scene);
    }
    groupedFrom = convexGroupFrom;
    // The evaluator may hold a tree made before.
    if (current != &separate && current != &besideSeparate) current = nullptr;
}

FramePlan Renderer::Impl::planFrame(const ViewSetup& view, const RenderSettings& settings, bool aovs,
                                    LeafRects& leafRects) const {
    FrameFacts facts;
    facts.outside = beyondNearPlane(view, scene.bounds());
    facts.plainScene = !plainLeaves.empty();
    facts.plainBesideScene = !besideLeaves.empty();
    if (facts.plainBesideScene && settings.plainUnions && facts.outside) {
        std::vector<PixelRect> plainRects, csgRects;
        for (int leaf : besideLeaves) plainRects.push_back(leafRects(leaf));
        for (int leaf : besideSeparate.tree.operandLeaf) csgRects.push_back(leafRects(leaf));
        facts.plainBesideShare = plainBesideShare(view.width, view.height, EvaluatePass::kBlock, plainRects, csgRects);
    }
    facts.resultPeel = roundSink != nullptr;
    facts.aovs = aovs;
    facts.unionOnlyOperands = unionOnlyOperands;
    for (std::size_t form = 0; form < kTreeForms; ++form)
        facts.kinds[form] = compilation(static_cast<TreeForm>(form)).tree.kind;
    return render::planFrame(facts, settings);
}

ViewSetup Renderer::Impl::drawFrame(const Camera& camera, const RenderSettings& requested, Frame& frame,
                                    bool aovs) {
    const RenderSettings settings = deviceSettings(requested);
    const auto frameStart = Clock::now();
    ViewSetup view = frameView(camera, settings);
    passTimes = settings.passTimes;
    if (groupedFrom != settings.convexGroupFrom) groupTrees(settings.convexGroupFrom);
    // A thin bar seen aslant (a Menger sponge's) reaches a few blocks of the
    // many its rectangle holds: its screen hull says which. Leaves of many
    // vertices keep their rectangle alone.
    constexpr std::size_t kMostHullVertices = 4096;
    LeafRects leafRects(view, scene, settings.screenHulls ? kMostHullVertices : 0);
    const FramePlan plan = planFrame(view, settings, aovs, leafRects);
    // The result peel (sampleResult) runs its rays along the model's axes,
    // on grids that put rays exactly along a solid's silhouette edges,
    // where the rasterizer's depths of the front and back faces that meet
    // there (interpolated from vertices snapped to its sub-pixel grid) part
    // by up to 2^-17 of the scene's scale: a chord that exact arithmetic
    // gives no length. Its cells are far coarser than that, so it takes
    // sixteen times the tolerance of an image.
    if (plan.resultPeel) view.coincidence *= 16.0;
    const ColorScheme& scheme = colorScheme(settings.colorScheme);

    frame.width = view.width;
    frame.height = view.height;
    FrameStats& stats = frame.stats;
    stats.layersPerLeaf.assign(leafCount, 0);
    if (settings.keepBlockForms) {
        frame.blockForms.assign(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height),
                                BlockForm::None);
    }
    const Compilation& chosen = compilation(plan.form);
    if (current != &chosen && !plan.plainFrame) {
        evaluate->setTree(chosen.tree, canMarkLeaves);
        current = &chosen;
    }
    const csg::CompiledTree& compiled = chosen.tree;
    stats.operands = compiled.operandCount();
    stats.tiles = 0;
    stats.peelPasses = 0;
    const ScreenRects screen = screenRects(compiled, plan, leafRects);

    resetDrawState();
    targets.ensure(view.width, view.height);
    // A pixel around `drawn` for the shade pass's Sobel filter.
    // The translucent and alpha passes read the result beyond the marked pixels.
    if (!plan.shownOnly) {
        using NormalClear = FrameTargets::NormalClear;
        targets.clearResult(aovs || !translucentLeaves.empty() || !alphaLeaves.empty(),
                            plan.aovNormals                                           ? NormalClear::WholeFrame
                            : (plan.evaluated && plan.litAsDrawn) || plan.plainBeside ? NormalClear::None
                                                                                      : NormalClear::Drawn,
                            screen.drawn.grown(1));
    }
    targets.leafMarks = settings.leafMarks && canMarkLeaves;
    targets.plainFrame = plan.plainFrame;
    targets.plainBeside = false;
    targets.plainMarks = false;
    if (copiedLeaves > 0) {
        stats.notes.push_back(std::to_string(copiedLeaves) +
                              (copiedLeaves == 1 ? " leaf repeats a lower one exactly and shares its peeled layers"
                                                 : " leaves repeat lower ones exactly and share their peeled layers"));
    }
    std::optional<Lighting> litAs;
    if (plan.litAsDrawn) litAs = settings.lighting;
    stats.litAsDrawn = plan.litAsDrawn;
    if (plan.plainFrame) {
        PlainPass::Output output;
        output.litAs = litAs;
        output.shownOnly = plan.shownOnly;
        output.background = glm::vec4(glm::vec3(scheme.background), 1.0f);
        // Only shown, the '%' and '#' leaves read the plain pass's own depth
        // image; read back, every image is kept anyway.
        output.keepResult = !alphaLeaves.empty();
        output.depthRead = plan.shownOnly && !translucentLeaves.empty();
        drawPlain(view, screen.drawn, ShadePass::baseColors(scene, scheme), output, frame);
    } else if (plan.evaluated && plan.plainBeside) {
        // The plain leaves first, straight into the G-buffer, only what the
        // frame needs of them (the shown-only targets): the depth and leaf
        // codes everywhere, a miss where none is drawn, for the evaluator,
        // which then reads them at each pixel it may write; the colour lit
        // as drawn, or the normals and the marks for the shade pass.
        PlainPass::Output output;
        output.litAs = litAs;
        output.shownOnly = true;
        output.keepResult = true;
        output.beside = true;
        output.background = glm::vec4(glm::vec3(scheme.background), 1.0f);
        const std::vector<glm::vec2> baseColors = ShadePass::baseColors(scene, scheme);
        // Over the whole frame's rectangle: the plain pass clears its marks
        // there, which the evaluator then writes too.
        drawPlain(view, screen.drawn, baseColors, output, frame);
        targets.plainBeside = true;
        targets.plainMarks = !litAs;
        peelAndEvaluate(view, plan, screen.rects, screen.markLeaves, screen.markRects, settings, baseColors, litAs,
                        leafRects, frame);
    } else if (plan.evaluated) {
        if (plan.litAsDrawn) {
            // The normal pass lights only the pixels the result covers.
            const float background[4] = {scheme.background.r, scheme.background.g, scheme.background.b, 1.0f};
            glClearNamedFramebufferfv(targets.colorTarget.id(), GL_COLOR, 0, background);
        }
        peelAndEvaluate(view, plan, screen.rects, screen.markLeaves, screen.markRects, settings,
                        ShadePass::baseColors(scene, scheme), litAs, leafRects, frame);
    } else {
        stats.notes.push_back(compiled.kind == csg::CompiledTree::Kind::Empty ? "the CSG result is empty"
                                                                        : "the CSG result is everything");
    }

    if (!plan.resultPeel) {
        const auto start = Clock::now();
        // A plain frame only shown keeps no result images: its own depth
        // image (PlainPass::Output::depthRead) stands in for them.
        const gpu::Texture* windowDepth = nullptr;
        if (plan.plainFrame && plan.shownOnly) windowDepth = plan.litAsDrawn ? &targets.shownDepth : &targets.plainDepth;
        shadeFrame(view, scheme, settings, screen.drawn, plan.litAsDrawn, windowDepth);
        stats.shadeMs = msSince(start);
    }
    stats.totalMs = msSince(frameStart);
    return view;
}

Frame Renderer::render(const Camera& camera, const RenderSettings& settings) {
    Frame frame;
    impl_->drawFrame(camera, settings, frame, true);
    const auto start = Clock::now();
    impl_->readBack(frame, settings);
    frame.stats.readbackMs = msSince(start);
    frame.stats.totalMs += frame.stats.readbackMs;
    return frame;
}

Frame Renderer::shade(const Camera& camera, const RenderSettings& settings, const ExternalResult& result) {
    Impl& impl = *impl_;
    if (!impl.hasScene) throw Error("renderer: shade() before setScene()");
    const auto frameStart = Clock::now();
    const ColorScheme& scheme = colorScheme(settings.colorScheme);
    const ViewSetup view = makeView(camera, impl.scene.bounds());
    const int w = view.width, h = view.height;
    const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (result.depth.size() != n || result.normal.size() != n || result.leaf.size() != n || result.cut.size() != n)
        throw Error("renderer: shade() needs width * height values in every AOV");

    // The G-buffer as the normal pass writes it, then flipped to GL's bottom-up rows.
    const std::vector<glm::vec2> bases = ShadePass::baseColors(impl.scene, scheme);
    std::vector<float> depth(result.depth.begin(), result.depth.end());
    std::vector<float> normal(n * 4, 0.0f);
    std::vector<std::int32_t> codes(n, shader::kLeafMiss);
    for (std::size_t i = 0; i < n; ++i) {
        const int leaf = result.leaf[i];
        if (leaf < 0) continue;
        if (static_cast<std::size_t>(leaf) >= bases.size())
            throw Error("renderer: shade() got leaf " + std::to_string(leaf) + ", which the scene lacks");
        const glm::vec2 base = bases[static_cast<std::size_t>(leaf)];
        normal[i * 4 + 0] = result.normal[i].x;
        normal[i * 4 + 1] = result.normal[i].y;
        normal[i * 4 + 2] = result.normal[i].z;
        normal[i * 4 + 3] = result.cut[i] ? base.y : base.x;
        codes[i] = shader::leafCode(leaf, result.cut[i] != 0);
    }
    resetDrawState();
    impl.targets.ensure(w, h);
    impl.targets.plainFrame = false;
    impl.targets.plainBeside = false;
    impl.targets.plainMarks = false;
    flipRows(std::span(depth), w, h, 1);
    flipRows(std::span(normal), w, h, 4);
    flipRows(std::span(codes), w, h, 1);
    impl.targets.resultDepth.upload(0, 0, 0, w, h, 1, GL_RED, GL_FLOAT, depth.data());
    impl.targets.normal.upload(0, 0, 0, w, h, 1, GL_RGBA, GL_FLOAT, normal.data());
    impl.targets.resultLeaf.upload(0, 0, 0, w, h, 1, GL_RED_INTEGER, GL_INT, codes.data());

    Frame frame;
    frame.width = w;
    frame.height = h;
    const auto start = Clock::now();
    impl.shadeFrame(view, scheme, settings, std::nullopt);
    frame.stats.shadeMs = msSince(start);
    impl.readColor(frame);
    frame.depth.assign(result.depth.begin(), result.depth.end());
    frame.normal.assign(result.normal.begin(), result.normal.end());
    frame.leaf.assign(result.leaf.begin(), result.leaf.end());
    for (std::int32_t leaf : frame.leaf) frame.stats.coveredPixels += leaf >= 0 ? 1 : 0;
    gpu::checkErrors();
    frame.stats.totalMs = msSince(frameStart);
    return frame;
}

FrameStats Renderer::renderInto(unsigned framebuffer, int x, int y, const Camera& camera,
                                const RenderSettings& settings) {
    Frame frame;
    impl_->drawFrame(camera, settings, frame, false);
    const auto start = Clock::now();
    glBlitNamedFramebuffer(impl_->targets.colorTarget.id(), framebuffer, 0, 0, frame.width, frame.height, x, y,
                           x + frame.width, y + frame.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glFinish();
    gpu::checkErrors();
    frame.stats.readbackMs = msSince(start);
    frame.stats.totalMs += frame.stats.readbackMs;
    return frame.stats;
}

}  // namespace strata::render
