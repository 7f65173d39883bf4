#include "strata/reference/IntervalCsg.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "strata/core/Error.h"

namespace strata::reference {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

IntervalList leafIntervals(int leaf, std::span<Crossing> crossings, double mergeTolerance) {
    IntervalList list;
    leafIntervals(leaf, crossings, mergeTolerance, list);
    return list;
}

void leafIntervals(int leaf, std::span<Crossing> crossings, double mergeTolerance, IntervalList& list) {
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) {
        return x.t != y.t ? x.t < y.t : x.handle < y.handle;
    });
    list.clear();
    bool inside = crossings.size() % 2 == 1;
    if (inside) list.push_back({-kInfinity, kInfinity, Surface{}, Surface{}});
    std::size_t first = 0;
    while (first < crossings.size()) {
        std::size_t last = first + 1;
        while (last < crossings.size() && crossings[last].t - crossings[first].t <= mergeTolerance) ++last;
        if ((last - first) % 2 == 1) {
            // The change goes inward when we were outside; prefer a crossing
            // whose facing says the same (they agree on a clean mesh).
            const bool enters = !inside;
            std::size_t pick = first;
            for (std::size_t k = first; k < last; ++k) {
                if (crossings[k].entering == enters) {
                    pick = k;
                    break;
                }
            }
            const Surface surface{leaf, crossings[pick].handle, enters};
            if (enters) {
                list.push_back({crossings[pick].t, kInfinity, surface, Surface{}});
            } else {
                list.back().end = crossings[pick].t;
                list.back().endSurface = surface;
            }
            inside = enters;
        }
        first = last;
    }
    // Parity of the whole equals parity of the odd groups, so we end outside.
}

void unite(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    out.clear();
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        // Next interval by begin; on a tie the first operand's.
        const Interval& next = (j == b.size() || (i < a.size() && a[i].begin <= b[j].begin)) ? a[i++] : b[j++];
        if (out.empty() || next.begin > out.back().end) {
            out.push_back(next);
        } else if (next.end > out.back().end) {
            // Overlapping or touching: one stretch, no surface where they meet.
            out.back().end = next.end;
            out.back().endSurface = next.endSurface;
        }
    }
}

void intersect(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    out.clear();
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const Interval& x = a[i];
        const Interval& y = b[j];
        const bool xBegins = x.begin >= y.begin;
        const bool xEnds = x.end <= y.end;
        const double begin = xBegins ? x.begin : y.begin;
        const double end = xEnds ? x.end : y.end;
        if (begin < end) {
            out.push_back({begin, end, xBegins ? x.beginSurface : y.beginSurface, xEnds ? x.endSurface : y.endSurface});
        }
        if (x.end < y.end) {
            ++i;
        } else if (y.end < x.end) {
            ++j;
        } else {
            ++i;
            ++j;
        }
    }
}

void subtract(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    out.clear();
    std::size_t j = 0;
    for (const Interval& x : a) {
        // Subtrahends that end before x begins (touching included) cannot cut it.
        while (j < b.size() && b[j].end <= x.begin) ++j;
        double begin = x.begin;
        Surface beginSurface = x.beginSurface;
        bool covered = false;
        for (std::size_t k = j; k < b.size() && b[k].begin < x.end; ++k) {
            if (b[k].begin > begin) out.push_back({begin, b[k].begin, beginSurface, b[k].beginSurface});
            if (b[k].end >= x.end) {
                covered = true;
                break;
            }
            begin = b[k].end;
            beginSurface = b[k].endSurface;
        }
        if (!covered && begin < x.end) out.push_back({begin, x.end, beginSurface, x.endSurface});
    }
}

IntervalList unite(const IntervalList& a, const IntervalList& b) {
    IntervalList out;
    unite(a, b, out);
    return out;
}

IntervalList intersect(const IntervalList& a, const IntervalList& b) {
    IntervalList out;
    intersect(a, b, out);
    return out;
}

IntervalList subtract(const IntervalList& a, const IntervalList& b) {
    IntervalList out;
    subtract(a, b, out);
    return out;
}

std::optional<FirstChange> firstChange(const IntervalList& list) {
    if (list.empty()) return std::nullopt;
    const Interval& first = list.front();
    if (first.begin != -kInfinity) return FirstChange{first.begin, first.beginSurface, true};
    if (first.end != kInfinity) return FirstChange{first.end, first.endSurface, false};
    return std::nullopt;  // inside all along: no change to see
}

