#include "EvaluatePass.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <span>
#include <string>

#include <glm/vec4.hpp>

#include "SceneBuffers.h"
#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// llvmpipe stops all loops of one shader invocation after 65535 iterations in
// total (gallivm's loop limiter); stay inside that, and mark the pixels that
// would not fit (see uLoopBudget in evaluate.frag).
int loopBudgetForThisDriver() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool limited = renderer != nullptr && std::string(renderer).find("llvmpipe") != std::string::npos;
    // The shader counts one pixel's iterations; the limiter counts those of
    // the 8 or 16 pixels that run in lockstep, which can be more where their
    // walks differ. Half the limit leaves that margin.
    return limited ? 30000 : std::numeric_limits<int>::max();
}

// Bit m of a truth table: the result when slot i is inside exactly for the bits i of m.
using TruthTable = std::array<std::uint64_t, 4>;

// `code`'s truth table over the operands `used` (at most 8; slot i is
// used[i]), all 256 states at once: each stack entry is the 256-bit column
// of its value.
TruthTable truthTable(const std::vector<std::uint32_t>& code, const std::vector<std::uint32_t>& used) {
    auto column = [&](std::uint32_t instruction) {
        const std::uint32_t operand = instruction >> csg::kOperandShift;
        const auto slot = static_cast<std::size_t>(std::find(used.begin(), used.end(), operand) - used.begin());
        TruthTable c{};
        for (std::uint32_t m = 0; m < 256; ++m) {
            if ((m >> slot) & 1u) c[m / 64] |= std::uint64_t(1) << (m % 64);
        }
        if (instruction & csg::kOpNegate) {
            for (std::uint64_t& w : c) w = ~w;
        }
        return c;
    };
    auto combine = [](std::uint32_t op, TruthTable& top, const TruthTable& source) {
        for (std::size_t w = 0; w < top.size(); ++w) top[w] = op == csg::kOpAnd ? top[w] & source[w] : top[w] | source[w];
    };
    return csg::foldCode<TruthTable>(code, column, combine);
}

}  // namespace

EvaluatePass::EvaluatePass() : empty_("evaluate") {}

int EvaluatePass::capacityFor(int count) {
    int capacity = 16;
    while (capacity < count) capacity *= 2;
    return capacity;
}

gpu::Program& EvaluatePass::programFor(Variant variant, bool leafMarks, bool resultPeel, bool plainBeside) {
    const ProgramKey key{variant, leafMarks, groups_, resultPeel, plainBeside};
    auto it = variants_.find(key);
    if (it == variants_.end()) {
        std::vector<gpu::ShaderDefine> defines;
        if (leafMarks) defines.push_back({"LEAF_MARKS", "1"});
        if (resultPeel) defines.push_back({"RESULT_PEEL", "1"});
        if (groups_) defines.push_back({"GROUPS", "1"});
        if (plainBeside) defines.push_back({"PLAIN_BESIDE", "1"});
        switch (variant.form) {
            case BlockForm::FirstSurface: defines.push_back({"FIRST_SURFACE_FORM", "1"}); break;
            case BlockForm::Register: defines.push_back({"REGISTER_FORM", "1"}); break;
            case BlockForm::Product: defines.push_back({"PRODUCT_FORM", "1"}); break;
            default: defines.push_back({"ARRAY_FORM", "1"});
        }
        if (variant.maxLive > 0) defines.push_back({"MAX_LIVE", std::to_string(variant.maxLive)});
        it = variants_
                 .emplace(key,
                          gpu::Program::fromFiles("evaluate", {"csg/evaluate.vert", "csg/evaluate.frag"}, defines))
                 .first;
    }
    return it->second;
}

