#include "strata/model/Projection.h"

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "strata/flat/FlatClipper.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

// Follows OpenSCAD 2021.01's GeometryEvaluator::visit(ProjectionNode): the
// shadow through Clipper, triangle by triangle; the cut as the section of the
// result by z = 0 (there from the exact CGAL result, here leaf by leaf and
// combined as the tree combines them, which gives the same region).

namespace strata::model {

using mesh::Mesh;
using flat::Outline;
using flat::Outlines;

namespace {

Outlines shadowOf(const scene::Tree& tree, const Model& model) {
    std::vector<std::vector<std::array<glm::dvec2, 3>>> children;
    for (int child : tree.nodes[static_cast<std::size_t>(tree.root)].children) {
        std::vector<std::array<glm::dvec2, 3>> triangles;
        for (int l : tree.leavesUnder(child)) {
            const Mesh& mesh = model.leafMeshes[static_cast<std::size_t>(l)];
            for (const auto& t : mesh.triangles) {
                triangles.push_back({glm::dvec2(mesh.positions[t[0]]), glm::dvec2(mesh.positions[t[1]]),
                                     glm::dvec2(mesh.positions[t[2]])});
            }
        }
        children.push_back(std::move(triangles));
    }
    return flat::shadow(children);
}

// The closed loops where the plane z = 0 cuts a closed mesh, each running
// counter-clockwise around the solid's inside (holes clockwise).
Outlines section(const Mesh& mesh) {
    std::vector<glm::dvec2> points;
    std::unordered_map<std::uint64_t, int> onEdge;  // (lower, higher vertex) -> point
    std::unordered_map<uint32_t, int> onVertex;  // vertices lying on the plane
    auto crossing = [&](uint32_t a, uint32_t b) {
        // A vertex on the plane is the crossing itself, whichever edge reaches it.
        for (uint32_t v : {a, b}) {
            if (mesh.positions[v].z != 0.0) continue;
            const auto [it, added] = onVertex.emplace(v, static_cast<int>(points.size()));
            if (added) points.emplace_back(mesh.positions[v].x, mesh.positions[v].y);
            return it->second;
        }
        if (a > b) std::swap(a, b);  // the same point from both triangles of the edge
        const std::uint64_t key = (std::uint64_t(a) << 32) | b;
        const auto found = onEdge.find(key);
        if (found != onEdge.end()) return found->second;
        const glm::dvec3& p = mesh.positions[a];
        const glm::dvec3& q = mesh.positions[b];
        const double t = p.z / (p.z - q.z);
        points.emplace_back(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y));
        const int id = static_cast<int>(points.size()) - 1;
        onEdge.emplace(key, id);
        return id;
    };
    std::vector<std::pair<int, int>> segments;
    for (const auto& t : mesh.triangles) {
        const bool above[3] = {mesh.positions[t[0]].z >= 0, mesh.positions[t[1]].z >= 0, mesh.positions[t[2]].z >= 0};
        if (above[0] == above[1] && above[1] == above[2]) continue;
        int ends[2];
        int k = 0;
        for (int e = 0; e < 3; ++e) {
            const int f = (e + 1) % 3;
            if (above[e] != above[f]) ends[k++] = crossing(t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>(f)]);
        }
        // The solid lies to the left of the cut, walking along z x normal.
        const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
        const glm::dvec2 along(-n.y, n.x);
        const glm::dvec2 d = points[static_cast<std::size_t>(ends[1])] - points[static_cast<std::size_t>(ends[0])];
        if (glm::dot(d, along) >= 0) segments.emplace_back(ends[0], ends[1]);
        else segments.emplace_back(ends[1], ends[0]);
    }
    // Chain the segments into loops.
    std::unordered_multimap<int, std::size_t> from;
    for (std::size_t i = 0; i < segments.size(); ++i) from.emplace(segments[i].first, i);
    std::vector<bool> used(segments.size(), false);
    Outlines result;
    result.sanitized = true;  // orientations mean inside and hole
    for (std::size_t s = 0; s < segments.size(); ++s) {
        if (used[s]) continue;
        Outline loop;
        std::size_t at = s;
        for (;;) {
            used[at] = true;
            loop.points.push_back(points[static_cast<std::size_t>(segments[at].first)]);
            const int end = segments[at].second;
            if (end == segments[s].first) break;
            std::size_t next = segments.size();
            for (auto [it, last] = from.equal_range(end); it != last; ++it) {
                if (!used[it->second]) {
                    next = it->second;
                    break;
                }
            }
            if (next == segments.size()) {
                loop.points.clear();  // an open chain: not part of a closed section
                break;
            }
            at = next;
        }
        if (loop.points.size() >= 3) result.outlines.push_back(std::move(loop));
    }
    return result;
}

Outlines cutOf(const scene::Tree& tree, const Model& model) {
    // OpenSCAD cuts its exact result, so the section's corners are the
    // crossings themselves; Clipper's booleans between the leaves' sections
    // move them onto its grid. Corners that a boolean kept are put back where
    // they were; only the corners it made (where sections cross) stay on the grid.
    std::map<std::pair<std::int64_t, std::int64_t>, glm::dvec2> exact;
    auto restore = [&](Outlines o) {
        for (Outline& outline : o.outlines)
            for (glm::dvec2& p : outline.points) {
                const auto it = exact.find(flat::gridPoint(p));
                if (it != exact.end()) p = it->second;
            }
        return o;
    };
    // Children come after their parents: evaluate from the last node back.
    std::vector<Outlines> results(tree.nodes.size());
    for (std::size_t i = tree.nodes.size(); i-- > 0;) {
        const scene::Node& n = tree.nodes[i];
        if (n.kind == scene::NodeKind::Leaf) {
            const Outlines cut = section(model.leafMeshes[static_cast<std::size_t>(n.leaf)]);
            for (const Outline& o : cut.outlines)
                for (const glm::dvec2& p : o.points) exact.emplace(flat::gridPoint(p), p);
            results[i] = flat::apply({&cut}, flat::FlatBoolean::Union);
            continue;
        }
        std::vector<const Outlines*> operands;
        for (int c : n.children) operands.push_back(&results[static_cast<std::size_t>(c)]);
        const flat::FlatBoolean op = n.kind == scene::NodeKind::Intersection ? flat::FlatBoolean::Intersection
                                       : n.kind == scene::NodeKind::Difference ? flat::FlatBoolean::Difference
                                                                               : flat::FlatBoolean::Union;
        results[i] = operands.empty() ? Outlines{} : flat::apply(operands, op);
    }
    return restore(std::move(results[static_cast<std::size_t>(tree.root)]));
}

}  // namespace

Outlines project(const scene::Projection& projection) {
    if (!projection.solid || projection.solid->root < 0) return {};
    const scene::Tree& tree = *projection.solid;
    const Model model = buildModel(tree);
    return projection.cut ? cutOf(tree, model) : shadowOf(tree, model);
}

}  // namespace strata::model
