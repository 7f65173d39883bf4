#include "strata/csg/CompiledTree.h"

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <utility>

#include "strata/core/Error.h"

namespace strata::csg {

namespace {

// The normalized tree: n-ary AND/OR over literals, or a constant.
struct Expr {
    enum class Type { Literal, And, Or, Empty, Everything };
    Type type = Type::Empty;
    int leaf = -1;          // Literal: the tree leaf
    bool negated = false;   // Literal: complemented
    std::vector<int> children;
    int need = 1;           // Sethi–Ullman stack need, once computed
};

class Compiler {
public:
    Compiler(const scene::Tree& tree, const std::vector<bool>& leafIsEmpty, const std::vector<int>& sameLeaf)
        : tree_(tree), leafIsEmpty_(leafIsEmpty), sameLeaf_(sameLeaf) {
        exprs_.push_back(make(Expr::Type::Empty));       // kEmpty
        exprs_.push_back(make(Expr::Type::Everything));  // kEverything
    }

    CompiledTree compile() {
        CompiledTree compiled;
        if (tree_.root < 0) return compiled;  // nothing at all: empty
        const int root = propagateLiterals(flattenSameType(normalize(tree_.root)));
        if (root == kEmpty) return compiled;
        if (root == kEverything) {
            compiled.kind = CompiledTree::Kind::Everything;
            return compiled;
        }
        compiled.kind = CompiledTree::Kind::Code;
        assignOperands(root, compiled);
        computeNeeds(root);
        emit(root, compiled);
        return compiled;
    }

private:
    static constexpr int kEmpty = 0;

    static Expr make(Expr::Type type) {
        Expr e;
        e.type = type;
        return e;
    }
    static constexpr int kEverything = 1;

    // --- 1 and 2: difference to intersection, De Morgan, constant folding ---

    // Memo per (node, negated): -1 not seen, -2 in progress (a cycle if met again).
    int& memo(int node, bool negated) { return memo_[static_cast<std::size_t>(node) * 2 + (negated ? 1 : 0)]; }

    int normalize(int rootNode) {
        memo_.assign(tree_.nodes.size() * 2, -1);
        struct Frame {
            int node;
            bool negated;
            bool expanded;
        };
        std::vector<Frame> stack{{rootNode, false, false}};
        checkNode(rootNode);
        while (!stack.empty()) {
            Frame& frame = stack.back();
            const scene::Node& node = tree_.nodes[static_cast<std::size_t>(frame.node)];
            int& slot = memo(frame.node, frame.negated);
            if (!frame.expanded) {
                if (slot >= 0) {  // shared subtree, already normalized
                    stack.pop_back();
                    continue;
                }
                if (slot == -2) throw Error(node.where, "the CSG tree has a cycle through this node");
                slot = -2;
                frame.expanded = true;
                const Frame parent = frame;  // `frame` dangles once we push
                for (std::size_t i = node.children.size(); i-- > 0;) {
                    const int child = node.children[i];
                    checkNode(child);
                    const bool childNegated = node.kind == scene::NodeKind::Difference && i > 0
                                                  ? !parent.negated
                                                  : parent.negated;
                    const int childSlot = memo(child, childNegated);
                    if (childSlot == -2) {
                        throw Error(tree_.nodes[static_cast<std::size_t>(child)].where,
                                    "the CSG tree has a cycle through this node");
                    }
                    if (childSlot < 0) stack.push_back({child, childNegated, false});
                }
                continue;
            }
            slot = combine(node, frame.negated);
            stack.pop_back();
        }
        return memo(rootNode, false);
    }

    void checkNode(int node) const {
        if (node < 0 || static_cast<std::size_t>(node) >= tree_.nodes.size()) {
            throw Error("CSG tree: node index " + std::to_string(node) + " out of range");
        }
    }