void EvaluatePass::setTree(const csg::CompiledTree& tree, bool leafMarks) {
    tree_ = tree;
    operandLeaf_ = tree.operandLeaf;
    // The variants that look up a group's member cost every written pixel a
    // lookup (both sides of a branch run on llvmpipe): only where needed.
    groups_ = std::any_of(tree.operandGroups.begin(), tree.operandGroups.end(),
                          [](const std::vector<int>& members) { return !members.empty(); });
    // Every leaf the evaluator may write: the operands' and their groups' members.
    leafCount_ = operandLeaf_.empty() ? 0 : static_cast<std::size_t>(operandLeaf_.back()) + 1;
    for (const std::vector<int>& members : tree.operandGroups) {
        if (!members.empty()) leafCount_ = std::max(leafCount_, static_cast<std::size_t>(members.back()) + 1);
    }
    shownFaces_ = gpu::Buffer("shown faces", std::max<std::size_t>(leafCount_, 1) * sizeof(std::uint32_t), nullptr,
                              GL_DYNAMIC_STORAGE_BIT);
    // Compile now rather than mid-frame the variants that most scenes use.
    if (!operandLeaf_.empty()) {
        const int operands = tree.operandCount();
        programFor({BlockForm::FirstSurface, 0}, leafMarks);
        programFor({BlockForm::Register, 4}, leafMarks);
        const bool product = !tree.code.empty() && csg::countingTree(tree.code).nodes.size() == 1;  // one AND or OR
        if (product && operands > kRegisterOperands) programFor({BlockForm::Product, 0}, leafMarks);
        if (operands > 4) programFor({BlockForm::Register, kRegisterOperands}, leafMarks);
        // The array form only as large as most blocks need: a block with
        // more live operands compiles its own variant when it comes. (The
        // largest ones do not link on every driver: NVIDIA's refused 2048.)
        if (operands > kRegisterOperands) {
            programFor({BlockForm::Array, capacityFor(std::min(operands, kPrecompiledLive))}, leafMarks);
        }
    }
}

std::vector<std::uint32_t> EvaluatePass::shownFaces() const {
    std::vector<std::uint32_t> faces(leafCount_);
    if (!faces.empty()) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        shownFaces_.downloadSpan(std::span(faces));
    }
    return faces;
}

EvaluatePass::BlockTree EvaluatePass::addTree(const std::vector<std::uint32_t>& code,
                                              const std::vector<OperandLayers>& operandLayers, TreeData& data,
                                              Forms forms) const {
    // The operands the tree reads, each once, and their layers in all.
    std::vector<std::uint32_t> used;
    int slots = 0;
    bool slotsReach = true;  // every layer number fits a slot's field
    for (std::uint32_t instruction : code) {
        if (instruction & csg::kOpFromStack) continue;
        const std::uint32_t operand = instruction >> csg::kOperandShift;
        if (std::find(used.begin(), used.end(), operand) != used.end()) continue;
        used.push_back(operand);
        slots += operandLayers[operand].count;
        slotsReach = slotsReach && static_cast<unsigned>(operandLayers[operand].first + operandLayers[operand].count) <=
                                       shader::kSlotLayerMask + 1u;
    }
    // The first-surface and product forms stop at the first change.
    if (forms == Forms::Any && code.size() == 1 && (code[0] & csg::kOpNegate) == 0 && slots == 1) {
        return firstSurfaceTree(used[0], operandLayers);
    }
    if (forms != Forms::ArrayOnly && slots <= kRegisterSlots &&
        used.size() <= static_cast<std::size_t>(kRegisterOperands) && slotsReach) {
        return registerTree(code, used, slots, operandLayers, data);
    }
    const csg::CountingTree tree = csg::countingTree(code);
    const bool onePassEach = slots == static_cast<int>(used.size());
    if (onePassEach && forms == Forms::Any && tree.nodes.size() == 1) return productTree(tree, operandLayers, data);
    return arrayTree(tree, used, operandLayers, data);
}

EvaluatePass::BlockTree EvaluatePass::firstSurfaceTree(std::uint32_t operand,
                                                       const std::vector<OperandLayers>& operandLayers) const {
    // The tree is the operand itself, of one layer. Its record holds that
    // layer and the leaf (and, set by planBlocks(), the leaf's front-face
    // mark); no literals.
    return {{static_cast<unsigned>(operandLayers[operand].first), static_cast<unsigned>(operandLeaf_[operand]), 0u, 0u},
            {BlockForm::FirstSurface, 0}};
}

