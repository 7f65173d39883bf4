#include "EvaluatePass.h"

#include <algorithm>
#include <limits>
#include <map>
#include <span>
#include <string>

#include <glm/vec4.hpp>

#include "strata/gpu/Check.h"

namespace strata::render {

namespace {

// Uniform locations in shaders/csg/evaluate.frag.
constexpr GLint kTileOrigin = 2;
constexpr GLint kBlocksX = 3;
constexpr GLint kLoopBudget = 4;

// llvmpipe stops all loops of one shader invocation after 65535 iterations in
// total (gallivm's loop limiter); stay inside that, and mark the pixels that
// would not fit (see uLoopBudget in evaluate.frag).
int loopBudgetForThisDriver() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const bool limited = renderer != nullptr && std::string(renderer).find("llvmpipe") != std::string::npos;
    // The shader's count is an estimate. Measured on intersections of 96 and
    // 128 spheres and a slab minus 128 spheres: every pixel it puts under
    // 30000 matched the CPU reference, and some near 40000 did not (it
    // undercounts the limiter about twofold).
    return limited ? 30000 : std::numeric_limits<int>::max();
}

// Uploads `data` into `buffer`, replacing it with a larger one when needed.
template <class T>
void put(gpu::Buffer& buffer, const char* label, const std::vector<T>& data) {
    const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), sizeof(T));
    if (buffer.size() < bytes) buffer = gpu::Buffer(label, bytes * 2, nullptr, GL_DYNAMIC_STORAGE_BIT);
    if (!data.empty()) buffer.uploadSpan(std::span<const T>(data));
}

}  // namespace

EvaluatePass::EvaluatePass() : empty_("evaluate") {}

int EvaluatePass::capacityFor(int count) {
    int capacity = 16;
    while (capacity < count) capacity *= 2;
    return capacity;
}

gpu::Program& EvaluatePass::programFor(int operands, int live) {
    const std::pair<int, int> key{capacityFor(operands), capacityFor(live)};
    auto it = programs_.find(key);
    if (it == programs_.end()) {
        const std::vector<gpu::ShaderDefine> defines{{"MAX_OPERANDS", std::to_string(key.first)},
                                                     {"MAX_LIVE", std::to_string(key.second)},
                                                     {"BLOCK", std::to_string(kBlock)}};
        it = programs_
                 .emplace(key, gpu::Program::fromFiles("evaluate", {"common/fullscreen.vert", "csg/evaluate.frag"},
                                                       defines))
                 .first;
    }
    return it->second;
}

void EvaluatePass::setProgram(const TreeProgram& program) {
    program_ = program;
    operandLeaf_ = program.operandLeaf;
    // Compile now rather than mid-frame: with up to kMinLive operands this is
    // the only variant a frame will use.
    if (!operandLeaf_.empty()) programFor(program.operandCount(), std::min(program.operandCount(), kMinLive));
}

void EvaluatePass::run(FrameTargets& targets, const gpu::Texture& layers, const PixelRect& tile,
                       const std::vector<OperandLayers>& operandLayers, const std::vector<PixelRect>& rects) {
    if (operandLeaf_.empty()) return;
    std::vector<glm::uvec4> table(operandLeaf_.size());
    for (std::size_t k = 0; k < table.size(); ++k) {
        table[k] = {static_cast<unsigned>(operandLayers[k].first), static_cast<unsigned>(operandLayers[k].count),
                    static_cast<unsigned>(operandLeaf_[k]), 0u};
    }
    put(table_, "operand table", table);

    // Per block: x, y the range of its operand list in `lists`; z, w the range
    // of its specialised program in `code`. Blocks with the same operands
    // share one program.
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
    std::vector<glm::uvec4> blocks(blockCount, glm::uvec4(0u));
    std::vector<std::uint32_t> lists;
    std::vector<std::uint32_t> code;
    std::map<std::vector<std::uint32_t>, glm::uvec2> programs;  // operand list -> code range
    std::vector<char> present(operandLeaf_.size(), 0);
    std::size_t longest = 0;
    for (std::size_t b = 0; b < blockCount; ++b) {
        const std::vector<std::uint32_t>& list = members[b];
        if (list.empty()) continue;
        longest = std::max(longest, list.size());
        auto it = programs.find(list);
        if (it == programs.end()) {
            for (std::uint32_t k : list) present[k] = 1;
            const std::vector<std::uint32_t> specialised = specializeProgram(program_, present);
            for (std::uint32_t k : list) present[k] = 0;
            it = programs.emplace(list, glm::uvec2(code.size(), specialised.size())).first;
            code.insert(code.end(), specialised.begin(), specialised.end());
        }
        if (it->second.y == 0) continue;  // the result is constant here: nothing to walk
        blocks[b] = {static_cast<unsigned>(lists.size()), static_cast<unsigned>(list.size()), it->second.x,
                     it->second.y};
        lists.insert(lists.end(), list.begin(), list.end());
    }
    put(blocks_, "evaluate blocks", blocks);
    put(blockOperands_, "evaluate block operands", lists);
    put(blockCode_, "evaluate block programs", code);

    const int operands = static_cast<int>(operandLeaf_.size());
    gpu::Program& program =
        programFor(operands, std::max(static_cast<int>(longest), std::min(operands, kMinLive)));
    program.setUniform(kTileOrigin, glm::ivec2(tile.x, tile.y));
    program.setUniform(kBlocksX, blocksX);
    static const int loopBudget = loopBudgetForThisDriver();
    program.setUniform(kLoopBudget, loopBudget);
    program.use();
    layers.bindUnit(0);
    blockCode_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    table_.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    blocks_.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    blockOperands_.bindBase(GL_SHADER_STORAGE_BUFFER, 3);
    targets.evaluateTarget.bindForDraw();
    glViewport(tile.x, tile.y, tile.width, tile.height);
    empty_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    gpu::checkErrors();
}

}  // namespace strata::render
