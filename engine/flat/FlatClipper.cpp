#include "strata/flat/FlatClipper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <polyclipping/clipper.hpp>

#include "BoxGroups.h"
#include "strata/core/Error.h"

namespace strata::flat {

using detail::FlatBox;
using detail::meetingBoxGroups;

namespace {

// Clipper's coordinate range (hiRange in clipper.cpp): points beyond it make
// Clipper throw, so they are refused here with a message of our own.
constexpr double kClipperRange = 4611686018427387903.0;  // 0x3FFFFFFFFFFFFFFF

ClipperLib::cInt toGrid(double v) {
    const double scaled = v * kClipperScale;
    if (!(std::fabs(scaled) < kClipperRange)) {
        throw Error("a 2D coordinate (" + std::to_string(v) + ") is too large for the 1/65536 grid");
    }
    // The conversion truncates toward zero, as OpenSCAD's IntPoint(x * 2^16) does.
    return static_cast<ClipperLib::cInt>(scaled);
}

ClipperLib::Path toPath(const Outline& outline, bool keepOrientation) {
    ClipperLib::Path path;
    path.reserve(outline.points.size());
    for (const glm::dvec2& p : outline.points) path.emplace_back(toGrid(p.x), toGrid(p.y));
    // Unsanitized outlines are all made to point up first, as OpenSCAD does.
    if (!keepOrientation && !ClipperLib::Orientation(path)) std::reverse(path.begin(), path.end());
    return path;
}

ClipperLib::Paths toPaths(const Outlines& shape) {
    ClipperLib::Paths paths;
    paths.reserve(shape.outlines.size());
    for (const Outline& o : shape.outlines) paths.push_back(toPath(o, shape.sanitized));
    return paths;
}

Outlines fromTree(const ClipperLib::PolyTree& tree) {
    Outlines result;
    for (const ClipperLib::PolyNode* node = tree.GetFirst(); node != nullptr; node = node->GetNext()) {
        ClipperLib::Path cleaned;
        ClipperLib::CleanPolygon(node->Contour, cleaned);
        if (cleaned.size() < 3) continue;  // cleaning can leave nothing
        Outline outline;
        // The sign is read from the orientation, not from IsHole(): offsets get the latter wrong.
        outline.positive = ClipperLib::Orientation(node->Contour);
        outline.points.reserve(cleaned.size());
        for (const ClipperLib::IntPoint& p : cleaned) {
            outline.points.emplace_back(1.0 * static_cast<double>(p.X) / kClipperScale,
                                        1.0 * static_cast<double>(p.Y) / kClipperScale);
        }
        result.outlines.push_back(std::move(outline));
    }
    result.sanitized = true;
    return result;
}

ClipperLib::PolyTree sanitizeTree(const ClipperLib::Paths& paths) {
    ClipperLib::PolyTree tree;
    ClipperLib::Clipper clipper;
    clipper.AddPaths(paths, ClipperLib::ptSubject, true);
    clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd);
    return tree;
}

ClipperLib::Paths sanitizedPaths(const Outlines& shape) {
    ClipperLib::Paths paths = toPaths(shape);
    if (!shape.sanitized) ClipperLib::PolyTreeToPaths(sanitizeTree(paths), paths);
    return paths;
}

// The quads swept by `poly` along the closed outline `path`: the sum of their
// edges, left for the union (OpenSCAD keeps Clipper's own union out of this
// step, for robustness).
void convolve(const ClipperLib::Path& poly, const ClipperLib::Path& path, ClipperLib::Paths& quads) {
    const std::size_t polyCount = poly.size(), pathCount = path.size();
    if (polyCount == 0 || pathCount == 0) return;
    std::vector<ClipperLib::Path> moved(pathCount);
    for (std::size_t i = 0; i < pathCount; ++i) {
        moved[i].reserve(polyCount);
        for (const ClipperLib::IntPoint& q : poly) moved[i].emplace_back(path[i].X + q.X, path[i].Y + q.Y);
    }
    for (std::size_t i = 0; i < pathCount; ++i) {
        for (std::size_t j = 0; j < polyCount; ++j) {
            ClipperLib::Path quad{moved[i][j], moved[(i + 1) % pathCount][j], moved[(i + 1) % pathCount][(j + 1) % polyCount],
                                  moved[i][(j + 1) % polyCount]};
            if (!ClipperLib::Orientation(quad)) ClipperLib::ReversePath(quad);
            quads.push_back(std::move(quad));
        }
    }
}

// A copy of every outline of `a` moved to a point of each outer outline of `b`:
// the sum's inside, which the swept edges alone leave open.
void fillInsides(const ClipperLib::Paths& a, const ClipperLib::Paths& b, ClipperLib::Paths& target) {
    for (const ClipperLib::Path& outline : b) {
        if (outline.empty() || !ClipperLib::Orientation(outline)) continue;
        const ClipperLib::IntPoint delta = outline[0];
        for (const ClipperLib::Path& path : a) {
            ClipperLib::Path moved = path;
            for (ClipperLib::IntPoint& p : moved) {
                p.X += delta.X;
                p.Y += delta.Y;
            }
            target.push_back(std::move(moved));
        }
    }
}

}  // namespace