EvaluatePass::BlockTree EvaluatePass::registerTree(const std::vector<std::uint32_t>& code,
                                                   const std::vector<std::uint32_t>& used, int slots,
                                                   const std::vector<OperandLayers>& operandLayers,
                                                   TreeData& data) const {
    // A slot per peeled layer, the tree as a truth table over the operands'
    // inside bits: in the record for 4 slots, in two nodes for 8 and 16.
    const TruthTable table = truthTable(code, used);
    BlockTree out;
    out.variant = {BlockForm::Register, slots <= 4 ? 4 : slots <= 8 ? 8 : kRegisterSlots};
    std::uint32_t tableField = static_cast<std::uint32_t>(table[0] & 0xffffu);
    if (out.variant.maxLive > 4) {
        tableField = static_cast<std::uint32_t>(data.nodes.size());
        for (int half = 0; half < 2; ++half) {
            const std::uint64_t a = table[static_cast<std::size_t>(half * 2)];
            const std::uint64_t b = table[static_cast<std::size_t>(half * 2 + 1)];
            data.nodes.emplace_back(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(a >> 32),
                                    static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(b >> 32));
        }
    }
    out.record = {static_cast<unsigned>(data.literals.size()), static_cast<unsigned>(slots), tableField, 0u};
    for (std::size_t bit = 0; bit < used.size(); ++bit) {
        const std::uint32_t operand = used[bit];
        for (int layer = 0; layer < operandLayers[operand].count; ++layer) {
            data.literals.emplace_back(static_cast<unsigned>(operandLayers[operand].first + layer),
                                       static_cast<unsigned>(bit),
                                       static_cast<unsigned>(operandLeaf_[operand]), 0u);
        }
    }
    return out;
}

EvaluatePass::BlockTree EvaluatePass::productTree(const csg::CountingTree& tree,
                                                  const std::vector<OperandLayers>& operandLayers,
                                                  TreeData& data) const {
    // One AND (OR) of literals; each literal's wish is its own value (its
    // negation, for an OR: the result is then !P).
    const bool isAnd = tree.nodes[0].isAnd;
    BlockTree out;
    out.variant = {BlockForm::Product, 0};
    out.record = {static_cast<unsigned>(data.literals.size()), static_cast<unsigned>(tree.literals.size()),
                  isAnd ? 0u : 1u, 0u};
    for (const csg::CountingTree::Literal& l : tree.literals) {
        const OperandLayers& layers = operandLayers[l.operand];
        data.literals.emplace_back(static_cast<unsigned>(layers.first), static_cast<unsigned>(layers.count),
                                   static_cast<unsigned>(operandLeaf_[l.operand]), l.negated == isAnd ? 0u : 1u);
    }
    return out;
}

EvaluatePass::BlockTree EvaluatePass::arrayTree(const csg::CountingTree& tree, const std::vector<std::uint32_t>& used,
                                                const std::vector<OperandLayers>& operandLayers,
                                                TreeData& data) const {
    // The counting tree. An operand with several literals (identical leaves
    // share one: IdenticalLeaves.h) is one live slot: its literals follow
    // each other, the first carrying their number above the layer count
    // (shader::kRunShift), the others 0 there.
    BlockTree out;
    out.record = {static_cast<unsigned>(data.literals.size()), static_cast<unsigned>(tree.literals.size()),
                  static_cast<unsigned>(data.nodes.size()), static_cast<unsigned>(tree.nodes.size())};
    out.variant = {BlockForm::Array, capacityFor(static_cast<int>(std::max(used.size(), tree.nodes.size())))};
    std::map<std::uint32_t, std::vector<const csg::CountingTree::Literal*>> byOperand;
    for (const csg::CountingTree::Literal& l : tree.literals) byOperand[l.operand].push_back(&l);
    for (std::uint32_t operand : used) {
        const std::size_t runStart = data.literals.size();
        const OperandLayers& layers = operandLayers[operand];
        for (const csg::CountingTree::Literal* l : byOperand[operand]) {
            data.literals.emplace_back(static_cast<unsigned>(layers.first), static_cast<unsigned>(layers.count),
                                       static_cast<unsigned>(operandLeaf_[operand]),
                                       l->parent | (l->negated ? shader::kNegate : 0u));
        }
        data.literals[runStart].y |= static_cast<unsigned>(data.literals.size() - runStart) << shader::kRunShift;
    }
    static_assert(csg::CountingTree::kNoParent == shader::kNoParent, "the root's parent reads as no node");
    for (const csg::CountingTree::Node& n : tree.nodes)
        data.nodes.emplace_back(n.parent, n.isAnd ? shader::kNodeAnd : 0u, n.children, n.trueWhenOutside);
    return out;
}

