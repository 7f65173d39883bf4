#include "SumOfProducts.h"

#include <glm/common.hpp>

namespace strata::bench {
namespace {

enum class Op { Leaf, Union, Intersection, Difference };

// One term of the binary tree; terms refer to each other by index, and one
// term may be the operand of several (a shared subtree).
struct Term {
    Op op = Op::Leaf;
    int leaf = -1;             // for Op::Leaf: index into Tree::leaves; -1: the empty set
    int left = -1, right = -1; // for operations; -1: no operand (only while collapsing)
    LeafBox box{};
};

constexpr int kNone = -1;

class Normalizer {
public:
    Normalizer(const scene::Tree& tree, const std::vector<std::optional<LeafBox>>& boxes, std::size_t limit)
        : tree_(tree), boxes_(boxes), limit_(limit) {}

    SumOfProducts run() {
        SumOfProducts out;
        out.limit = limit_;
        if (tree_.root < 0) return out;
        const int root = fromNode(tree_.root);
        const int normalized = rewriteAll(root);
        out.elements = count_;
        if (aborted_) {
            out.gaveUp = true;
            return out;
        }
        if (normalized != kNone) readProducts(normalized, out.products);
        return out;
    }

private:
    bool isLeaf(int t) const { return t != kNone && terms_[std::size_t(t)].op == Op::Leaf; }
    bool isEmptySet(int t) const { return isLeaf(t) && terms_[std::size_t(t)].leaf < 0; }
    bool isUnion(int t) const { return t != kNone && terms_[std::size_t(t)].op == Op::Union; }
    bool isOperation(int t) const { return t != kNone && terms_[std::size_t(t)].op != Op::Leaf; }
    Term& at(int t) { return terms_[std::size_t(t)]; }

    int emptySet() {
        terms_.push_back(Term{});
        return int(terms_.size() - 1);
    }

    static bool overlaps(const LeafBox& a, const LeafBox& b) {
        // Boxes that only touch still overlap (OpenSCAD tests min > max).
        const glm::dvec3 lo = glm::max(a.min, b.min), hi = glm::min(a.max, b.max);
        return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z;
    }

    // A binary operation, with empty operands dropped and disjoint boxes pruned.
    int combine(Op op, int left, int right) {
        if (left == kNone && right == kNone) return emptySet();
        if (left == kNone) return right;
        if (right == kNone) return left;
        if (isEmptySet(right)) return op == Op::Intersection ? right : left;
        if (isEmptySet(left)) return op == Op::Union ? right : left;
        const LeafBox a = at(left).box, b = at(right).box;
        if (op == Op::Intersection && !overlaps(a, b)) return emptySet();
        if (op == Op::Difference && !overlaps(a, b)) return left;
        Term term;
        term.op = op;
        term.left = left;
        term.right = right;
        if (op == Op::Union)
            term.box = {glm::min(a.min, b.min), glm::max(a.max, b.max)};
        else if (op == Op::Intersection)
            term.box = {glm::max(a.min, b.min), glm::min(a.max, b.max)};
        else
            term.box = a;
        terms_.push_back(term);
        return int(terms_.size() - 1);
    }

    int leafTerm(const scene::Node& node) {
        const std::size_t leaf = std::size_t(node.leaf);
        if (node.leaf < 0 || leaf >= boxes_.size() || !boxes_[leaf]) return emptySet();
        Term term;
        term.leaf = node.leaf;
        term.box = *boxes_[leaf];
        terms_.push_back(term);
        return int(terms_.size() - 1);
    }

    static Op opOf(scene::NodeKind kind) {
        return kind == scene::NodeKind::Union          ? Op::Union
               : kind == scene::NodeKind::Intersection ? Op::Intersection
                                                       : Op::Difference;
    }

    // The scene's node as a binary term, each operation folded from the left
    // over its children in order; depth first with a stack of its own, as
    // scene trees can nest many thousand deep.
    int fromNode(int root) {
        struct Frame {
            int node;
            std::size_t next = 0;  // the child to fold in next
            int folded = kNone;
        };
        std::vector<Frame> stack{{root}};
        int done = kNone;  // the term of the node finished last
        bool returning = false;
        while (!stack.empty()) {
            Frame& frame = stack.back();
            const scene::Node& node = tree_.nodes[std::size_t(frame.node)];
            if (returning) {
                frame.folded = frame.folded == kNone ? done : combine(opOf(node.kind), frame.folded, done);
                ++frame.next;
                returning = false;
            }
            if (node.kind == scene::NodeKind::Leaf) {
                done = leafTerm(node);
            } else if (node.children.empty()) {
                done = emptySet();
            } else if (frame.next < node.children.size()) {
                stack.push_back({node.children[frame.next]});
                continue;
            } else {
                done = frame.folded;
            }
            stack.pop_back();
            returning = true;
        }
        return done;
    }