std::pair<std::int64_t, std::int64_t> gridPoint(const glm::dvec2& p) { return {toGrid(p.x), toGrid(p.y)}; }

Outlines minkowski(const std::vector<const Outlines*>& children) {
    if (children.empty()) return {};
    if (children.size() == 1) return children[0] ? *children[0] : Outlines{};
    ClipperLib::Clipper clipper;
    ClipperLib::Paths sum = children[0] ? toPaths(*children[0]) : ClipperLib::Paths{};
    for (std::size_t i = 1; i < children.size(); ++i) {
        if (!children[i]) continue;
        const ClipperLib::Paths next = toPaths(*children[i]);
        ClipperLib::Paths terms;
        for (const ClipperLib::Path& b : next)
            for (const ClipperLib::Path& a : sum) convolve(a, b, terms);
        fillInsides(sum, next, terms);
        fillInsides(next, sum, terms);
        clipper.Clear();
        clipper.AddPaths(terms, ClipperLib::ptSubject, true);
        if (i + 1 != children.size()) clipper.Execute(ClipperLib::ctUnion, sum, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    }
    ClipperLib::PolyTree result;
    clipper.Execute(ClipperLib::ctUnion, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return fromTree(result);
}

Outlines shadow(const std::vector<std::vector<std::array<glm::dvec2, 3>>>& children) {
    ClipperLib::Clipper sum;
    for (const auto& triangles : children) {
        ClipperLib::Paths paths;
        paths.reserve(triangles.size());
        for (const auto& t : triangles) {
            ClipperLib::Path path{{toGrid(t[0].x), toGrid(t[0].y)}, {toGrid(t[1].x), toGrid(t[1].y)},
                                  {toGrid(t[2].x), toGrid(t[2].y)}};
            if (!ClipperLib::Orientation(path)) std::reverse(path.begin(), path.end());
            paths.push_back(std::move(path));
        }
        // NonZero, so that triangles sharing edges leave no holes between them.
        ClipperLib::Clipper child;
        child.AddPaths(paths, ClipperLib::ptSubject, true);
        ClipperLib::Paths joined;
        child.Execute(ClipperLib::ctUnion, joined, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        sum.AddPaths(joined, ClipperLib::ptSubject, true);
    }
    ClipperLib::PolyTree result;
    sum.StrictlySimple(true);
    sum.Execute(ClipperLib::ctUnion, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return fromTree(result);
}

Outlines sanitize(const Outlines& shape) { return fromTree(sanitizeTree(toPaths(shape))); }

namespace {

// A union of many operands whose boxes mostly do not meet, as the glyphs of
// a line of text, group by group (BoxGroups.h): groups whose boxes do not
// meet cannot touch, nor lie in a hole of one another, so their unions
// stand side by side as they are.
Outlines groupedUnion(const std::vector<ClipperLib::Paths>& operands) {
    std::vector<FlatBox<ClipperLib::cInt>> boxes;
    boxes.reserve(operands.size());
    for (const ClipperLib::Paths& paths : operands) {
        FlatBox<ClipperLib::cInt> b{std::numeric_limits<ClipperLib::cInt>::max(),
                                    std::numeric_limits<ClipperLib::cInt>::max(),
                                    std::numeric_limits<ClipperLib::cInt>::min(),
                                    std::numeric_limits<ClipperLib::cInt>::min()};
        for (const ClipperLib::Path& path : paths) {
            for (const ClipperLib::IntPoint& p : path) {
                b = {std::min(b.x0, p.X), std::min(b.y0, p.Y), std::max(b.x1, p.X), std::max(b.y1, p.Y)};
            }
        }
        boxes.push_back(b);
    }
    Outlines result;
    result.sanitized = true;
    for (const std::vector<std::size_t>& group : meetingBoxGroups(boxes)) {
        ClipperLib::Clipper clipper;
        for (std::size_t k = 0; k < group.size(); ++k) {
            clipper.AddPaths(operands[group[k]], k == 0 ? ClipperLib::ptSubject : ClipperLib::ptClip, true);
        }
        ClipperLib::PolyTree tree;
        clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        Outlines part = fromTree(tree);
        for (Outline& o : part.outlines) result.outlines.push_back(std::move(o));
    }
    return result;
}

}  // namespace

Outlines apply(const std::vector<const Outlines*>& children, FlatBoolean op) {
    std::vector<ClipperLib::Paths> operands;
    operands.reserve(children.size());
    for (const Outlines* child : children) operands.push_back(child ? sanitizedPaths(*child) : ClipperLib::Paths{});

    ClipperLib::Clipper clipper;
    ClipperLib::PolyTree result;
    if (op == FlatBoolean::Intersection && operands.size() >= 2) {
        ClipperLib::Paths source = operands[0];
        for (std::size_t i = 1; i < operands.size(); ++i) {
            clipper.AddPaths(source, ClipperLib::ptSubject, true);
            clipper.AddPaths(operands[i], ClipperLib::ptClip, true);
            clipper.Execute(ClipperLib::ctIntersection, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
            if (i + 1 != operands.size()) {
                ClipperLib::PolyTreeToPaths(result, source);
                clipper.Clear();
            }
        }
        return fromTree(result);
    }
    // Few operands gain nothing from grouping (one pass over their boxes).
    if (op == FlatBoolean::Union && operands.size() >= 16) return groupedUnion(operands);
    bool first = true;
    for (const ClipperLib::Paths& paths : operands) {
        clipper.AddPaths(paths, first ? ClipperLib::ptSubject : ClipperLib::ptClip, true);
        first = false;
    }
    const ClipperLib::ClipType type = op == FlatBoolean::Union          ? ClipperLib::ctUnion
                                      : op == FlatBoolean::Intersection ? ClipperLib::ctIntersection
                                                                        : ClipperLib::ctDifference;
    clipper.Execute(type, result, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return fromTree(result);
}

Outlines offset(const Outlines& shape, double amount, FlatJoin join, double miterLimit, double arcTolerance) {
    const ClipperLib::JoinType type = join == FlatJoin::Round   ? ClipperLib::jtRound
                                      : join == FlatJoin::Miter ? ClipperLib::jtMiter
                                                                : ClipperLib::jtSquare;
    ClipperLib::ClipperOffset clipperOffset(miterLimit, arcTolerance * kClipperScale);
    clipperOffset.AddPaths(toPaths(shape), type, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree result;
    clipperOffset.Execute(result, amount * kClipperScale);
    return fromTree(result);
}

}  // namespace strata::flat