std::vector<int> EvaluatePass::groupTable(std::size_t leafCount, const csg::CompiledTree& tree,
                                          const std::vector<OperandLayers>& layers) {
    std::vector<int> table(std::max<std::size_t>(leafCount, 1), -1);
    for (std::size_t k = 0; k < tree.operandLeaf.size(); ++k) {
        if (layers[k].idsLayer < 0) continue;  // no group, or one missing the tile
        const std::span<const int> members = tree.leavesOf(k);
        table[static_cast<std::size_t>(tree.operandLeaf[k])] = static_cast<int>(table.size());
        table.push_back(layers[k].idsLayer);
        table.insert(table.end(), members.begin(), members.end());
    }
    return table;
}

std::vector<std::vector<std::uint32_t>> EvaluatePass::operandsPerBlock(
    const PixelRect& tile, int blocksX, const std::vector<OperandLayers>& operandLayers,
    const std::vector<PixelRect>& rects, const std::vector<ScreenHull>& hulls) const {
    const int blocksY = (tile.height + kBlock - 1) / kBlock;
    std::vector<std::vector<std::uint32_t>> operands(static_cast<std::size_t>(blocksX) *
                                                     static_cast<std::size_t>(blocksY));
    // A pixel of margin around a hull, as around a rectangle: the peel
    // rasterizes in float.
    constexpr double kMargin = 1.0;
    for (std::size_t k = 0; k < operandLeaf_.size(); ++k) {
        if (operandLayers[k].count == 0 || !rects[k].intersects(tile)) continue;
        const PixelRect valid = PeelPass::region(rects[k], tile, kBlock);
        // `valid` starts on a block corner and ends on one or at the tile's edge.
        const int bx0 = valid.x / kBlock, bx1 = (valid.x + valid.width + kBlock - 1) / kBlock;
        const int by1 = (valid.y + valid.height + kBlock - 1) / kBlock;
        const ScreenHull* hull = k < hulls.size() && !hulls[k].empty() ? &hulls[k] : nullptr;
        for (int by = valid.y / kBlock; by < by1; ++by) {
            int first = bx0, last = bx1 - 1;
            if (hull != nullptr) {
                // Only the blocks of this row whose pixel centres the hull can reach.
                const double y0 = tile.y + by * kBlock + 0.5 - kMargin;
                const double y1 = tile.y + std::min((by + 1) * kBlock, tile.height) - 0.5 + kMargin;
                double x0 = 0.0, x1 = 0.0;
                if (!hullSpan(*hull, y0, y1, x0, x1)) continue;
                const double px0 = std::ceil(x0 - kMargin - tile.x - 0.5), px1 = std::floor(x1 + kMargin - tile.x - 0.5);
                if (px1 < 0.0 || px0 >= tile.width) continue;
                first = std::max(first, static_cast<int>(std::max(px0, 0.0)) / kBlock);
                last = std::min(last, static_cast<int>(std::min(px1, tile.width - 1.0)) / kBlock);
            }
            for (int bx = first; bx <= last; ++bx) {
                operands[static_cast<std::size_t>(by * blocksX + bx)].push_back(static_cast<std::uint32_t>(k));
            }
        }
    }
    return operands;
}

