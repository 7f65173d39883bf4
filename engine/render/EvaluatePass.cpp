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

// Uniform locations in shaders/csg/evaluate.frag (the loop budget: array and product forms).
constexpr GLint kTileOrigin = 2;
constexpr GLint kLoopBudget = 4;
// ... and in shaders/csg/evaluate.vert.
constexpr GLint kFirstBlock = 5;
constexpr GLint kTileSize = 6;
constexpr GLint kBlocksX = 7;

// The register form's slot (blocks.glsl): the vertex stage packs its layer
// number below kSlotLayers and, above it, its operand's bit in the truth
// table, plus kSlotFirstLayer on the operand's first layer.
constexpr int kSlotLayers = 1 << 16;
constexpr unsigned kSlotFirstLayer = 8u;

// The array form's literals: their layer count below kRunShift, and above it,
// on an operand's first literal, how many of its literals follow each other.
constexpr int kRunShift = 16;

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
        const std::uint32_t operand = instruction >> kOperandShift;
        const auto slot = static_cast<std::size_t>(std::find(used.begin(), used.end(), operand) - used.begin());
        TruthTable c{};
        for (std::uint32_t m = 0; m < 256; ++m) {
            if ((m >> slot) & 1u) c[m / 64] |= std::uint64_t(1) << (m % 64);
        }
        if (instruction & kOpNegate) {
            for (std::uint64_t& w : c) w = ~w;
        }
        return c;
    };
    auto combine = [](std::uint32_t op, TruthTable& top, const TruthTable& source) {
        for (std::size_t w = 0; w < top.size(); ++w) top[w] = op == kOpAnd ? top[w] & source[w] : top[w] | source[w];
    };
    return foldCode<TruthTable>(code, column, combine);
}

}  // namespace

EvaluatePass::EvaluatePass() : empty_("evaluate") {}

BlockForm EvaluatePass::blockForm(int variant) {
    return variant == kFirstSurfaceForm ? BlockForm::FirstSurface
           : variant == kProductForm    ? BlockForm::Product
           : variant <= kRegisterForm   ? BlockForm::Register
                                        : BlockForm::Array;
}

int EvaluatePass::capacityFor(int count) {
    int capacity = 16;
    while (capacity < count) capacity *= 2;
    return capacity;
}

gpu::Program& EvaluatePass::programFor(int form, bool leafMarks) {
    const int key = (form * 2 + (leafMarks ? 1 : 0)) * 2 + (groups_ ? 1 : 0);
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        std::vector<gpu::ShaderDefine> defines{{"BLOCK", std::to_string(kBlock)}};
        if (leafMarks) defines.push_back({"LEAF_MARKS", "1"});
        if (groups_) defines.push_back({"GROUPS", "1"});
        if (form == kProductForm) {
            defines.push_back({"PRODUCT_FORM", "1"});
        } else if (form == kFirstSurfaceForm) {
            defines.push_back({"FIRST_SURFACE_FORM", "1"});
        } else {
            defines.push_back({"MAX_LIVE", std::to_string(form)});
        }
        it = programs_
                 .emplace(key,
                          gpu::Program::fromFiles("evaluate", {"csg/evaluate.vert", "csg/evaluate.frag"}, defines))
                 .first;
    }
    return it->second;
}