CsgProgram::CsgProgram(const scene::Tree& tree) : leafCount_(tree.leaves.size()) {
    const auto nodeCount = static_cast<int>(tree.nodes.size());
    std::vector<bool> onPath(tree.nodes.size(), false);
    std::vector<bool> used(tree.leaves.size(), false);
    std::size_t depth = 0;
    auto emit = [&](Instruction instruction) {
        code_.push_back(instruction);
        if (instruction.op == Op::Leaf || instruction.op == Op::Empty) {
            maxStack_ = std::max(maxStack_, ++depth);
        } else {
            depth -= static_cast<std::size_t>(instruction.operand) - 1;
        }
    };
    auto malformed = [&](int node, const std::string& what) {
        const SourceLocation& where = tree.nodes[static_cast<std::size_t>(node)].where;
        if (where.line > 0) throw Error(where, "malformed CSG tree: " + what);
        throw Error("malformed CSG tree: node " + std::to_string(node) + ": " + what);
    };

    if (tree.root < 0) {
        emit({Op::Empty, 0});
        return;
    }
    if (tree.root >= nodeCount) throw Error("malformed CSG tree: root " + std::to_string(tree.root) + " out of range");

    // Depth-first, children in order, with an explicit stack: trees may be deep.
    struct Frame {
        int node;
        std::size_t next;
    };
    std::vector<Frame> path{{tree.root, 0}};
    onPath[static_cast<std::size_t>(tree.root)] = true;
    while (!path.empty()) {
        Frame& frame = path.back();
        const scene::Node& node = tree.nodes[static_cast<std::size_t>(frame.node)];
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf < 0 || node.leaf >= static_cast<int>(tree.leaves.size())) {
                malformed(frame.node, "leaf index " + std::to_string(node.leaf) + " out of range");
            }
            if (tree.leaves[static_cast<std::size_t>(node.leaf)].display == scene::Display::Background) {
                emit({Op::Empty, 0});
            } else {
                emit({Op::Leaf, node.leaf});
                used[static_cast<std::size_t>(node.leaf)] = true;
            }
        } else if (frame.next < node.children.size()) {
            const int child = node.children[frame.next++];
            if (child < 0 || child >= nodeCount) {
                malformed(frame.node, "child index " + std::to_string(child) + " out of range");
            }
            if (onPath[static_cast<std::size_t>(child)]) malformed(frame.node, "cycle through node " + std::to_string(child));
            onPath[static_cast<std::size_t>(child)] = true;
            path.push_back({child, 0});
            continue;
        } else {
            const auto k = static_cast<int>(node.children.size());
            if (k == 0) {
                emit({Op::Empty, 0});
            } else if (k >= 2) {
                const Op op = node.kind == scene::NodeKind::Union          ? Op::Union
                              : node.kind == scene::NodeKind::Intersection ? Op::Intersection
                                                                           : Op::Difference;
                emit({op, k});
            }
        }
        onPath[static_cast<std::size_t>(frame.node)] = false;
        path.pop_back();
    }
    for (std::size_t i = 0; i < used.size(); ++i) {
        if (used[i]) leaves_.push_back(static_cast<int>(i));
    }
}

const IntervalList& CsgProgram::evaluate(std::span<const IntervalList> leafLists, Workspace& workspace) const {
    std::vector<IntervalList>& stack = workspace.stack;
    if (stack.size() < maxStack_) stack.resize(maxStack_);
    std::size_t top = 0;  // number of lists on the stack
    for (const Instruction& instruction : code_) {
        switch (instruction.op) {
            case Op::Leaf: {
                const IntervalList& list = leafLists[static_cast<std::size_t>(instruction.operand)];
                stack[top++].assign(list.begin(), list.end());
                break;
            }
            case Op::Empty:
                stack[top++].clear();
                break;
            case Op::Union:
            case Op::Intersection:
            case Op::Difference: {
                const std::size_t base = top - static_cast<std::size_t>(instruction.operand);
                // Most leaves miss most rays: empty operands take the short way.
                for (std::size_t k = base + 1; k < top; ++k) {
                    IntervalList& result = stack[base];
                    IntervalList& operand = stack[k];
                    if (instruction.op == Op::Union) {
                        if (operand.empty()) continue;
                        if (result.empty()) {
                            std::swap(result, operand);
                            continue;
                        }
                        unite(result, operand, workspace.scratch);
                    } else {
                        if (result.empty()) break;
                        if (operand.empty()) {
                            if (instruction.op == Op::Intersection) result.clear();
                            continue;
                        }
                        if (instruction.op == Op::Intersection) {
                            intersect(result, operand, workspace.scratch);
                        } else {
                            subtract(result, operand, workspace.scratch);
                        }
                    }
                    std::swap(result, workspace.scratch);
                }
                top = base + 1;
                break;
            }
        }
    }
    return stack[0];
}

bool CsgProgram::contains(std::span<const char> inside, std::vector<char>& stack) const {
    stack.clear();
    for (const Instruction& instruction : code_) {
        switch (instruction.op) {
            case Op::Leaf: stack.push_back(inside[static_cast<std::size_t>(instruction.operand)]); break;
            case Op::Empty: stack.push_back(0); break;
            case Op::Union:
            case Op::Intersection:
            case Op::Difference: {
                const std::size_t base = stack.size() - static_cast<std::size_t>(instruction.operand);
                char value = stack[base];
                for (std::size_t k = base + 1; k < stack.size(); ++k) {
                    if (instruction.op == Op::Union) value = value || stack[k];
                    else if (instruction.op == Op::Intersection) value = value && stack[k];
                    else value = value && !stack[k];
                }
                stack.resize(base + 1);
                stack[base] = value;
                break;
            }
        }
    }
    return !stack.empty() && stack.back() != 0;
}

}  // namespace strata::reference