EvaluatePass::BlockPlan EvaluatePass::planBlocks(const FrameTargets& targets, const PixelRect& tile,
                                                 const std::vector<OperandLayers>& operandLayers,
                                                 const std::vector<PixelRect>& rects,
                                                 const std::vector<ScreenHull>& hulls,
                                                 const std::vector<int>& groupTable, Forms forms) const {
    BlockPlan plan;
    plan.blocksX = (tile.width + kBlock - 1) / kBlock;
    const std::vector<std::vector<std::uint32_t>> operands =
        operandsPerBlock(tile, plan.blocksX, operandLayers, rects, hulls);
    // Blocks with the same operands share one specialised tree.
    plan.blocks.assign(operands.size(), glm::uvec4(0u));
    std::map<std::vector<std::uint32_t>, BlockTree> trees;  // operand list -> its tree
    std::vector<char> present(operandLeaf_.size(), 0);
    for (std::size_t b = 0; b < operands.size(); ++b) {
        const std::vector<std::uint32_t>& list = operands[b];
        if (list.empty()) continue;
        auto it = trees.find(list);
        if (it == trees.end()) {
            for (std::uint32_t k : list) present[k] = 1;
            const std::vector<std::uint32_t> specialised = csg::specializeCode(tree_, present);
            for (std::uint32_t k : list) present[k] = 0;
            it = trees.emplace(list, specialised.empty()
                                         ? BlockTree{}
                                         : addTree(specialised, operandLayers, plan.data, forms))
                     .first;
            // The first-surface form's mark, so its pixels need no lookup.
            BlockTree& tree = it->second;
            if (tree.variant.form == BlockForm::FirstSurface && targets.leafMarks) {
                tree.record.z =
                    static_cast<unsigned>(shader::stencilMark(targets.markSlot(static_cast<int>(tree.record.y)), 0));
            }
        }
        plan.blocks[b] = it->second.record;
        if (it->second.variant.form != BlockForm::None)
            plan.blocksOf[it->second.variant].push_back(static_cast<std::uint32_t>(b));
    }
    // Each draw's instances: runs of blocks along a row that share a record
    // (one tree: the same operands), one quad each. A cheese's cube alone
    // covers whole rows of blocks, and on llvmpipe every small triangle
    // costs its setup and binning.
    const auto blocksX = static_cast<std::uint32_t>(plan.blocksX);
    for (const auto& [variant, list] : plan.blocksOf) {
        const std::size_t before = plan.runs.size();
        for (std::size_t i = 0; i < list.size();) {
            const std::uint32_t b = list[i];
            std::size_t n = 1;
            while (i + n < list.size() && list[i + n] == b + n && (b + n) % blocksX != 0 &&
                   plan.blocks[list[i + n]] == plan.blocks[b]) {
                ++n;
            }
            plan.runs.emplace_back(b, static_cast<std::uint32_t>(n));
            i += n;
        }
        plan.runsOf[variant] = plan.runs.size() - before;
    }
    // The first-surface form reports only back faces: the front faces of its
    // operands count as shown beforehand. Where none shows (the eye inside the
    // operand, or the operand misses the block's pixels), the normal pass
    // draws them for nothing, and its mark test keeps them out of the image.
    plan.shownBefore.assign(leafCount_, 0u);
    for (const auto& [list, tree] : trees) {
        // A group's surfaces are its members', which the shader reports.
        if (tree.variant.form == BlockForm::FirstSurface && groupTable[tree.record.y] < 0)
            plan.shownBefore[tree.record.y] |= kFrontFaces;
    }
    return plan;
}

