#include "CsgParserImpl.h"

namespace strata::scene::detail {

namespace {

// Leaves whose solid is convex by construction: a Minkowski sum with them is
// the hull of vertex sums.
bool convexByConstruction(const Primitive& p) {
    return std::holds_alternative<Cube>(p) || std::holds_alternative<Sphere>(p) || std::holds_alternative<Cylinder>(p) ||
           std::holds_alternative<Hull>(p);
}

// Leaves whose parameters make no solid (a cube with a side of 0, a sphere
// of radius 0, a cylinder of no height or no radius): OpenSCAD makes them
// empty, and mesh::tessellate makes no mesh for them.
bool emptyByParameters(const Primitive& p) {
    if (const auto* c = std::get_if<Cube>(&p)) {
        const glm::dvec3 s = c->size;
        return !(s.x > 0 && s.y > 0 && s.z > 0) || std::isinf(s.x) || std::isinf(s.y) || std::isinf(s.z);
    }
    if (const auto* s = std::get_if<Sphere>(&p)) return !(s->r > 0) || std::isinf(s->r);
    if (const auto* c = std::get_if<Cylinder>(&p)) {
        return !(c->h > 0) || std::isinf(c->h) || !(c->r1 >= 0) || !(c->r2 >= 0) || !(c->r1 > 0 || c->r2 > 0) ||
               std::isinf(c->r1) || std::isinf(c->r2);
    }
    return false;
}

constexpr std::size_t kMaxMinkowskiParts = 4096;

}  // namespace

// projection(): solids again below it, whatever the context, read as a tree of their own.
void Parser::openProjection(const Statement& st, Open open, const Open& parent) {
    const bool off = parent.flat ? (parent.flatNode < 0 || st.disabled || st.background) : st.dropped;
    open.gather = Open::Gather::Projection;
    open.cut = boolean(st.args, "cut", 0, false);
    open.flat = false;
    open.flatParent = parent.flat ? parent.flatNode : -1;
    open.outside = open.context;
    open.context = Context{};
    open.shape = !off;
    if (!off) {
        open.node = tree_.addNode(NodeKind::Union, {});
        tree_.nodes[static_cast<std::size_t>(open.node)].where = st.where;
    }
    enterBlock(st, std::move(open));
}

// resize(newsize = [x, y, z], auto = [0, 0, 0] | true): a size of 0 keeps an axis.
Resize Parser::resizeArguments(const std::vector<CsgArgument>& args) const {
    Resize r;
    const CsgArgument* size = find(args, "newsize", 0);
    if (size != nullptr && size->value.type == CsgValue::Type::Numbers) {
        const std::vector<double>& v = size->value.numbers;
        if (v.size() > 3) lex_.failAt(size->where, "newsize must be a vector of up to 3 numbers");
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (!std::isfinite(v[i])) lex_.failAt(size->where, "newsize must be finite");
            r.newsize[static_cast<int>(i)] = v[i];
        }
    } else if (size != nullptr && size->value.type == CsgValue::Type::Number) {
        r.newsize = glm::dvec3(number(*size, "newsize"));
    } else if (size != nullptr && size->value.type != CsgValue::Type::Undef) {
        lex_.failAt(size->where, "newsize must be a vector of numbers");
    }
    const CsgArgument* autosize = find(args, "auto", 1);
    if (autosize != nullptr) {
        const CsgValue& v = autosize->value;
        if (v.type == CsgValue::Type::Bool) {
            r.autosize = {v.boolean, v.boolean, v.boolean};
        } else if (v.type == CsgValue::Type::Numbers) {
            for (std::size_t i = 0; i < v.numbers.size() && i < 3; ++i) r.autosize[i] = v.numbers[i] != 0.0;
        } else if (v.type == CsgValue::Type::List) {
            for (std::size_t i = 0; i < v.items.size() && i < 3; ++i) {
                const CsgValue& item = v.items[i];
                r.autosize[i] = item.type == CsgValue::Type::Bool ? item.boolean
                                : item.type == CsgValue::Type::Number ? item.number != 0.0
                                                                      : false;
            }
        }
    }
    return r;
}