    // All children of `node` are normalized; fold them into one expression.
    int combine(const scene::Node& node, bool negated) {
        if (node.kind == scene::NodeKind::Leaf) {
            if (node.leaf < 0 || static_cast<std::size_t>(node.leaf) >= tree_.leaves.size()) {
                throw Error(node.where, "CSG tree: leaf index " + std::to_string(node.leaf) + " out of range");
            }
            const auto leaf = static_cast<std::size_t>(node.leaf);
            const bool empty = tree_.leaves[leaf].display == scene::Display::Background ||
                               (leaf < leafIsEmpty_.size() && leafIsEmpty_[leaf]);
            if (empty) return negated ? kEverything : kEmpty;
            Expr literal = make(Expr::Type::Literal);
            literal.leaf = node.leaf;
            if (leaf < sameLeaf_.size()) {
                const int same = sameLeaf_[leaf];
                if (same < 0 || static_cast<std::size_t>(same) >= tree_.leaves.size()) {
                    throw Error("CSG tree: leaf " + std::to_string(node.leaf) + " is said to equal leaf " +
                                std::to_string(same) + ", which is out of range");
                }
                literal.leaf = same;
            }
            literal.negated = negated;
            exprs_.push_back(literal);
            return static_cast<int>(exprs_.size()) - 1;
        }
        // A node with no children is empty, whatever its kind (OpenSCAD's
        // union(){}, intersection(){}, difference(){}).
        if (node.children.empty()) return negated ? kEverything : kEmpty;

        // Union is OR, Intersection and Difference are AND; complementing swaps them.
        const bool isOr = (node.kind == scene::NodeKind::Union) != negated;
        const Expr::Type type = isOr ? Expr::Type::Or : Expr::Type::And;
        const int absorbing = isOr ? kEverything : kEmpty;  // x OR all = all, x AND empty = empty
        const int neutral = isOr ? kEmpty : kEverything;

        std::vector<int> children;
        for (std::size_t i = 0; i < node.children.size(); ++i) {
            const bool childNegated =
                node.kind == scene::NodeKind::Difference && i > 0 ? !negated : negated;
            const int child = memo(node.children[i], childNegated);
            if (child == absorbing) return absorbing;
            if (child == neutral) continue;
            children.push_back(child);  // an AND in an AND is spliced later, once (flattenSameType)
        }
        if (children.empty()) return neutral;
        if (children.size() == 1) return children.front();
        Expr combined = make(type);
        combined.children = std::move(children);
        exprs_.push_back(std::move(combined));
        return static_cast<int>(exprs_.size()) - 1;
    }

    // AND(AND(a, b), c) = AND(a, b, c), and likewise for OR: each AND/OR that
    // starts a run of its own type (the root, or under the other type, or
    // with two parents) takes the children of the whole run, in order, in one
    // walk. A chain of n nested differences is then one AND of n + 1
    // children, made in O(n), not one list per level.
    int flattenSameType(int root) {
        if (root == kEmpty || root == kEverything || isLiteral(root)) return root;
        std::vector<int> parents(exprs_.size(), 0);
        postorder(root, [&](int e) {
            for (int c : exprs_[static_cast<std::size_t>(e)].children) ++parents[static_cast<std::size_t>(c)];
        });
        std::vector<char> done(exprs_.size(), 0);
        std::vector<int> starts{root};
        std::vector<int> members;
        while (!starts.empty()) {
            const int start = starts.back();
            starts.pop_back();
            if (done[static_cast<std::size_t>(start)] || isLiteral(start)) continue;
            done[static_cast<std::size_t>(start)] = 1;
            const Expr::Type type = exprs_[static_cast<std::size_t>(start)].type;
            std::vector<int> flat;
            members.clear();
            std::vector<std::pair<int, std::size_t>> walk{{start, 0}};
            while (!walk.empty()) {
                const auto [e, next] = walk.back();
                const std::vector<int>& children = exprs_[static_cast<std::size_t>(e)].children;
                if (next == children.size()) {
                    walk.pop_back();
                    continue;
                }
                walk.back().second = next + 1;
                const int c = children[next];
                const Expr& child = exprs_[static_cast<std::size_t>(c)];
                if (child.type == type && parents[static_cast<std::size_t>(c)] == 1) {
                    members.push_back(c);  // part of the run: its children join `flat`
                    walk.push_back({c, 0});
                } else {
                    flat.push_back(c);
                    starts.push_back(c);
                }
            }
            for (int m : members) std::vector<int>().swap(exprs_[static_cast<std::size_t>(m)].children);
            if (!members.empty()) exprs_[static_cast<std::size_t>(start)].children = std::move(flat);
        }
        return root;
    }

