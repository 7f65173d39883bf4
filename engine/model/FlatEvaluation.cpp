#include "strata/model/FlatEvaluation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <glm/common.hpp>

#include "strata/core/DegreeTrig.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/flat/FlatClipper.h"
#include "strata/flat/FlatImport.h"
#include "strata/flat/Text.h"
#include "strata/mesh/Primitives.h"
#include "strata/model/Projection.h"

// Follows OpenSCAD 2021.01's src/GeometryEvaluator.cc (applyToChildren2D, the
// visits of TransformNode and OffsetNode), src/primitives.cc (square, circle,
// polygon) and src/Polygon2d.cc (transform).

namespace strata::model {

using flat::Outline;
using flat::Outlines;
using mesh::fragmentsFromR;
using flat::importFlat;
using flat::textGlyphs;

namespace {

using Result = std::optional<Outlines>;  // nullopt: no geometry (OpenSCAD's nullptr or empty)

constexpr double kOffsetMiterLimit = 1000000.0;  // OpenSCAD's OffsetNode::miter_limit

Outlines square(const scene::Square& s) {
    Outlines shape;
    shape.sanitized = true;  // made counter-clockwise, used as is
    const double x = s.size.x, y = s.size.y;
    if (!(x > 0.0 && y > 0.0) || std::isinf(x) || std::isinf(y)) return shape;
    glm::dvec2 a(0.0, 0.0), b(x, y);
    if (s.center) {
        a -= glm::dvec2(x / 2, y / 2);
        b -= glm::dvec2(x / 2, y / 2);
    }
    shape.outlines.push_back(Outline{{a, {b.x, a.y}, b, {a.x, b.y}}, true});
    return shape;
}

Outlines circle(const scene::Circle& c) {
    Outlines shape;
    shape.sanitized = true;
    if (!(c.r > 0.0) || std::isinf(c.r)) return shape;
    const int n = fragmentsFromR(c.r, c.fragments);
    Outline o;
    o.points.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double phi = (360.0 * i) / n;
        o.points[static_cast<std::size_t>(i)] = {c.r * cosDegrees(phi), c.r * sinDegrees(phi)};
    }
    shape.outlines.push_back(std::move(o));
    return shape;
}

Outlines polygon(const scene::Polygon& p) {
    Outlines shape;
    if (p.paths.empty()) {
        if (p.points.size() > 2) shape.outlines.push_back(Outline{p.points, true});
    } else {
        for (const auto& path : p.paths) {
            Outline o;
            for (int index : path) {
                if (index >= 0 && static_cast<std::size_t>(index) < p.points.size())
                    o.points.push_back(p.points[static_cast<std::size_t>(index)]);
            }
            shape.outlines.push_back(std::move(o));
        }
    }
    return flat::sanitize(shape);
}

// Polygon2d::transform with the xy part of a 3D matrix; a flattening matrix
// empties the shape, a mirroring one makes Clipper orient it again.
Result transform(Outlines shape, const glm::dmat4& m) {
    // OpenSCAD's mat2, rows (m00 m01 m03), (m10 m11 m13), (m30 m31 m33); glm is m[column][row].
    const double a = m[0][0], b = m[1][0], c = m[3][0];
    const double d = m[0][1], e = m[1][1], f = m[3][1];
    const double g = m[0][3], h = m[1][3], k = m[3][3];
    const double det = a * (e * k - f * h) - d * (b * k - c * h) + g * (b * f - c * e);
    if (det == 0.0) return std::nullopt;
    for (Outline& o : shape.outlines) {
        for (glm::dvec2& p : o.points) {
            const double x = p.x, y = p.y;
            p = {(a * x + b * y) + c, (d * x + e * y) + f};
        }
    }
    if (shape.sanitized && det <= 0.0) return flat::sanitize(shape);
    return shape;
}

flat::FlatBoolean booleanOf(scene::FlatOp op) {
    if (op == scene::FlatOp::Intersection) return flat::FlatBoolean::Intersection;
    if (op == scene::FlatOp::Difference) return flat::FlatBoolean::Difference;
    return flat::FlatBoolean::Union;
}

// applyToChildren2D: one child passes through untouched (or absent), several
// go through Clipper; no children at all is no geometry.
Result combine(std::vector<Result>& children, scene::FlatOp op) {
    if (children.empty()) return std::nullopt;
    if (children.size() == 1) return std::move(children.front());
    std::vector<const Outlines*> operands;
    operands.reserve(children.size());
    for (const Result& r : children) operands.push_back(r && !r->empty() ? &*r : nullptr);
    return flat::apply(operands, booleanOf(op));
}

Result offset(const Outlines& shape, const scene::Offset& o) {
    const double n = fragmentsFromR(std::fabs(o.amount), o.fragments);
    const double tolerance = std::fabs(o.amount) * (1 - cosDegrees(180 / n));
    const flat::FlatJoin join = o.join == scene::Offset::Join::Round   ? flat::FlatJoin::Round
                                  : o.join == scene::Offset::Join::Miter ? flat::FlatJoin::Miter
                                                                         : flat::FlatJoin::Square;
    return flat::offset(shape, o.amount, join, kOffsetMiterLimit, tolerance);
}

// OpenSCAD's applyHull2D: the convex hull of every child's points, one
// counter-clockwise outline, left unsanitized as OpenSCAD leaves it.
Result hull(const std::vector<Result>& children) {
    std::vector<glm::dvec2> points;
    for (const Result& r : children)
        if (r)
            for (const Outline& o : r->outlines) points.insert(points.end(), o.points.begin(), o.points.end());
    if (points.empty()) return std::nullopt;
    std::sort(points.begin(), points.end(),
              [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    auto turn = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    // Andrew's monotone chain; collinear points are not corners.
    std::vector<glm::dvec2> h(2 * points.size());
    std::size_t k = 0;
    for (const glm::dvec2& p : points) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], p) <= 0) --k;
        h[k++] = p;
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(h[k - 2], h[k - 1], points[i]) <= 0) --k;
        h[k++] = points[i];
    }
    h.resize(k > 1 ? k - 1 : k);
    if (h.size() < 3) return std::nullopt;
    Outlines shape;
    shape.outlines.push_back(Outline{std::move(h), true});
    return shape;
}