// resize() closes: its leaves (placed relative to it) become a resize group
// that buildModel scales once their meshes are known; flat children become
// one flat result, resized as OpenSCAD resizes a Polygon2d.
int Parser::finishResize(const Open& open) {
    const Node& n = tree_.nodes[static_cast<std::size_t>(open.node)];
    if (n.children.empty()) return emptyNode(n.where);
    if (flatChildren(open.node)) {
        const int merged = mergeFlatChildren(open.node, FlatOp::Resize, open.resize.outer, &open.context);
        if (merged < 0) return -1;
        FlatTree& shape = std::get<FlatSlab>(tree_.leaves[static_cast<std::size_t>(tree_.nodes[static_cast<std::size_t>(merged)].leaf)].primitive).shape;
        FlatNode& root = shape.nodes[static_cast<std::size_t>(shape.root)];
        root.newsize = {open.resize.newsize.x, open.resize.newsize.y};
        root.autosize = {open.resize.autosize[0], open.resize.autosize[1]};
        return merged;
    }
    Resize resize = open.resize;
    exactify(open.node);  // the box of a difference or intersection is its exact result's
    resize.leaves = tree_.leavesUnder(open.node);
    tree_.resizes.push_back(std::move(resize));
    const std::vector<int>& children = tree_.nodes[static_cast<std::size_t>(open.node)].children;
    return children.size() == 1 ? children.front() : open.node;
}

// The subtree under `root`, moved into a tree of its own (nodes parent
// first, its leaves and the resize groups wholly inside it); what stays
// behind is unreachable and dropped by compact().
std::shared_ptr<Tree> Parser::extractSolid(int root) {
    auto solid = std::make_shared<Tree>();
    solid->source = tree_.source;
    std::unordered_map<int, int> nodeMap, leafMap;
    std::vector<int> order{root}, todo{root};
    nodeMap[root] = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        for (int c : tree_.nodes[static_cast<std::size_t>(order[i])].children) {
            if (nodeMap.emplace(c, static_cast<int>(order.size())).second) order.push_back(c);
        }
    }
    for (int n : order) {
        Node node = tree_.nodes[static_cast<std::size_t>(n)];
        for (int& c : node.children) c = nodeMap.at(c);
        if (node.kind == NodeKind::Leaf) {
            auto [it, added] = leafMap.emplace(node.leaf, static_cast<int>(solid->leaves.size()));
            if (added) solid->leaves.push_back(std::move(tree_.leaves[static_cast<std::size_t>(node.leaf)]));
            node.leaf = it->second;
        }
        solid->nodes.push_back(std::move(node));
    }
    for (const Resize& r : tree_.resizes) {
        Resize inside = r;
        bool all = true;
        for (int& l : inside.leaves) {
            const auto it = leafMap.find(l);
            if (it == leafMap.end()) {
                all = false;
                break;
            }
            l = it->second;
        }
        if (all) solid->resizes.push_back(std::move(inside));
    }
    solid->root = 0;
    return solid;
}

// Every difference or intersection reached from `root` through unions
// becomes one Exact leaf holding its subtree, so that the leaves under
// `root` make its result (for the nodes that need that result's geometry).
void Parser::exactify(int root) {
    std::vector<int> todo{root};
    while (!todo.empty()) {
        const int at = todo.back();
        todo.pop_back();
        if (tree_.nodes[static_cast<std::size_t>(at)].kind != NodeKind::Union) continue;
        for (std::size_t i = 0; i < tree_.nodes[static_cast<std::size_t>(at)].children.size(); ++i) {
            const int c = tree_.nodes[static_cast<std::size_t>(at)].children[i];
            const NodeKind kind = tree_.nodes[static_cast<std::size_t>(c)].kind;
            if (kind == NodeKind::Union) {
                todo.push_back(c);
            } else if (kind == NodeKind::Difference || kind == NodeKind::Intersection) {
                const SourceLocation where = tree_.nodes[static_cast<std::size_t>(c)].where;
                Leaf leaf;
                leaf.where = where;
                Exact exact{extractSolid(c)};
                // The result shows as its first solid does.
                if (!exact.solid->leaves.empty()) {
                    leaf.color = exact.solid->leaves.front().color;
                    leaf.display = exact.solid->leaves.front().display;
                }
                leaf.primitive = std::move(exact);
                const int node = tree_.addLeaf(std::move(leaf));
                tree_.nodes[static_cast<std::size_t>(at)].children[i] = node;
            }
        }
    }
}