    // --- 2b: an AND's literals are true, an OR's false, inside its other children ---

    // AND(x, F) = AND(x, F with x true): where x is false both are false. Likewise
    // OR(x, F) = OR(x, F with x false). So a literal that an ancestor holds is
    // a constant below it, and folds away there: a chain intersected with one
    // solid at every level (identical leaves share a leaf) keeps only the
    // outermost intersection. Rebuilds the expression without recursing;
    // left as it is where an inner expression is shared (a rebuild per place
    // could grow without bound).
    int propagateLiterals(int root) {
        if (root == kEmpty || root == kEverything || isLiteral(root) || innerExpressionShared(root)) return root;
        Held held;
        held.known.assign(tree_.leaves.size(), -1);
        std::vector<Rebuild> stack;
        stack.push_back(Rebuild{root, 0, 0, {}, false});
        int result = -1;
        while (!stack.empty()) {
            Rebuild& f = stack.back();
            const Expr& x = exprs_[static_cast<std::size_t>(f.e)];
            if (result >= 0) {  // a child just rebuilt
                keepChild(f, result);
                result = -1;
            }
            if (f.next == 0 && f.kept.empty() && !f.absorbed) holdLiterals(f, held);
            // Then the other children, under what the literals hold.
            while (!f.absorbed && f.next < x.children.size() && isLiteral(x.children[f.next])) ++f.next;
            if (!f.absorbed && f.next < x.children.size()) {
                const int child = x.children[f.next++];
                stack.push_back(Rebuild{child, 0, held.forced.size(), {}, false});
                continue;
            }
            result = rebuilt(f, held);
            stack.pop_back();
        }
        return result;
    }

    // The literals' values that the AND/OR expressions being rebuilt hold.
    struct Held {
        std::vector<signed char> known;  // per leaf: -1 free, else inside (1) or not
        std::vector<int> forced;         // leaves set in `known`, in order
    };
    // An expression being rebuilt by propagateLiterals.
    struct Rebuild {
        int e;
        std::size_t next = 0;        // children of e visited
        std::size_t forcedMark = 0;  // Held::forced.size() on entry
        std::vector<int> kept;       // e's rebuilt children
        bool absorbed = false;       // a child was e's absorbing constant
    };

    static int absorbingOf(Expr::Type type) { return type == Expr::Type::And ? kEmpty : kEverything; }
    static int neutralOf(Expr::Type type) { return type == Expr::Type::And ? kEverything : kEmpty; }

    // Adds a rebuilt `child` to f's children: a constant absorbs f or
    // vanishes, a child of f's own operation merges into f.
    void keepChild(Rebuild& f, int child) const {
        const Expr::Type type = exprs_[static_cast<std::size_t>(f.e)].type;
        if (child == absorbingOf(type)) {
            f.absorbed = true;
        } else if (child != neutralOf(type)) {
            const Expr& c = exprs_[static_cast<std::size_t>(child)];
            if (c.type == type) {
                f.kept.insert(f.kept.end(), c.children.begin(), c.children.end());
            } else {
                f.kept.push_back(child);
            }
        }
    }

