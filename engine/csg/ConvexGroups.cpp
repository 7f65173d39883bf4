#include "strata/csg/ConvexGroups.h"

#include <algorithm>
#include <map>
#include <span>

namespace strata::csg {

namespace {

// Whether the instruction reads an operand (a literal): every PUSH, as
// foldCode reads them, and an AND or OR not taking its value from the stack.
bool isLiteral(std::uint32_t instruction) {
    return (instruction & kOpMask) == kOpPush || !(instruction & kOpFromStack);
}

// The literals a group joins: an AND's plain literals and an OR's negated
// ones for an intersection; an OR's plain literals for a union.
enum class Join { Intersection, Union };

CompiledTree joinLiterals(const CompiledTree& compiled, const std::vector<char>& groupable, std::size_t mostMembers,
                          std::size_t leastMembers, Join join) {
    if (compiled.kind != CompiledTree::Kind::Code || mostMembers < 2) return compiled;
    const std::vector<std::uint32_t>& code = compiled.code;
    // Literal instructions in code order: countingTree's literals are the same, one for one.
    std::vector<std::size_t> literalAt;
    std::vector<int> uses(compiled.operandLeaf.size(), 0);
    for (std::size_t i = 0; i < code.size(); ++i) {
        if (!isLiteral(code[i])) continue;
        literalAt.push_back(i);
        ++uses[code[i] >> kOperandShift];
    }
    const CountingTree tree = countingTree(code);

    // Candidates per node, in code order: for an intersection an AND's plain
    // literals and an OR's negated ones (!a | !b is !(a & b)); for a union
    // an OR's plain literals. Operands that are groups already stay as they are.
    std::map<std::uint32_t, std::vector<std::size_t>> byNode;  // node -> literal indices
    for (std::size_t l = 0; l < tree.literals.size(); ++l) {
        const CountingTree::Literal& literal = tree.literals[l];
        const bool inAnd = tree.nodes[literal.parent].isAnd;
        if (join == Join::Intersection ? literal.negated == inAnd : inAnd || literal.negated) continue;
        if (literal.operand >= groupable.size() || !groupable[literal.operand] || uses[literal.operand] != 1) continue;
        if (compiled.leavesOf(literal.operand).size() > 1) continue;
        byNode[literal.parent].push_back(l);
    }

    // Each operand's new members (empty: dropped into a group); a group
    // keeps its first literal's instruction and deletes the others, all of
    // them AND (OR) with a literal (a node's only PUSH is its first
    // literal), which leave the stack as it was.
    const std::size_t n = compiled.operandLeaf.size();
    std::vector<std::vector<int>> members(n);
    std::vector<char> unite(n, 0);  // a union group
    for (std::size_t k = 0; k < n; ++k) {
        const std::span<const int> leaves = compiled.leavesOf(k);
        members[k].assign(leaves.begin(), leaves.end());
        unite[k] = compiled.isUnionGroup(k) ? 1 : 0;
    }
    std::vector<char> deleted(code.size(), 0);
    bool any = false;
    for (const auto& [node, literals] : byNode) {
        if (literals.size() < leastMembers) continue;
        for (std::size_t start = 0; start + 1 < literals.size(); start += mostMembers) {
            const std::size_t end = std::min(literals.size(), start + mostMembers);
            const std::uint32_t keeper = tree.literals[literals[start]].operand;
            for (std::size_t i = start + 1; i < end; ++i) {
                const std::uint32_t operand = tree.literals[literals[i]].operand;
                members[keeper].push_back(compiled.operandLeaf[operand]);
                members[operand].clear();
                deleted[literalAt[literals[i]]] = 1;
            }
            std::sort(members[keeper].begin(), members[keeper].end());
            unite[keeper] = join == Join::Union ? 1 : 0;
            any = true;
        }
    }
    if (!any) return compiled;

    // Renumber: the operands left, by their lowest leaf.
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < n; ++k) {
        if (!members[k].empty()) kept.push_back(k);
    }
    std::sort(kept.begin(), kept.end(), [&](std::size_t a, std::size_t b) { return members[a][0] < members[b][0]; });
    std::vector<std::uint32_t> renumbered(n, 0);
    CompiledTree out;
    out.kind = compiled.kind;
    out.stackDepth = compiled.stackDepth;
    out.operandGroups.resize(kept.size());
    const bool anyUnion = std::any_of(kept.begin(), kept.end(), [&](std::size_t k) { return unite[k] != 0; });
    if (anyUnion) out.unionGroups.assign(kept.size(), 0);
    for (std::size_t j = 0; j < kept.size(); ++j) {
        renumbered[kept[j]] = static_cast<std::uint32_t>(j);
        out.operandLeaf.push_back(members[kept[j]][0]);
        if (members[kept[j]].size() > 1) out.operandGroups[j] = std::move(members[kept[j]]);
        if (anyUnion) out.unionGroups[j] = unite[kept[j]];
    }
    for (std::size_t i = 0; i < code.size(); ++i) {
        if (deleted[i]) continue;
        const std::uint32_t instruction = code[i];
        out.code.push_back(isLiteral(instruction) ? (instruction & ((1u << kOperandShift) - 1u)) |
                                                        (renumbered[instruction >> kOperandShift] << kOperandShift)
                                                  : instruction);
    }
    return out;
}

}  // namespace

CompiledTree groupConvexProducts(const CompiledTree& compiled, const std::vector<char>& groupable,
                                 std::size_t mostMembers, std::size_t leastMembers) {
    return joinLiterals(compiled, groupable, mostMembers, leastMembers, Join::Intersection);
}

CompiledTree groupUnionOperands(const CompiledTree& compiled, const std::vector<char>& groupable,
                                std::size_t mostMembers) {
    return joinLiterals(compiled, groupable, mostMembers, 2, Join::Union);
}

}  // namespace strata::csg