// Every child of `node` that holds a resize() becomes one Exact leaf holding
// its subtree (with the resize group, which extractSolid keeps): a hull or
// Minkowski sum copies its leaves, and a copy would not be resized. Only the
// resizes from `first` on can be inside it.
void Parser::exactifyResized(int node, std::size_t first) {
    std::unordered_set<int> resized;
    for (std::size_t i = first; i < tree_.resizes.size(); ++i) {
        resized.insert(tree_.resizes[i].leaves.begin(), tree_.resizes[i].leaves.end());
    }
    if (resized.empty()) return;
    for (std::size_t i = 0; i < tree_.nodes[static_cast<std::size_t>(node)].children.size(); ++i) {
        const int c = tree_.nodes[static_cast<std::size_t>(node)].children[i];
        const std::vector<int> under = tree_.leavesUnder(c);
        if (std::none_of(under.begin(), under.end(), [&](int l) { return resized.count(l) != 0; })) continue;
        Leaf leaf;
        leaf.where = tree_.nodes[static_cast<std::size_t>(c)].where;
        Exact exact{extractSolid(c)};
        if (!exact.solid->leaves.empty()) {
            leaf.color = exact.solid->leaves.front().color;
            leaf.display = exact.solid->leaves.front().display;
        }
        leaf.primitive = std::move(exact);
        const int replacement = tree_.addLeaf(std::move(leaf));
        tree_.nodes[static_cast<std::size_t>(node)].children[i] = replacement;
    }
}

// projection() closes: its solids become a Projection shape, joined to the
// flat tree it stands in, or shown as a slab of its own among solids.
int Parser::finishProjection(const Open& open) {
    const SourceLocation where = tree_.nodes[static_cast<std::size_t>(open.node)].where;
    // The shadow of a difference or intersection needs its exact result.
    if (!open.cut) exactify(open.node);
    Projection projection;
    projection.cut = open.cut;
    projection.solid = extractSolid(open.node);
    FlatNode shape;
    shape.op = FlatOp::Shape;
    shape.where = where;
    if (open.flatParent >= 0) {
        FlatTree& flat = pending().tree;
        shape.shape = static_cast<int>(flat.shapes.size());
        flat.shapes.emplace_back(std::in_place_type<Projection>, std::move(projection));
        const int index = flat.add(std::move(shape));
        flat.nodes[static_cast<std::size_t>(open.flatParent)].children.push_back(index);
        return -1;
    }
    FlatTree flat;
    shape.shape = 0;
    flat.shapes.emplace_back(std::in_place_type<Projection>, std::move(projection));
    flat.root = flat.add(std::move(shape));
    Leaf leaf = leafAt(open.outside, where);
    leaf.primitive = FlatSlab{std::move(flat)};
    return tree_.addLeaf(std::move(leaf));
}

// A node that stands for the empty solid where a statement makes nothing
// (a hull or minkowski of no solid): it takes part in the CSG as the empty
// set, as OpenSCAD's empty result does (an intersection with it is empty).
int Parser::emptyNode(SourceLocation where) {
    const int node = tree_.addNode(NodeKind::Union, {});
    tree_.nodes[static_cast<std::size_t>(node)].where = std::move(where);
    return node;
}