    // f's literal children, first: constants where `held` knows them, else
    // they hold their value for the rest (a repeat is then a constant).
    void holdLiterals(Rebuild& f, Held& held) const {
        const Expr& x = exprs_[static_cast<std::size_t>(f.e)];
        const bool isAnd = x.type == Expr::Type::And;
        for (int c : x.children) {
            if (!isLiteral(c)) continue;
            const Expr& l = exprs_[static_cast<std::size_t>(c)];
            const int k = held.known[static_cast<std::size_t>(l.leaf)];
            if (k >= 0) {
                const int value = l.negated ? 1 - k : k;
                keepChild(f, value == 1 ? kEverything : kEmpty);
                continue;
            }
            const bool holds = isAnd;  // the literal's value wherever the others matter
            held.known[static_cast<std::size_t>(l.leaf)] = static_cast<signed char>(holds != l.negated ? 1 : 0);
            held.forced.push_back(l.leaf);
            f.kept.push_back(c);
        }
    }

    // f, every child visited: its rebuilt expression. Its literals hold no
    // more.
    int rebuilt(Rebuild& f, Held& held) {
        const Expr::Type type = exprs_[static_cast<std::size_t>(f.e)].type;
        int out;
        if (f.absorbed) {
            out = absorbingOf(type);
        } else if (f.kept.empty()) {
            out = neutralOf(type);
        } else if (f.kept.size() == 1) {
            out = f.kept.front();
        } else {
            Expr e = make(type);
            e.children = std::move(f.kept);
            exprs_.push_back(std::move(e));
            out = static_cast<int>(exprs_.size()) - 1;
        }
        for (std::size_t i = f.forcedMark; i < held.forced.size(); ++i)
            held.known[static_cast<std::size_t>(held.forced[i])] = -1;
        held.forced.resize(f.forcedMark);
        return out;
    }

    // Whether some AND/OR expression under `root` has two parents.
    bool innerExpressionShared(int root) const {
        std::vector<char> seen(exprs_.size(), 0);
        std::vector<int> stack{root};
        seen[static_cast<std::size_t>(root)] = 1;
        while (!stack.empty()) {
            const int e = stack.back();
            stack.pop_back();
            for (int c : exprs_[static_cast<std::size_t>(e)].children) {
                if (isLiteral(c)) continue;
                if (seen[static_cast<std::size_t>(c)]) return true;
                seen[static_cast<std::size_t>(c)] = 1;
                stack.push_back(c);
            }
        }
        return false;
    }

    // Visits every expression reachable from `root` once, children before parents.
    template <class F>
    void postorder(int root, F&& visit) {
        std::vector<char> done(exprs_.size(), 0);
        std::vector<std::pair<int, bool>> stack{{root, false}};
        while (!stack.empty()) {
            auto [e, expanded] = stack.back();
            stack.pop_back();
            if (done[static_cast<std::size_t>(e)]) continue;
            if (expanded) {
                done[static_cast<std::size_t>(e)] = 1;
                visit(e);
                continue;
            }
            stack.push_back({e, true});
            for (int child : exprs_[static_cast<std::size_t>(e)].children) {
                if (!done[static_cast<std::size_t>(child)]) stack.push_back({child, false});
            }
        }
    }

    void assignOperands(int root, CompiledTree& compiled) {
        std::vector<int> leaves;
        postorder(root, [&](int e) {
            const Expr& x = exprs_[static_cast<std::size_t>(e)];
            if (x.type == Expr::Type::Literal) leaves.push_back(x.leaf);
        });
        std::sort(leaves.begin(), leaves.end());
        leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
        compiled.operandLeaf = leaves;
        operandOfLeaf_.assign(tree_.leaves.size(), -1);
        for (std::size_t k = 0; k < leaves.size(); ++k) {
            operandOfLeaf_[static_cast<std::size_t>(leaves[k])] = static_cast<int>(k);
        }
    }

    // --- 3: Sethi–Ullman ordering ---