// Polygon2d::resize: each axis given a size scaled to it, an `auto` axis by
// the larger given one's scale; a shape with no extent along a given axis
// cannot be stretched and stays as it is.
Result resize(Outlines shape, const scene::FlatNode& node) {
    glm::dvec2 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (const Outline& o : shape.outlines)
        for (const glm::dvec2& p : o.points) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    const glm::dvec2 size = hi - lo;
    const glm::dvec2 want = node.newsize;
    const int largest = (want.y != 0.0 && want.y > want.x) ? 1 : 0;
    if ((want.x > 0 && size.x == 0.0) || (want.y > 0 && size.y == 0.0)) return shape;
    const glm::dvec2 scale(want.x > 0 ? want.x / size.x : 1, want.y > 0 ? want.y / size.y : 1);
    const double autoscale = want[largest] > 0 ? want[largest] / size[largest] : 1;
    const glm::dvec2 s(!node.autosize[0] || want.x > 0 ? scale.x : autoscale,
                       !node.autosize[1] || want.y > 0 ? scale.y : autoscale);
    glm::dmat4 m(1.0);
    m[0][0] = s.x;
    m[1][1] = s.y;
    return transform(std::move(shape), m);
}

Result nonEmpty(Result r) {
    if (r && r->empty()) return std::nullopt;
    return r;
}

Result evaluateNode(const scene::FlatTree& tree, const scene::FlatNode& node, std::vector<Result>& children) {
    // transform, offset and resize act on the union of their children.
    auto onUnion = [&children](auto&& apply) -> Result {
        Result joined = combine(children, scene::FlatOp::Union);
        if (!joined) return std::nullopt;
        return nonEmpty(apply(std::move(*joined)));
    };
    switch (node.op) {
        case scene::FlatOp::Shape:
            return nonEmpty(flatPrimitive(tree.shapes[static_cast<std::size_t>(node.shape)]));
        case scene::FlatOp::Union:
        case scene::FlatOp::Intersection:
        case scene::FlatOp::Difference: return nonEmpty(combine(children, node.op));
        case scene::FlatOp::Transform:
            return onUnion([&](Outlines shape) { return transform(std::move(shape), node.matrix); });
        case scene::FlatOp::Offset: return onUnion([&](Outlines shape) { return offset(shape, node.offset); });
        case scene::FlatOp::Resize: return onUnion([&](Outlines shape) { return resize(std::move(shape), node); });
        case scene::FlatOp::Hull: return hull(children);
        case scene::FlatOp::Minkowski: {
            if (children.empty()) return std::nullopt;
            std::vector<const Outlines*> operands;
            for (const Result& r : children) operands.push_back(r ? &*r : nullptr);
            return nonEmpty(flat::minkowski(operands));
        }
        case scene::FlatOp::Empty: break;
    }
    return std::nullopt;
}

}  // namespace