void EvaluatePass::setProgram(const TreeProgram& program, bool leafMarks) {
    program_ = program;
    operandLeaf_ = program.operandLeaf;
    // The variants that look up a group's member cost every written pixel a
    // lookup (both sides of a branch run on llvmpipe): only where needed.
    groups_ = std::any_of(program.operandGroups.begin(), program.operandGroups.end(),
                          [](const std::vector<int>& members) { return !members.empty(); });
    // Every leaf the evaluator may write: the operands' and their groups' members.
    leafCount_ = operandLeaf_.empty() ? 0 : static_cast<std::size_t>(operandLeaf_.back()) + 1;
    for (const std::vector<int>& members : program.operandGroups) {
        if (!members.empty()) leafCount_ = std::max(leafCount_, static_cast<std::size_t>(members.back()) + 1);
    }
    shownFaces_ = gpu::Buffer("shown faces", std::max<std::size_t>(leafCount_, 1) * sizeof(std::uint32_t), nullptr,
                              GL_DYNAMIC_STORAGE_BIT);
    // Compile now rather than mid-frame the variants that most scenes use.
    if (!operandLeaf_.empty()) {
        programFor(kFirstSurfaceForm, leafMarks);
        programFor(4, leafMarks);
        const bool product = !program.code.empty() && countingTree(program.code).nodes.size() == 1;  // one AND or OR
        if (product && program.operandCount() > kRegisterForm) programFor(kProductForm, leafMarks);
        if (program.operandCount() > 4) programFor(kRegisterForm, leafMarks);
        if (program.operandCount() > kRegisterForm) programFor(capacityFor(program.operandCount()), leafMarks);
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
                                              const std::vector<OperandLayers>& operandLayers,
                                              std::vector<glm::uvec4>& literals, std::vector<glm::uvec4>& nodes,
                                              bool generalOnly) const {
    auto literal = [&](std::uint32_t operand, std::uint32_t parent) {
        const OperandLayers& layers = operandLayers[operand];
        return glm::uvec4(static_cast<unsigned>(layers.first), static_cast<unsigned>(layers.count),
                          static_cast<unsigned>(operandLeaf_[operand]), parent);
    };
    // The operands the tree reads, each once, and their layers in all.
    std::vector<std::uint32_t> used;
    int slots = 0;
    bool slotsReach = true;  // every layer number fits a slot's field
    for (std::uint32_t instruction : code) {
        if (instruction & kOpFromStack) continue;
        const std::uint32_t operand = instruction >> kOperandShift;
        if (std::find(used.begin(), used.end(), operand) != used.end()) continue;
        used.push_back(operand);
        slots += operandLayers[operand].count;
        slotsReach = slotsReach && operandLayers[operand].first + operandLayers[operand].count <= kSlotLayers;
    }
    const bool onePassEach = slots == static_cast<int>(used.size());

    BlockTree out;
    if (!generalOnly && code.size() == 1 && (code[0] & kOpNegate) == 0 && slots == 1) {
        // The first-surface form: the tree is the operand itself, of one
        // layer. Its record holds that layer and the leaf (and, set by run(),
        // the leaf's first mark); no literals.
        const std::uint32_t operand = used[0];
        out.form = kFirstSurfaceForm;
        out.record = {static_cast<unsigned>(operandLayers[operand].first), static_cast<unsigned>(operandLeaf_[operand]),
                      0u, 0u};
        return out;
    }
    if (!generalOnly && slots <= kRegisterForm && slotsReach) {
        // The register form: a slot per peeled layer, the tree as a truth
        // table over the operands' inside bits.
        const TruthTable table = truthTable(code, used);
        out.form = slots <= 4 ? 4 : kRegisterForm;
        std::uint32_t tableField = static_cast<std::uint32_t>(table[0] & 0xffffu);
        if (out.form == kRegisterForm) {
            tableField = static_cast<std::uint32_t>(nodes.size());
            for (int half = 0; half < 2; ++half) {
                const std::uint64_t a = table[static_cast<std::size_t>(half * 2)];
                const std::uint64_t b = table[static_cast<std::size_t>(half * 2 + 1)];
                nodes.emplace_back(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(a >> 32),
                                   static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(b >> 32));
            }
        }
        out.record = {static_cast<unsigned>(literals.size()), static_cast<unsigned>(slots), tableField, 0u};
        for (std::size_t bit = 0; bit < used.size(); ++bit) {
            const std::uint32_t operand = used[bit];
            for (int layer = 0; layer < operandLayers[operand].count; ++layer) {
                const unsigned info = static_cast<unsigned>(bit) | (layer == 0 ? kSlotFirstLayer : 0u);
                literals.emplace_back(static_cast<unsigned>(operandLayers[operand].first + layer), info,
                                      static_cast<unsigned>(operandLeaf_[operand]), 0u);
            }
        }
        return out;
    }
    const CountingTree tree = countingTree(code);
    if (onePassEach && !generalOnly && tree.nodes.size() == 1) {
        // The product form: one AND (OR) of literals; each literal's wish is
        // its own value (its negation, for an OR: the result is then !P).
        const bool isAnd = tree.nodes[0].isAnd;
        out.form = kProductForm;
        out.record = {static_cast<unsigned>(literals.size()), static_cast<unsigned>(tree.literals.size()),
                      isAnd ? 0u : 1u, 0u};
        for (const CountingTree::Literal& l : tree.literals)
            literals.push_back(literal(l.operand, l.negated == isAnd ? 0u : 1u));
        return out;
    }
    // The array form: the counting tree. An operand with several literals
    // (identical leaves share one: IdenticalLeaves.h) is one live slot: its
    // literals follow each other, the first carrying their number above the
    // layer count (kRunShift), the others 0 there.
    out.record = {static_cast<unsigned>(literals.size()), static_cast<unsigned>(tree.literals.size()),
                  static_cast<unsigned>(nodes.size()), static_cast<unsigned>(tree.nodes.size())};
    out.form = capacityFor(static_cast<int>(std::max(used.size(), tree.nodes.size())));
    std::map<std::uint32_t, std::vector<const CountingTree::Literal*>> byOperand;
    for (const CountingTree::Literal& l : tree.literals) byOperand[l.operand].push_back(&l);
    for (std::uint32_t operand : used) {
        const std::size_t runStart = literals.size();
        for (const CountingTree::Literal* l : byOperand[operand])
            literals.push_back(literal(l->operand, l->parent | (l->negated ? 0x80000000u : 0u)));
        literals[runStart].y |= static_cast<unsigned>(literals.size() - runStart) << kRunShift;
    }
    for (const CountingTree::Node& n : tree.nodes)
        nodes.emplace_back(n.parent, n.isAnd ? 1u : 0u, n.children, n.trueWhenOutside);
    return out;
}

std::vector<int> EvaluatePass::groupTable(std::size_t leafCount, const TreeProgram& program,
                                          const std::vector<OperandLayers>& layers) {
    std::vector<int> table(std::max<std::size_t>(leafCount, 1), -1);
    for (std::size_t k = 0; k < program.operandLeaf.size(); ++k) {
        if (layers[k].group < 0) continue;  // no group, or one missing the tile
        const std::span<const int> members = program.leavesOf(k);
        table[static_cast<std::size_t>(program.operandLeaf[k])] = static_cast<int>(table.size());
        table.push_back(layers[k].group);
        table.insert(table.end(), members.begin(), members.end());
    }
    return table;
}

void EvaluatePass::run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                       const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects,
                       const std::vector<int>& groupTable, const gpu::Texture& groupIds, bool generalOnly,
                       FrameStats& stats, std::vector<BlockForm>* forms) {
    if (operandLeaf_.empty()) return;
    // The operands whose rectangle meets each block.
    const int blocksX = (tile.width + kBlock - 1) / kBlock;
    const int blocksY = (tile.height + kBlock - 1) / kBlock;
    const std::size_t blockCount = static_cast<std::size_t>(blocksX) * static_cast<std::size_t>(blocksY);
    std::vector<std::vector<std::uint32_t>> members(blockCount);
    for (std::size_t k = 0; k < operandLeaf_.size(); ++k) {
        if (operandLayers[k].count == 0 || !rects[k].intersects(tile)) continue;
        const PixelRect valid = PeelPass::region(rects[k], tile, kBlock);
        // `valid` starts on a block corner and ends on one or at the tile's edge.
        const int bx1 = (valid.x + valid.width + kBlock - 1) / kBlock;
        const int by1 = (valid.y + valid.height + kBlock - 1) / kBlock;
        for (int by = valid.y / kBlock; by < by1; ++by) {
            for (int bx = valid.x / kBlock; bx < bx1; ++bx) {
                members[static_cast<std::size_t>(by * blocksX + bx)].push_back(static_cast<std::uint32_t>(k));
            }
        }
    }
    // Blocks with the same operands share one specialised tree.
    std::vector<glm::uvec4> blocks(blockCount, glm::uvec4(0u));
    std::vector<glm::uvec4> literals;
    std::vector<glm::uvec4> nodes;
    std::map<std::vector<std::uint32_t>, BlockTree> trees;  // operand list -> its tree
    std::vector<char> present(operandLeaf_.size(), 0);
    std::map<int, std::vector<std::uint32_t>> byForm;  // shader variant -> its blocks
    for (std::size_t b = 0; b < blockCount; ++b) {
        const std::vector<std::uint32_t>& list = members[b];
        if (list.empty()) continue;
        auto it = trees.find(list);
        if (it == trees.end()) {
            for (std::uint32_t k : list) present[k] = 1;
            const std::vector<std::uint32_t> specialised = specializeProgram(program_, present);
            for (std::uint32_t k : list) present[k] = 0;
            it = trees.emplace(list, specialised.empty() ? BlockTree{}
                                                         : addTree(specialised, operandLayers, literals, nodes,
                                                                   generalOnly))
                     .first;
            // The first-surface form's mark base, so its pixels need no lookup.
            BlockTree& tree = it->second;
            if (tree.form == kFirstSurfaceForm && targets.leafMarks) {
                tree.record.z = 1u + 4u * static_cast<unsigned>(targets.markSlot(static_cast<int>(tree.record.y)));
            }
        }
        blocks[b] = it->second.record;
        if (it->second.form > 0) byForm[it->second.form].push_back(static_cast<std::uint32_t>(b));
    }
    // Each draw's instances: runs of blocks along a row that share a record
    // (one tree: the same operands), one quad each. A cheese's cube alone
    // covers whole rows of blocks, and on llvmpipe every small triangle
    // costs its setup and binning.
    std::vector<glm::uvec2> drawn;  // first block, blocks in the run
    std::map<int, std::size_t> runs;  // shader variant -> its instances
    for (const auto& [form, list] : byForm) {
        const std::size_t before = drawn.size();
        for (std::size_t i = 0; i < list.size();) {
            const std::uint32_t b = list[i];
            std::size_t n = 1;
            while (i + n < list.size() && list[i + n] == b + n && (b + n) % static_cast<std::uint32_t>(blocksX) != 0 &&
                   blocks[list[i + n]] == blocks[b]) {
                ++n;
            }
            drawn.emplace_back(b, static_cast<std::uint32_t>(n));
            i += n;
        }
        runs[form] = drawn.size() - before;
    }
    if (forms != nullptr) {
        forms->assign(blockCount, BlockForm::None);
        for (const auto& [form, list] : byForm) {
            for (std::uint32_t b : list) (*forms)[b] = blockForm(form);
        }
    }
    // The first-surface form reports only back faces: the front faces of its
    // operands count as shown beforehand. Where none shows (the eye inside the
    // operand, or the operand misses the block's pixels), the normal pass
    // draws them for nothing, and its mark test keeps them out of the image.
    std::vector<std::uint32_t> faces(leafCount_, 0u);
    for (const auto& [list, tree] : trees) {
        // A group's surfaces are its members', which the shader reports.
        if (tree.form == kFirstSurfaceForm && groupTable[tree.record.y] < 0) faces[tree.record.y] |= kFrontFaces;
    }
    gpu::Buffer::uploadGrowing(blocks_, "evaluate blocks", blocks);
    gpu::Buffer::uploadGrowing(blockOperands_, "evaluate block literals", literals);
    gpu::Buffer::uploadGrowing(blockNodes_, "evaluate block nodes", nodes);
    gpu::Buffer::uploadGrowing(drawnBlocks_, "evaluate drawn blocks", drawn);
    gpu::Buffer::uploadGrowing(groupTable_, "evaluate group table", groupTable);

    layers.bindUnit(0);
    blockNodes_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    blocks_.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    blockOperands_.bindBase(GL_SHADER_STORAGE_BUFFER, 3);
    drawnBlocks_.bindBase(GL_SHADER_STORAGE_BUFFER, 4);
    groupTable_.bindBase(GL_SHADER_STORAGE_BUFFER, 6);
    if (groupIds.id() != 0) groupIds.bindUnit(3);
    if (!faces.empty()) shownFaces_.uploadSpan(std::span<const std::uint32_t>(faces));
    shownFaces_.bindBase(GL_SHADER_STORAGE_BUFFER, 5);
    if (targets.leafMarks) targets.markSlotBuffer().bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    targets.evaluateTarget.bindForDraw();
    glViewport(tile.x, tile.y, tile.width, tile.height);
    // A pixel the shader writes (does not discard) is marked for the later
    // passes: with kWritten, or with the value the shader gives (leaf marks).
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, FrameTargets::kWritten, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    empty_.bind();
    static const int loopBudget = loopBudgetForThisDriver();
    int first = 0;
    for (const auto& [form, list] : byForm) {
        switch (blockForm(form)) {
            case BlockForm::FirstSurface: stats.firstSurfaceBlocks += list.size(); break;
            case BlockForm::Product: stats.productBlocks += list.size(); break;
            case BlockForm::Register: stats.registerBlocks += list.size(); break;
            default: stats.arrayBlocks += list.size();
        }
        gpu::Program& program = programFor(form, targets.leafMarks);
        program.setUniform(kTileOrigin, glm::ivec2(tile.x, tile.y));
        if (form == kProductForm || form > kRegisterForm) program.setUniform(kLoopBudget, loopBudget);
        program.setUniform(kFirstBlock, first);
        program.setUniform(kTileSize, glm::ivec2(tile.width, tile.height));
        program.setUniform(kBlocksX, blocksX);
        program.use();
        glDrawArraysInstanced(GL_TRIANGLES, 0, 6, static_cast<GLsizei>(runs[form]));
        first += static_cast<int>(runs[form]);
    }
    glDisable(GL_STENCIL_TEST);
    gpu::checkErrors();
}

}  // namespace strata::render