    bool isLiteral(int e) const { return exprs_[static_cast<std::size_t>(e)].type == Expr::Type::Literal; }
    int need(int e) const { return exprs_[static_cast<std::size_t>(e)].need; }

    void computeNeeds(int root) {
        postorder(root, [&](int e) {
            Expr& x = exprs_[static_cast<std::size_t>(e)];
            if (x.type == Expr::Type::Literal) {
                x.need = 1;
                return;
            }
            // Subexpressions first, deepest need first (stable, so equal needs
            // keep their input order), then the literals, fused.
            std::stable_partition(x.children.begin(), x.children.end(),
                                  [&](int c) { return !isLiteral(c); });
            const auto firstLiteral = std::find_if(x.children.begin(), x.children.end(),
                                                   [&](int c) { return isLiteral(c); });
            std::stable_sort(x.children.begin(), firstLiteral,
                             [&](int a, int b) { return need(a) > need(b); });
            int n = 1;
            for (auto it = x.children.begin(); it != firstLiteral; ++it) {
                n = std::max(n, need(*it) + (it == x.children.begin() ? 0 : 1));
            }
            x.need = n;
        });
    }

    std::uint32_t literal(std::uint32_t op, int e) const {
        const Expr& x = exprs_[static_cast<std::size_t>(e)];
        const auto operand = static_cast<std::uint32_t>(operandOfLeaf_[static_cast<std::size_t>(x.leaf)]);
        return op | (x.negated ? kOpNegate : 0u) | (operand << kOperandShift);
    }

    void emit(int root, CompiledTree& compiled) {
        int depth = 0;
        auto put = [&](std::uint32_t instruction) {
            compiled.code.push_back(instruction);
            if ((instruction & kOpMask) == kOpPush) ++depth;
            if (instruction & kOpFromStack) --depth;
            compiled.stackDepth = std::max(compiled.stackDepth, depth);
        };
        // Frame: an expression and how many of its subexpression children are emitted.
        std::vector<std::pair<int, std::size_t>> stack{{root, 0}};
        while (!stack.empty()) {
            auto& [e, next] = stack.back();
            const Expr& x = exprs_[static_cast<std::size_t>(e)];
            if (x.type == Expr::Type::Literal) {
                put(literal(kOpPush, e));
                stack.pop_back();
                continue;
            }
            const std::uint32_t op = x.type == Expr::Type::And ? kOpAnd : kOpOr;
            const auto subexpressions = static_cast<std::size_t>(
                std::find_if(x.children.begin(), x.children.end(), [&](int c) { return isLiteral(c); }) -
                x.children.begin());
            if (next >= 2) put(op | kOpFromStack);  // combine the child just emitted
            if (next < subexpressions) {
                const int child = x.children[next];
                ++next;
                stack.push_back({child, 0});
                continue;
            }
            std::size_t i = subexpressions;
            if (subexpressions == 0) put(literal(kOpPush, x.children[i++]));
            for (; i < x.children.size(); ++i) put(literal(op, x.children[i]));
            stack.pop_back();
        }
        if (compiled.stackDepth > kMaxStackDepth) {
            throw Error("CSG tree needs an evaluation stack of " + std::to_string(compiled.stackDepth) +
                        " entries; the evaluator holds " + std::to_string(kMaxStackDepth));
        }
    }