Outlines flatPrimitive(const scene::FlatPrimitive& primitive) {
    return std::visit(
        [](const auto& p) -> Outlines {
            using T = std::decay_t<decltype(p)>;
            if constexpr (std::is_same_v<T, scene::Square>) return square(p);
            else if constexpr (std::is_same_v<T, scene::Circle>) return circle(p);
            else if constexpr (std::is_same_v<T, scene::Polygon>) return polygon(p);
            else if constexpr (std::is_same_v<T, scene::Text>) {
                // The glyphs are unioned as OpenSCAD's TextNode does: each cleaned, then one union.
                std::vector<Outlines> glyphs = textGlyphs(p);
                const std::string step = "text: uniting " + std::to_string(glyphs.size()) + " glyphs";
                reportProgress(step.c_str(), 0, 0);
                std::vector<const Outlines*> operands;
                for (const Outlines& g : glyphs) operands.push_back(&g);
                return flat::apply(operands, flat::FlatBoolean::Union);
            } else if constexpr (std::is_same_v<T, scene::Projection>) {
                return project(p);
            } else {
                // As OpenSCAD's leaf nodes: cleaned by Clipper unless the reader already did (SVG).
                Outlines imported = importFlat(p);
                return imported.sanitized ? imported : flat::sanitize(imported);
            }
        },
        primitive);
}

Outlines evaluateFlat(const scene::FlatTree& tree) {
    if (tree.root < 0) return {};
    // Children come after their parents: walking backwards meets them first.
    std::vector<Result> results(tree.nodes.size());
    for (std::size_t i = tree.nodes.size(); i-- > 0;) {
        const scene::FlatNode& node = tree.nodes[i];
        try {
            std::vector<Result> children;
            children.reserve(node.children.size());
            for (int c : node.children) children.push_back(std::move(results[static_cast<std::size_t>(c)]));
            results[i] = evaluateNode(tree, node, children);
        } catch (const Error& e) {
            rethrowAt(node.where, e);
        }
    }
    Result& root = results[static_cast<std::size_t>(tree.root)];
    return root ? std::move(*root) : Outlines{};
}

namespace {

// Copies node `n` of the 3D tree, and everything under it, into `out` as
// flat nodes (parents before children, as evaluateFlat walks them). An
// explicit stack of (node, its copy's parent): trees may nest deeply.
int copyFlat(const scene::Tree& tree, int n, scene::FlatTree& out) {
    int top = -1;
    std::vector<std::pair<int, int>> todo{{n, -1}};
    while (!todo.empty()) {
        const auto [index, parent] = todo.back();
        todo.pop_back();
        const scene::Node& node = tree.nodes[static_cast<std::size_t>(index)];
        scene::FlatNode made;
        made.where = node.where;
        int at = -1;
        if (node.kind == scene::NodeKind::Leaf) {
            const scene::Leaf& leaf = tree.leaves[static_cast<std::size_t>(node.leaf)];
            made.op = scene::FlatOp::Transform;
            made.matrix = leaf.transform;
            made.where = leaf.where;
            at = out.add(std::move(made));
            const scene::FlatTree& shape = std::get<scene::FlatSlab>(leaf.primitive).shape;
            if (shape.root >= 0) {
                const int nodeOffset = static_cast<int>(out.nodes.size());
                const int shapeOffset = static_cast<int>(out.shapes.size());
                for (scene::FlatNode f : shape.nodes) {
                    for (int& k : f.children) k += nodeOffset;
                    if (f.shape >= 0) f.shape += shapeOffset;
                    out.nodes.push_back(std::move(f));
                }
                out.shapes.insert(out.shapes.end(), shape.shapes.begin(), shape.shapes.end());
                out.nodes[static_cast<std::size_t>(at)].children.push_back(shape.root + nodeOffset);
            }
        } else {
            made.op = node.kind == scene::NodeKind::Difference     ? scene::FlatOp::Difference
                      : node.kind == scene::NodeKind::Intersection ? scene::FlatOp::Intersection
                                                                   : scene::FlatOp::Union;
            at = out.add(std::move(made));
            // Reversed on the stack, so the children are copied in order.
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) todo.emplace_back(*c, at);
        }
        if (parent >= 0) out.nodes[static_cast<std::size_t>(parent)].children.push_back(at);
        else top = at;
    }
    return top;
}

}  // namespace

Outlines flatResult(const scene::Tree& tree) {
    if (!tree.isFlat()) return {};
    scene::FlatTree combined;
    combined.root = copyFlat(tree, tree.root, combined);
    Outlines result = evaluateFlat(combined);
    return result.sanitized ? result : flat::sanitize(result);
}

}  // namespace strata::model