// hull() and minkowski() close: their children become hull leaves (a
// minkowski of unions of convex leaves, one hull per choice of a part from
// each child, under a union), or one flat result when the children are flat;
// all of them placed by the node's own transform. A child without a solid is
// left out (OpenSCAD's minkowski skips empty children), and without any the
// node is the empty solid. Returns the node that replaces the statement, or
// -1 when strata cannot make it yet (counted and warned, the subtree left out).
int Parser::finishGather(const Open& open) {
    if (open.gather == Open::Gather::Resize) return finishResize(open);
    if (open.gather == Open::Gather::Projection) return finishProjection(open);
    const bool hull = open.gather == Open::Gather::Hull;
    const char* name = hull ? "hull" : "minkowski";
    const Node& n = tree_.nodes[static_cast<std::size_t>(open.node)];
    const SourceLocation where = n.where;
    if (n.children.empty()) return emptyNode(where);
    if (flatChildren(open.node)) {
        return mergeFlatChildren(open.node, hull ? FlatOp::Hull : FlatOp::Minkowski, open.placement, &open.context);
    }

    // Each child's solid leaves (a hull takes them all as one set of points);
    // a difference or intersection among them, or a resize, is evaluated
    // exactly.
    exactify(open.node);
    exactifyResized(open.node, open.resizesBefore);
    std::vector<std::vector<int>> children;
    std::vector<int> solidChildren;  // the children with a solid in them
    bool convex = true;              // every solid leaf convex by construction
    for (int c : tree_.nodes[static_cast<std::size_t>(open.node)].children) {
        std::vector<int> solid;
        for (int l : tree_.leavesUnder(c)) {
            const Primitive& p = tree_.leaves[static_cast<std::size_t>(l)].primitive;
            if (std::holds_alternative<FlatSlab>(p)) {
                warnOnce("2d-in-3d", tree_.leaves[static_cast<std::size_t>(l)].where,
                         std::string("a 2D object inside ") + name + " of solids is ignored, as OpenSCAD ignores it");
                continue;
            }
            // Adds no point to a hull and no part to its child's union.
            if (emptyByParameters(p)) continue;
            convex = convex && convexByConstruction(p);
            solid.push_back(l);
        }
        if (!solid.empty()) {
            children.push_back(std::move(solid));
            solidChildren.push_back(c);
        }
    }
    if (children.empty()) return emptyNode(where);
    if (!hull && !convex) {
        // Other solids are split into convex parts once their meshes are known.
        MinkowskiSum sum;
        for (int c : solidChildren) sum.operands.push_back(extractSolid(c));
        Leaf leaf = leafAt(open.context, where);
        leaf.transform = open.placement;  // the operands are placed relative to the node
        leaf.primitive = std::move(sum);
        return tree_.addLeaf(std::move(leaf));
    }
    auto leafCopy = [&](int l) { return tree_.leaves[static_cast<std::size_t>(l)]; };
    auto hullLeaf = [&](Hull h) {
        Leaf leaf = leafAt(open.context, where);
        leaf.transform = open.placement;  // the parts are placed relative to the node
        leaf.primitive = std::move(h);
        return tree_.addLeaf(std::move(leaf));
    };
    if (hull) {
        // Each leaf is taken once, and the node it was under is left behind:
        // moved, not copied, so that hulls inside one another cost their
        // leaves once, not once for every hull around them.
        Hull h;
        for (const auto& child : children)
            for (int l : child) h.parts.push_back(std::move(tree_.leaves[static_cast<std::size_t>(l)]));
        return hullLeaf(std::move(h));
    }
    // minkowski: one hull per choice of a part from each child.
    std::size_t combinations = 1;
    for (const auto& child : children) {
        combinations *= child.size();
        if (combinations > kMaxMinkowskiParts) {
            unsupported("minkowski of more than " + std::to_string(kMaxMinkowskiParts) + " part combinations", where);
            return -1;
        }
    }
    // A part of child c goes into combinations / (its child's parts) sums:
    // copied into all but the last, moved into that one, so that sums inside
    // one another (each a hull leaf holding the sum inside it) cost their
    // leaves once, not once for every sum around them.
    std::unordered_map<int, std::size_t> usesLeft;
    for (const auto& child : children)
        for (int l : child) usesLeft[l] += combinations / child.size();
    auto take = [&](int l) {
        return --usesLeft[l] == 0 ? std::move(tree_.leaves[static_cast<std::size_t>(l)]) : leafCopy(l);
    };
    std::vector<int> sums;
    std::vector<std::size_t> choice(children.size(), 0);
    for (std::size_t k = 0; k < combinations; ++k) {
        Hull h;
        h.parts.push_back(take(children[0][choice[0]]));
        for (std::size_t c = 1; c < children.size(); ++c) h.summands.push_back(take(children[c][choice[c]]));
        sums.push_back(hullLeaf(std::move(h)));
        for (std::size_t c = 0; c < children.size() && ++choice[c] == children[c].size(); ++c) choice[c] = 0;
    }
    if (sums.size() == 1) return sums.front();
    const int u = tree_.addNode(NodeKind::Union, std::move(sums));
    tree_.nodes[static_cast<std::size_t>(u)].where = where;
    return u;
}

}  // namespace strata::scene::detail