    const scene::Tree& tree_;
    const std::vector<bool>& leafIsEmpty_;
    const std::vector<int>& sameLeaf_;
    std::vector<Expr> exprs_;
    std::vector<int> memo_;
    std::vector<int> operandOfLeaf_;
};

}  // namespace

CompiledTree compileTree(const scene::Tree& tree, const std::vector<bool>& leafIsEmpty,
                         const std::vector<int>& sameLeaf) {
    return Compiler(tree, leafIsEmpty, sameLeaf).compile();
}

std::vector<std::uint32_t> specializeCode(const CompiledTree& compiled, const std::vector<char>& present,
                                          bool* constant) {
    if (compiled.kind != CompiledTree::Kind::Code) {
        if (constant) *constant = compiled.kind == CompiledTree::Kind::Everything;
        return {};
    }
    // Symbolic run of the stack machine: each entry is a constant or the
    // instructions that compute it. Folding keeps the order of evaluation, so
    // the stack never gets deeper than the code's.
    struct Entry {
        int constant = -1;  // 0 or 1, or -1 for `code`
        std::vector<std::uint32_t> code;
    };
    auto literal = [&](std::uint32_t instruction) {
        Entry e;
        const std::uint32_t operand = instruction >> kOperandShift;
        if (operand < present.size() && present[operand]) {
            e.code.push_back((instruction & ~kOpMask) | kOpPush);
        } else {
            e.constant = (instruction & kOpNegate) ? 1 : 0;  // absent: outside, so !x is true
        }
        return e;
    };
    auto combine = [](std::uint32_t op, Entry& a, Entry b) {
        // AND: 0 absorbs, 1 is neutral; OR: the other way round.
        const int absorbing = op == kOpAnd ? 0 : 1;
        if (a.constant == absorbing) return;
        if (b.constant == absorbing) {
            a = Entry{absorbing, {}};
            return;
        }
        if (b.constant >= 0) return;  // b is the neutral constant
        if (a.constant >= 0) {        // a is the neutral constant
            a = std::move(b);
            return;
        }
        // Both computed: a single-literal b fuses back into AND/OR literal.
        if (b.code.size() == 1) {
            a.code.push_back((b.code[0] & ~kOpMask) | op);
        } else {
            a.code.insert(a.code.end(), b.code.begin(), b.code.end());
            a.code.push_back(op | kOpFromStack);
        }
    };
    Entry result = foldCode<Entry>(compiled.code, literal, combine);
    if (constant) *constant = result.constant == 1;
    return result.constant >= 0 ? std::vector<std::uint32_t>{} : std::move(result.code);
}

CountingTree countingTree(const std::vector<std::uint32_t>& code) {
    // Symbolic run of the stack machine where each entry names a literal or a
    // node; nodes are numbered as made, then renumbered root first.
    struct Entry {
        bool node = false;
        std::uint32_t index = 0;
    };
    CountingTree out;
    std::vector<CountingTree::Node> made;
    auto literal = [&](std::uint32_t instruction) {
        out.literals.push_back({instruction >> kOperandShift, 0, (instruction & kOpNegate) != 0});
        return Entry{false, static_cast<std::uint32_t>(out.literals.size() - 1)};
    };
    auto adopt = [&](std::uint32_t parent, const Entry& child) {
        if (child.node) {
            made[child.index].parent = parent;
        } else {
            out.literals[child.index].parent = parent;
        }
        ++made[parent].children;
    };
    auto combine = [&](std::uint32_t op, Entry& top, Entry source) {
        const bool isAnd = op == kOpAnd;
        if (top.node && made[top.index].isAnd == isAnd) {
            adopt(top.index, source);  // (a AND b) AND c is one AND of three
            return;
        }
        made.push_back({CountingTree::kNoParent, isAnd, 0, 0});
        const auto node = static_cast<std::uint32_t>(made.size() - 1);
        adopt(node, top);
        adopt(node, source);
        top = Entry{true, node};
    };
    if (code.empty()) throw Error("countingTree: no instructions");
    const Entry top = foldCode<Entry>(code, literal, combine);
    if (!top.node) {
        made.push_back({CountingTree::kNoParent, false, 0, 0});
        adopt(static_cast<std::uint32_t>(made.size() - 1), top);
    }

    // Breadth first from the root: every parent before its children.
    const auto count = made.size();
    std::vector<std::vector<std::uint32_t>> childNodes(count);
    std::uint32_t root = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
        if (made[i].parent == CountingTree::kNoParent) {
            root = i;
        } else {
            childNodes[made[i].parent].push_back(i);
        }
    }
    std::vector<std::uint32_t> order{root};
    for (std::size_t k = 0; k < order.size(); ++k) {
        for (std::uint32_t c : childNodes[order[k]]) order.push_back(c);
    }
    std::vector<std::uint32_t> renumbered(count);
    for (std::uint32_t k = 0; k < count; ++k) renumbered[order[k]] = k;
    out.nodes.resize(count);
    for (std::uint32_t k = 0; k < count; ++k) {
        out.nodes[k] = made[order[k]];
        if (out.nodes[k].parent != CountingTree::kNoParent) out.nodes[k].parent = renumbered[out.nodes[k].parent];
    }
    for (CountingTree::Literal& l : out.literals) l.parent = renumbered[l.parent];