    // One rewrite at the top of `t`, if a rule matches; `t` becomes the new term.
    bool rewriteOnce(int& t) {
        if (!isOperation(t) || isUnion(t)) return false;
        const Term term = at(t);
        if (isOperation(term.right)) {
            const Term r = at(term.right);
            const int x = term.left, y = r.left, z = r.right;
            if (term.op == Op::Difference && r.op == Op::Union) {
                t = combine(Op::Difference, combine(Op::Difference, x, y), z);
                return true;
            }
            if (term.op == Op::Intersection && r.op == Op::Union) {
                t = combine(Op::Union, combine(Op::Intersection, x, y), combine(Op::Intersection, x, z));
                return true;
            }
            if (term.op == Op::Difference && r.op == Op::Intersection) {
                t = combine(Op::Union, combine(Op::Difference, x, y), combine(Op::Difference, x, z));
                return true;
            }
            if (term.op == Op::Intersection && r.op == Op::Intersection) {
                t = combine(Op::Intersection, combine(Op::Intersection, x, y), z);
                return true;
            }
            if (term.op == Op::Difference && r.op == Op::Difference) {
                t = combine(Op::Union, combine(Op::Difference, x, y), combine(Op::Intersection, x, z));
                return true;
            }
            if (term.op == Op::Intersection && r.op == Op::Difference) {
                t = combine(Op::Difference, combine(Op::Intersection, x, y), z);
                return true;
            }
        }
        if (isOperation(term.left)) {
            const Term l = at(term.left);
            const int x = l.left, y = l.right, z = term.right;
            if (l.op == Op::Difference && term.op == Op::Intersection) {
                t = combine(Op::Difference, combine(Op::Intersection, x, z), y);
                return true;
            }
            if (l.op == Op::Union && term.op == Op::Difference) {
                t = combine(Op::Union, combine(Op::Difference, x, z), combine(Op::Difference, y, z));
                return true;
            }
            if (l.op == Op::Union && term.op == Op::Intersection) {
                t = combine(Op::Union, combine(Op::Intersection, x, z), combine(Op::Intersection, y, z));
                return true;
            }
        }
        return false;
    }

    // An operation left without an operand stands for what remains of it.
    int collapse(int t) {
        if (!isOperation(t)) return t;
        const Term& term = at(t);
        if (term.right == kNone) {
            --count_;
            return term.op == Op::Intersection ? term.right : term.left;
        }
        if (term.left == kNone) {
            --count_;
            return term.op == Op::Union ? term.right : term.left;
        }
        return t;
    }

    // The rewriting of the whole tree, depth first with a stack of its own
    // (trees of many thousand leaves are that deep): at an operation, rewrite
    // until no rule matches and count it; normalize its left operand, and
    // again from the rewriting while the operation is no union and its right
    // operand is an operation or its left one a union; then its right operand.
    int rewriteAll(int root) {
        enum class Step { Enter, Rewrite, LeftDone, RightDone };
        struct Frame {
            int term;
            Step step;
        };
        std::vector<Frame> stack{{root, Step::Enter}};
        int done = kNone;  // what the last finished frame gave back
        while (!stack.empty()) {
            Frame frame = stack.back();
            stack.pop_back();
            switch (frame.step) {
            case Step::Enter:
                if (isLeaf(frame.term)) {
                    done = frame.term;
                    break;
                }
                [[fallthrough]];
            case Step::Rewrite:
                while (frame.term != kNone && rewriteOnce(frame.term)) {
                }
                if (++count_ > limit_) {
                    aborted_ = true;
                    return kNone;
                }
                if (!isOperation(frame.term)) {
                    done = frame.term;
                    break;
                }
                stack.push_back({frame.term, Step::LeftDone});
                stack.push_back({at(frame.term).left, Step::Enter});
                break;
            case Step::LeftDone: {
                at(frame.term).left = done;
                const Term& term = at(frame.term);
                if (term.op != Op::Union && (isOperation(term.right) || isUnion(term.left))) {
                    stack.push_back({frame.term, Step::Rewrite});
                    break;
                }
                stack.push_back({frame.term, Step::RightDone});
                stack.push_back({term.right, Step::Enter});
                break;
            }
            case Step::RightDone:
                at(frame.term).right = done;
                done = collapse(frame.term);
                break;
            }
        }
        return done;
    }

    // The normalized tree, left operand first, into products.
    void readProducts(int root, std::vector<NormalizedProduct>& products) const {
        products.emplace_back();
        bool intoSubtractions = false;
        struct Item {
            int term;
            Op reachedAs;  // the operation this term is the right operand of, or what its parent was reached as
        };
        std::vector<Item> stack{{root, Op::Union}};
        while (!stack.empty()) {
            const Item item = stack.back();
            stack.pop_back();
            const Term& term = terms_[std::size_t(item.term)];
            if (term.op == Op::Leaf) {
                if (item.reachedAs == Op::Union && !products.back().intersections.empty()) {
                    products.emplace_back();
                    intoSubtractions = false;
                } else if (item.reachedAs == Op::Difference) {
                    intoSubtractions = true;
                } else if (item.reachedAs == Op::Intersection) {
                    intoSubtractions = false;
                }
                if (term.leaf >= 0)  // an empty set draws nothing
                    (intoSubtractions ? products.back().subtractions : products.back().intersections)
                        .push_back(term.leaf);
                continue;
            }
            stack.push_back({term.right, term.op});
            stack.push_back({term.left, item.reachedAs});
        }
        // A product with nothing intersected draws nothing.
        std::erase_if(products, [](const NormalizedProduct& p) { return p.intersections.empty(); });
    }

    const scene::Tree& tree_;
    const std::vector<std::optional<LeafBox>>& boxes_;
    std::size_t limit_;
    std::vector<Term> terms_;
    std::size_t count_ = 0;
    bool aborted_ = false;
};

}  // namespace

std::size_t SumOfProducts::primitives() const {
    std::size_t n = 0;
    for (const NormalizedProduct& p : products) n += p.intersections.size() + p.subtractions.size();
    return n;
}

SumOfProducts sumOfProducts(const scene::Tree& tree, const std::vector<std::optional<LeafBox>>& leafBoxes,
                            std::size_t limit) {
    return Normalizer(tree, leafBoxes, limit).run();
}

}  // namespace strata::bench