void EvaluatePass::draw(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                        const BlockPlan& plan, const std::vector<int>& groupTable, const gpu::Texture& groupIds,
                        double coincidence, FrameStats& stats, const gpu::Texture* start) {
    gpu::Buffer::uploadGrowing(blocks_, "evaluate blocks", plan.blocks);
    gpu::Buffer::uploadGrowing(blockOperands_, "evaluate block literals", plan.data.literals);
    gpu::Buffer::uploadGrowing(blockNodes_, "evaluate block nodes", plan.data.nodes);
    gpu::Buffer::uploadGrowing(drawnBlocks_, "evaluate drawn blocks", plan.runs);
    gpu::Buffer::uploadGrowing(groupTable_, "evaluate group table", groupTable);

    layers.bindUnit(shader::kTextureLayers);
    blockNodes_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferBlockNodes);
    blocks_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferBlocks);
    blockOperands_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferBlockOperands);
    drawnBlocks_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferDrawnBlocks);
    groupTable_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferGroupTable);
    if (groupIds.id() != 0) groupIds.bindUnit(shader::kTextureGroupIds);
    if (start != nullptr) start->bindUnit(shader::kTextureResultStart);
    if (!plan.shownBefore.empty()) shownFaces_.uploadSpan(std::span<const std::uint32_t>(plan.shownBefore));
    shownFaces_.bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferShownFaces);
    if (targets.leafMarks) targets.markSlotBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, shader::kBufferMarkSlots);
    const bool plainBeside = targets.plainBeside && start == nullptr;
    if (plainBeside) {
        // The plain leaves' surfaces, which each invocation reads at its own
        // pixel and may overwrite there (evaluate.frag, PLAIN_BESIDE).
        targets.resultDepth.bindUnit(shader::kTexturePlainDepth);
        targets.resultLeaf.bindUnit(shader::kTexturePlainLeaf);
        glTextureBarrier();
    }
    targets.evaluateFramebuffer().bindForDraw();
    glViewport(tile.x, tile.y, tile.width, tile.height);
    // A pixel the shader writes (does not discard) is marked for the later
    // passes: with kMarkWritten, or with the value the shader gives (leaf marks).
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, shader::kMarkWritten, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    empty_.bind();
    static const int loopBudget = loopBudgetForThisDriver();
    int first = 0;
    for (const auto& [variant, list] : plan.blocksOf) {
        switch (variant.form) {
            case BlockForm::FirstSurface: stats.firstSurfaceBlocks += list.size(); break;
            case BlockForm::Product: stats.productBlocks += list.size(); break;
            case BlockForm::Register: stats.registerBlocks += list.size(); break;
            default: stats.arrayBlocks += list.size();
        }
        const auto runs = static_cast<int>(plan.runsOf.at(variant));
        gpu::Program& program = programFor(variant, targets.leafMarks, start != nullptr, plainBeside);
        program.setUniform(shader::kEvaluateTileOrigin, glm::ivec2(tile.x, tile.y));
        if (variant.form == BlockForm::Product || variant.form == BlockForm::Array)
            program.setUniform(shader::kEvaluateLoopBudget, loopBudget);
        program.setUniform(shader::kEvaluateFirstBlock, first);
        program.setUniform(shader::kEvaluateTileSize, glm::ivec2(tile.width, tile.height));
        program.setUniform(shader::kEvaluateBlocksX, plan.blocksX);
        program.setUniform(shader::kEvaluateCoincidence, static_cast<float>(coincidence));
        program.use();
        glDrawArraysInstanced(GL_TRIANGLES, 0, 6, runs);
        first += runs;
    }
    glDisable(GL_STENCIL_TEST);
    gpu::checkErrors();
}

void EvaluatePass::run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                       const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
                       const std::vector<ScreenHull>& hulls, const std::vector<int>& groupTable, const gpu::Texture& groupIds, bool generalOnly,
                       double coincidence, FrameStats& stats, std::vector<BlockForm>* forms) {
    if (operandLeaf_.empty()) return;
    const BlockPlan plan =
        planBlocks(targets, tile, operandLayers, rects, hulls, groupTable, generalOnly ? Forms::ArrayOnly : Forms::Any);
    if (forms != nullptr) {
        forms->assign(plan.blocks.size(), BlockForm::None);
        for (const auto& [variant, list] : plan.blocksOf) {
            for (std::uint32_t b : list) (*forms)[b] = variant.form;
        }
    }
    draw(targets, layers, tile, plan, groupTable, groupIds, coincidence, stats);
}

void EvaluatePass::runResultRound(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                                  const std::vector<OperandLayers>& operandLayers,
                                  const std::vector<PixelRect>& rects, const std::vector<ScreenHull>& hulls,
                                  const std::vector<int>& groupTable, const gpu::Texture& groupIds,
                                  const gpu::Texture& start, bool samePlan,
                                  double coincidence, FrameStats& stats) {
    if (operandLeaf_.empty()) return;
    if (!samePlan) roundPlan_ = planBlocks(targets, tile, operandLayers, rects, hulls, groupTable, Forms::WalkOn);
    draw(targets, layers, tile, roundPlan_, groupTable, groupIds, coincidence, stats, &start);
}

}  // namespace strata::render