    // Values with every operand outside, children before parents.
    for (const CountingTree::Literal& l : out.literals) out.nodes[l.parent].trueWhenOutside += l.negated ? 1u : 0u;
    for (std::size_t k = count; k-- > 0;) {
        const CountingTree::Node& n = out.nodes[k];
        const bool value = n.isAnd ? n.trueWhenOutside == n.children : n.trueWhenOutside > 0;
        if (value && n.parent != CountingTree::kNoParent) ++out.nodes[n.parent].trueWhenOutside;
    }
    return out;
}

bool runCountingTree(const CountingTree& tree, const std::vector<bool>& operandInside) {
    std::vector<std::uint32_t> trueChildren(tree.nodes.size(), 0);
    for (const CountingTree::Literal& l : tree.literals) {
        if (operandInside.at(l.operand) != l.negated) ++trueChildren[l.parent];
    }
    // Children come after their parents: settle nodes from the last one up.
    bool value = false;
    for (std::size_t i = tree.nodes.size(); i-- > 0;) {
        const CountingTree::Node& n = tree.nodes[i];
        value = n.isAnd ? trueChildren[i] == n.children : trueChildren[i] > 0;
        if (value && n.parent != CountingTree::kNoParent) ++trueChildren[n.parent];
    }
    return value;
}

bool runCode(const std::vector<std::uint32_t>& code, const std::vector<bool>& operandInside) {
    // A stack of bits, top of stack in bit 0.
    std::uint32_t stack = 0;
    for (std::uint32_t instruction : code) {
        std::uint32_t value;
        if (instruction & kOpFromStack) {
            value = stack & 1u;
            stack >>= 1;
        } else {
            const std::uint32_t operand = instruction >> kOperandShift;
            value = (operandInside.at(operand) ? 1u : 0u) ^ ((instruction & kOpNegate) ? 1u : 0u);
        }
        switch (instruction & kOpMask) {
            case kOpPush: stack = (stack << 1) | value; break;
            case kOpAnd: stack &= ~1u | value; break;
            case kOpOr: stack |= value; break;
            default: break;
        }
    }
    return (stack & 1u) != 0;
}

bool runCompiledTree(const CompiledTree& compiled, const std::vector<bool>& operandInside) {
    if (compiled.kind == CompiledTree::Kind::Empty) return false;
    if (compiled.kind == CompiledTree::Kind::Everything) return true;
    return runCode(compiled.code, operandInside);
}

std::string disassemble(const CompiledTree& compiled) {
    std::ostringstream out;
    if (compiled.kind == CompiledTree::Kind::Empty) return "EMPTY\n";
    if (compiled.kind == CompiledTree::Kind::Everything) return "EVERYTHING\n";
    static const char* const kNames[] = {"PUSH", "AND", "OR", "?"};
    for (std::uint32_t instruction : compiled.code) {
        out << kNames[instruction & kOpMask] << ' ';
        if (instruction & kOpFromStack) {
            out << "pop";
        } else {
            out << ((instruction & kOpNegate) ? "!" : "") << (instruction >> kOperandShift);
        }
        out << '\n';
    }
    return out.str();
}

}  // namespace strata::csg
