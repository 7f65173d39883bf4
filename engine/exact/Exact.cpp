#include "strata/exact/Exact.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <deque>
#include <iterator>
#include <mutex>
#include <optional>
#include <vector>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/assertions.h>

namespace strata::exact::detail {
// CGAL's checks are on in this file (CMakeLists.txt), all but one: after
// corefinement has triangulated each face cut by the other solid, it
// asserts that the whole constrained Delaunay triangulation is valid, which
// tests every edge's circle and, on nearly cocircular points (a gear's
// many-sided caps), in exact arithmetic: three quarters of the gear's exact
// export. That triangulation is built with exact predicates; its own checks
// as it is built stay on, as do corefinement's checks of its input and of
// the result it assembles.
constexpr bool skippedCgalCheck(std::string_view expression) { return expression == "cdt.is_valid()"; }
}  // namespace strata::exact::detail

#pragma push_macro("CGAL_assertion")
#undef CGAL_assertion
#define CGAL_assertion(EX)                                                                                   \
    ((::strata::exact::detail::skippedCgalCheck(#EX) || CGAL::possibly(EX)) ? static_cast<void>(0)      \
                                                                                : ::CGAL::assertion_fail(#EX, __FILE__, __LINE__))
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#pragma pop_macro("CGAL_assertion")
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/boost/graph/copy_face_graph.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include "CoplanarFaces.h"
#include "strata/exact/ResultCache.h"
#include "NefPolyhedra.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"

namespace strata::exact {

using mesh::Bounds;
using mesh::Mesh;
using mesh::boundsOf;
using mesh::canonicalOrder;
using mesh::transformed;

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Solid = detail::ExactSolid;
using detail::Boolean;
namespace PMP = CGAL::Polygon_mesh_processing;

// Whether the closed solid's signed volume is zero. Summed first over the
// points' intervals, which decides every solid of some size at once; only
// where that sum's interval holds zero is the volume summed exactly (which
// on a result of 50,000 triangles takes seconds).
bool zeroVolume(const Solid& s) {
    using Interval = CGAL::Interval_nt<true>;
    Interval sixTimes = 0;
    for (const auto f : s.faces()) {
        std::array<std::array<Interval, 3>, 3> corner;
        std::size_t i = 0;
        for (const auto v : CGAL::vertices_around_face(s.halfedge(f), s)) {
            const Kernel::Point_3& p = s.point(v);
            corner[i++] = {CGAL::to_interval(p.x()), CGAL::to_interval(p.y()), CGAL::to_interval(p.z())};
        }
        const auto& [a, b, c] = corner;
        sixTimes += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    if (!sixTimes.do_overlap(Interval(0))) return false;
    return PMP::volume(s) == 0;
}

// A closed mesh that encloses nothing (faces back to back, as a polyhedron
// whose points coincide makes) is the empty solid: the booleans are
// regularized, and CGAL's Nef overlay is not defined on such a mesh.
// (An open mesh encloses no volume CGAL can measure: it is left to the Nef
// conversion, which refuses it with one line.)
bool enclosesNothing(const Solid& s) { return s.number_of_faces() > 0 && CGAL::is_closed(s) && zeroVolume(s); }

// Carries each face's source (CoplanarFaces.h) through corefinement: the
// pieces of a split face and the faces copied into the result keep it, so
// that the join knows them coplanar without an exact test.
struct SourceKeeper : PMP::Corefinement::Default_visitor<Solid> {
    std::uint64_t splitting = 0;
    static std::uint64_t of(const Solid& tm, Solid::Face_index f) {
        const auto [map, found] = tm.property_map<Solid::Face_index, std::uint64_t>(detail::kFaceSource);
        return found ? map[f] : 0;
    }
    static void set(Solid& tm, Solid::Face_index f, std::uint64_t source) {
        tm.add_property_map<Solid::Face_index, std::uint64_t>(detail::kFaceSource, 0).first[f] = source;
    }
    void before_subface_creations(Solid::Face_index f, Solid& tm) { splitting = of(tm, f); }
    void after_subface_created(Solid::Face_index f, Solid& tm) { set(tm, f, splitting); }
    void after_face_copy(Solid::Face_index from, const Solid& source, Solid::Face_index to, Solid& target) {
        set(target, to, of(source, from));
    }
};

// `from`'s faces added to `to`, each with its source.
void appendSolid(const Solid& from, Solid& to) {
    std::vector<std::pair<Solid::Face_index, Solid::Face_index>> copied;
    CGAL::copy_face_graph(from, to, CGAL::parameters::face_to_face_output_iterator(std::back_inserter(copied)));
    for (const auto& [source, target] : copied) SourceKeeper::set(to, target, SourceKeeper::of(from, source));
}

// A boolean's result whose triangles outnumber its operands' by a fifth
// was cut into pieces along coplanar faces (bars of a Menger sponge
// flush with each other); joined before the next boolean, which then
// works on the faces rather than the pieces (the sponge's largest union:
// 34,864 triangles, 14,372 joined). Results that grew less (a ball
// taken out of a block) are left: joining them at every step of a long
// chain would cost more than it saves.
Solid joinedIfCut(Solid result, std::size_t operandFaces) {
    if (result.number_of_faces() <= operandFaces + operandFaces / 5) return result;
    try {
        return detail::joinedCoplanarFaces(result);
    } catch (const std::exception&) {
        return result;  // joined, or joined through a Nef polyhedron, at the end
    }
}

// a OP b. Corefinement first (fast); where it fails on a degenerate
// configuration (CGAL's checks are on: a failed one throws) or cannot build
// a closed result, Nef polyhedra, which take every configuration but a
// solid that encloses nothing, taken as empty there.
Solid combine(Solid a, Solid b, Boolean op, const SourceLocation& where) {
    // Apart: nothing to compute. The boxes of the points' interval
    // approximations hold the exact points, so boxes that do not even touch
    // mean solids that do not.
    if (a.number_of_faces() == 0 || b.number_of_faces() == 0 ||
        !CGAL::do_overlap(PMP::bbox(a), PMP::bbox(b))) {
        if (op == Boolean::Intersection) return Solid{};
        if (op == Boolean::Difference) return a;
        if (a.number_of_faces() == 0) return b;
        appendSolid(b, a);  // two closed solids apart: one mesh of both
        return a;
    }
    const Solid a0 = a, b0 = b;  // corefinement rewrites its operands
    const std::size_t faces = a.number_of_faces() + b.number_of_faces();
    Solid out;
    try {
        bool ok = false;
        const auto keep = CGAL::parameters::visitor(SourceKeeper{});
        if (op == Boolean::Difference) ok = PMP::corefine_and_compute_difference(a, b, out, keep);
        else if (op == Boolean::Intersection) ok = PMP::corefine_and_compute_intersection(a, b, out, keep);
        else ok = PMP::corefine_and_compute_union(a, b, out, keep);
        // Where the result touches itself at a corner (a tetrahedron less a
        // cube that holds its apex leaves parts meeting at single points),
        // CGAL reports success with a vertex shared by two parts, which a
        // halfedge mesh cannot hold: the next boolean or conversion would
        // crash on it. Each part gets its own copy of such a vertex.
        if (ok && !CGAL::is_valid_polygon_mesh(out)) {
            PMP::duplicate_non_manifold_vertices(out);
            ok = CGAL::is_valid_polygon_mesh(out);
        }
        // A result that is not a closed mesh is a failure too: Nef
        // polyhedra do that boolean again.
        if (ok && CGAL::is_closed(out)) return joinedIfCut(std::move(out), faces);
    } catch (const std::exception&) {
        // Fall through to the slower, robust way.
    }
    // Only here is the exact volume worth its cost (a few per cent of a
    // whole export when asked at every boolean).
    const bool aEmpty = enclosesNothing(a0), bEmpty = enclosesNothing(b0);
    if (aEmpty || bEmpty) return combine(aEmpty ? Solid{} : a0, bEmpty ? Solid{} : b0, op, where);
    return detail::nefBoolean(a0, b0, op, where);
}

Solid toSolid(const Mesh& mesh, const SourceLocation& where) {
    Solid s = detail::toExactSolid(mesh, where, "an exact evaluation");
    detail::giveFacesSources(s);
    return s;
}

// Primitives whose object-space mesh is cheap to make again.
bool remakeable(const scene::Primitive& p) {
    return std::holds_alternative<scene::Cube>(p) || std::holds_alternative<scene::Sphere>(p) ||
           std::holds_alternative<scene::Cylinder>(p) || std::holds_alternative<scene::Polyhedron>(p) ||
           std::holds_alternative<scene::LinearExtrude>(p) || std::holds_alternative<scene::RotateExtrude>(p);
}

// A leaf's multmatrix() steps, outermost first.
using Chain = std::vector<const scene::TransformStep*>;

// The leaf's multmatrix() chain, when its product in doubles (as the parser
// multiplied it) is the leaf's transform bit for bit.
std::optional<Chain> checkedChain(const scene::Leaf& leaf) {
    Chain chain;
    for (const scene::TransformStep* s = leaf.steps.get(); s != nullptr; s = s->previous.get()) chain.push_back(s);
    std::reverse(chain.begin(), chain.end());
    glm::dmat4 product(1.0);
    for (const scene::TransformStep* s : chain) product = product * s->matrix;
    if (product != leaf.transform) return std::nullopt;
    return chain;
}

using ET = Kernel::FT::ET;

// The sign of a step's 3x3 determinant, exactly.
int determinantSign(const glm::dmat4& m) {
    auto at = [&](int col, int row) { return ET(m[col][row]); };
    const ET det = at(0, 0) * (at(1, 1) * at(2, 2) - at(2, 1) * at(1, 2)) -
                   at(1, 0) * (at(0, 1) * at(2, 2) - at(2, 1) * at(0, 2)) +
                   at(2, 0) * (at(0, 1) * at(1, 2) - at(1, 1) * at(0, 2));
    return CGAL::sign(det);
}

// `q` moved by `m` (the bottom row ignored), exactly.
std::array<ET, 3> moved(const glm::dmat4& m, const std::array<ET, 3>& q) {
    std::array<ET, 3> next;
    for (int i = 0; i < 3; ++i)
        next[static_cast<std::size_t>(i)] = ET(m[0][i]) * q[0] + ET(m[1][i]) * q[1] + ET(m[2][i]) * q[2] + ET(m[3][i]);
    return next;
}

// Whether the leaf's solid can be made from its object-space mesh and its
// chain: the checked world-space mesh is exactly the object mesh moved by
// the transform (nothing was cleaned away), and the transform is exactly
// the product of its chain.
std::optional<Chain> exactChain(const scene::Leaf& leaf, const Mesh& world, const ObjectMesh& objectMesh) {
    if (!leaf.steps || !remakeable(leaf.primitive)) return std::nullopt;
    std::optional<Chain> chain = checkedChain(leaf);
    if (!chain) return std::nullopt;
    const Mesh moved = transformed(objectMesh(leaf.primitive), leaf.transform);
    if (moved.positions != world.positions || moved.triangles != world.triangles) return std::nullopt;
    return chain;
}

// The outer steps of a transform chain that a subtree is evaluated under:
// its results are made in the frame inside them and moved out through them
// once. Steps of the chain from `parent` (exclusive) to `step` (inclusive).
struct Frame {
    const scene::TransformStep* step = nullptr;  // the innermost step factored out; null: none
    std::size_t depth = 0;                       // how many steps, from the outermost
};

// A leaf's solid with exact points (`chain`: its exactChain), in the frame
// `frame` (the outermost `frame.depth` steps of its chain left out). The
// checked world-space mesh is the leaf's object-space mesh moved by its
// transform, rounded to doubles at every point; leaves under one rotation,
// flush before it, are then a rounding apart after it, and the exact
// result keeps those slivers. So
// where the leaf has an exact chain, each object-space point is moved by the
// chain's matrices one by one in exact arithmetic instead, as OpenSCAD
// transforms results: faces flush in a frame stay flush. Elsewhere (only in
// the world frame) the world mesh as it is.
Solid leafSolid(const scene::Leaf& leaf, const std::optional<Chain>& chain, const Mesh& world, const SourceLocation& where,
                Frame frame, const ObjectMesh& objectMesh) {
    if (!chain) return toSolid(world, where);
    Mesh object = objectMesh(leaf.primitive);
    int sign = 1;
    for (std::size_t i = frame.depth; i < chain->size(); ++i) sign *= determinantSign((*chain)[i]->matrix);
    if (sign < 0)
        for (auto& t : object.triangles) std::swap(t[1], t[2]);
    std::vector<Kernel::Point_3> points;
    points.reserve(object.positions.size());
    for (const glm::dvec3& p : object.positions) {
        std::array<ET, 3> q{ET(p.x), ET(p.y), ET(p.z)};
        for (std::size_t i = chain->size(); i-- > frame.depth;) q = moved((*chain)[i]->matrix, q);
        points.emplace_back(Kernel::FT(q[0]), Kernel::FT(q[1]), Kernel::FT(q[2]));
    }
    Solid s = detail::toExactSolid(points, object, where, "an exact evaluation");
    detail::giveFacesSources(s);
    return s;
}

// How the subtree under a root is evaluated: each leaf's exact chain, found
// once, and the frame of each node, the longest chain of steps all its
// leaves share, stopping before a step that flattens space (a flat solid
// has no frame to be moved out of). A leaf without an exact chain gives
// every node above it the world frame.
struct Frames {
    std::unordered_map<int, std::optional<Chain>> chainOfLeaf;  // by leaf index
    std::unordered_map<int, Frame> ofNode;                      // by node index
};

Frames frames(const scene::Tree& tree, int root, const std::vector<Mesh>& leafMeshes, const ObjectMesh& objectMesh) {
    auto meet = [](Frame a, Frame b) {
        if (a.step == nullptr || b.step == nullptr) return Frame{};
        for (; a.depth > b.depth; --a.depth) a.step = a.step->previous.get();
        for (; b.depth > a.depth; --b.depth) b.step = b.step->previous.get();
        for (; a.step != b.step; --a.depth) {
            a.step = a.step->previous.get();
            b.step = b.step->previous.get();
        }
        return a.step == nullptr ? Frame{} : a;
    };
    Frames out;
    // Children before parents: a node is finished when it is met the second time.
    std::vector<std::pair<int, bool>> todo{{root, false}};
    while (!todo.empty()) {
        const auto [index, childrenDone] = todo.back();
        todo.pop_back();
        const scene::Node& n = tree.nodes[static_cast<std::size_t>(index)];
        if (n.kind == scene::NodeKind::Leaf) {
            auto found = out.chainOfLeaf.find(n.leaf);
            if (found == out.chainOfLeaf.end()) {
                found = out.chainOfLeaf
                            .emplace(n.leaf, exactChain(tree.leaves[static_cast<std::size_t>(n.leaf)],
                                                        leafMeshes[static_cast<std::size_t>(n.leaf)], objectMesh))
                            .first;
            }
            Frame f;
            if (const std::optional<Chain>& chain = found->second) {
                while (f.depth < chain->size() && determinantSign((*chain)[f.depth]->matrix) != 0) f.step = (*chain)[f.depth++];
            }
            out.ofNode[index] = f;
        } else if (!childrenDone) {
            todo.emplace_back(index, true);
            for (int child : n.children) todo.emplace_back(child, false);
        } else {
            Frame f = n.children.empty() ? Frame{} : out.ofNode.at(n.children.front());
            for (int child : n.children) f = meet(f, out.ofNode.at(child));
            out.ofNode[index] = f;
        }
    }
    return out;
}

// The solid, made in the frame `inner`, moved out to the frame `outer`
// around it: each point through the steps between, in exact arithmetic.
void moveOut(Solid& solid, Frame inner, Frame outer) {
    std::vector<const glm::dmat4*> steps;  // innermost first
    int sign = 1;
    for (const scene::TransformStep* s = inner.step; steps.size() < inner.depth - outer.depth; s = s->previous.get()) {
        steps.push_back(&s->matrix);
        sign *= determinantSign(s->matrix);
    }
    if (steps.empty()) return;
    for (const auto v : solid.vertices()) {
        const Kernel::Point_3& p = solid.point(v);
        std::array<ET, 3> q{p.x().exact(), p.y().exact(), p.z().exact()};
        for (const glm::dmat4* m : steps) q = moved(*m, q);
        solid.point(v) = Kernel::Point_3(Kernel::FT(q[0]), Kernel::FT(q[1]), Kernel::FT(q[2]));
    }
    if (sign < 0) PMP::reverse_face_orientations(solid);
}

Mesh toMesh(Solid& s) {
    PMP::triangulate_faces(s);
    Mesh mesh;
    std::vector<uint32_t> index(s.number_of_vertices() + s.number_of_removed_vertices(), 0);
    for (const Solid::Vertex_index v : s.vertices()) {
        const Kernel::Point_3& p = s.point(v);
        index[v] = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
    for (const Solid::Face_index f : s.faces()) {
        std::array<uint32_t, 3> tri{};
        int k = 0;
        for (const Solid::Vertex_index v : CGAL::vertices_around_face(s.halfedge(f), s)) {
            if (k < 3) tri[static_cast<std::size_t>(k)] = index[v];
            ++k;
        }
        if (k == 3) mesh.triangles.push_back(tri);
    }
    canonicalOrder(mesh);
    return mesh;
}

// The subtree's content: its operations in order and its leaves' meshes, bit
// for bit.
std::uint64_t contentKey(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes) {
    ContentKey key;
    std::vector<int> todo{node};
    while (!todo.empty()) {
        const scene::Node& n = tree.nodes[static_cast<std::size_t>(todo.back())];
        todo.pop_back();
        key.mix(static_cast<std::uint64_t>(n.kind) + 0x9e37ull * n.children.size());
        if (n.kind == scene::NodeKind::Leaf) key.mix(leafMeshes[static_cast<std::size_t>(n.leaf)]);
        todo.insert(todo.end(), n.children.rbegin(), n.children.rend());
    }
    return key.value();
}

// Results by content, oldest dropped first past the budget.
class ResultCache {
public:
    std::optional<Mesh> find(std::uint64_t key) {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = entries_.find(key);
        if (it == entries_.end()) return std::nullopt;
        ++hits_;
        return it->second;
    }
    void add(std::uint64_t key, const Mesh& mesh) {
        std::lock_guard<std::mutex> lock(mutex_);
        const std::size_t bytes = mesh.positions.size() * sizeof(glm::dvec3) + mesh.triangles.size() * 12;
        if (bytes > kBudget || !entries_.emplace(key, mesh).second) return;
        order_.push_back({key, bytes});
        bytes_ += bytes;
        while (bytes_ > kBudget && !order_.empty()) {
            entries_.erase(order_.front().first);
            bytes_ -= order_.front().second;
            order_.pop_front();
        }
    }
    std::size_t hits() {
        std::lock_guard<std::mutex> lock(mutex_);
        return hits_;
    }

private:
    static constexpr std::size_t kBudget = std::size_t(256) << 20;
    std::mutex mutex_;
    std::unordered_map<std::uint64_t, Mesh> entries_;
    std::deque<std::pair<std::uint64_t, std::size_t>> order_;
    std::size_t bytes_ = 0;
    std::size_t hits_ = 0;
};

ResultCache& cache() {
    static ResultCache instance;
    return instance;
}

// Booleans done and to do in one exact evaluation, for progress reports.
struct Steps {
    std::size_t done = 0;
    std::size_t total = 0;
};

Solid evaluate(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes, const ObjectMesh& objectMesh,
               Steps& steps);

// How many booleans the subtree takes: one per child after the first.
std::size_t booleansUnder(const scene::Tree& tree, int node) {
    std::size_t count = 0;
    std::vector<int> todo{node};
    while (!todo.empty()) {
        const scene::Node& n = tree.nodes[static_cast<std::size_t>(todo.back())];
        todo.pop_back();
        if (n.children.size() > 1) count += n.children.size() - 1;
        todo.insert(todo.end(), n.children.begin(), n.children.end());
    }
    return count;
}

// Whether the union's children lie in boxes (of their leaves' meshes) that
// are apart by more than rounding: no two can touch, so their union is the
// children side by side. Boxes closer than 2^-30 of the scene's size count as
// meeting: a leaf's exact points may lie a rounding away from its mesh's.
bool partsApart(const scene::Tree& tree, const scene::Node& n, const std::vector<Mesh>& leafMeshes) {
    if (n.children.size() < 2) return false;
    std::vector<Bounds> boxes;
    Bounds all;
    for (int child : n.children) {
        Bounds box;
        for (int l : tree.leavesUnder(child)) box.extend(boundsOf(leafMeshes[static_cast<std::size_t>(l)]));
        if (box.empty()) return false;  // nothing there to place: leave it to the evaluation
        all.extend(box);
        boxes.push_back(box);
    }
    const double reach = std::ldexp(all.diagonal(), -30);
    std::sort(boxes.begin(), boxes.end(), [](const Bounds& a, const Bounds& b) { return a.min.x < b.min.x; });
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < boxes.size() && boxes[j].min.x <= boxes[i].max.x + reach; ++j) {
            bool meet = true;
            for (int k = 0; k < 3; ++k)
                meet = meet && boxes[j].min[k] <= boxes[i].max[k] + reach && boxes[i].min[k] <= boxes[j].max[k] + reach;
            if (meet) return false;
        }
    }
    return true;
}

}  // namespace

void ContentKey::mix(const Mesh& m) {
    mix(m.positions.size());
    for (const glm::dvec3& p : m.positions) {
        mix(std::bit_cast<std::uint64_t>(p.x));
        mix(std::bit_cast<std::uint64_t>(p.y));
        mix(std::bit_cast<std::uint64_t>(p.z));
    }
    for (const auto& t : m.triangles) mix((std::uint64_t(t[0]) << 42) ^ (std::uint64_t(t[1]) << 21) ^ t[2]);
}

std::optional<Mesh> cachedResult(std::uint64_t key) { return cache().find(key); }
void keepResult(std::uint64_t key, const Mesh& mesh) { cache().add(key, mesh); }

std::size_t exactCacheHits() { return cache().hits(); }

namespace {

// The node under a chain of nodes of one child each.
int belowSingleChildren(const scene::Tree& tree, int node) {
    while (tree.nodes[static_cast<std::size_t>(node)].children.size() == 1)
        node = tree.nodes[static_cast<std::size_t>(node)].children.front();
    return node;
}

// The solid with its runs of coplanar triangles joined into faces, and the
// points no face needs gone; through a Nef polyhedron where that fails (a
// result that touches itself at a point inside one of its faces).
Solid joined(const Solid& solid, const SourceLocation& where) {
    if (solid.number_of_faces() == 0 || zeroVolume(solid)) return Solid{};
    try {
        return detail::joinedCoplanarFaces(solid);
    } catch (const std::exception&) {
        return detail::simplified(solid, where);
    }
}

// The subtree's result through CGAL, kept by its content; a lone leaf (no
// boolean to evaluate) is its own checked mesh, as OpenSCAD writes a lone
// object's polygons without CGAL. (Through a Nef polyhedron, only to join
// coplanar triangles, a sphere of 256 fragments took 5 s.)
Mesh evaluatedResult(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes,
                     const ObjectMesh& objectMesh) {
    if (const scene::Node& n = tree.nodes[static_cast<std::size_t>(belowSingleChildren(tree, node))];
        n.kind == scene::NodeKind::Leaf) {
        Mesh mesh = leafMeshes[static_cast<std::size_t>(n.leaf)];
        canonicalOrder(mesh);
        return mesh;
    }
    const std::uint64_t key = contentKey(tree, node, leafMeshes);
    if (std::optional<Mesh> known = cache().find(key)) return std::move(*known);
    Steps steps{0, booleansUnder(tree, node)};
    Solid solid = joined(evaluate(tree, node, leafMeshes, objectMesh, steps), tree.nodes[static_cast<std::size_t>(node)].where);
    Mesh result = toMesh(solid);
    cache().add(key, result);
    return result;
}

}  // namespace

Mesh exactResult(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes, const ObjectMesh& objectMesh) {
    // A union of parts whose boxes are apart (a plate of separate parts): the
    // union is the parts side by side, each evaluated, and kept, alone. One
    // level only: a file's nesting never becomes recursion here.
    if (const scene::Node& n = tree.nodes[static_cast<std::size_t>(belowSingleChildren(tree, node))];
        n.kind == scene::NodeKind::Union && partsApart(tree, n, leafMeshes)) {
        Mesh all;
        for (int child : n.children) {
            const Mesh part = evaluatedResult(tree, child, leafMeshes, objectMesh);
            const auto base = static_cast<uint32_t>(all.positions.size());
            all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
            for (const auto& t : part.triangles) all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
        }
        canonicalOrder(all);
        return all;
    }
    return evaluatedResult(tree, node, leafMeshes, objectMesh);
}

Mesh exactUnion(std::vector<Mesh> solids, const SourceLocation& where) {
    if (solids.empty()) return Mesh{};
    // Pairwise, in rounds, so that each solid takes part in about log2(n)
    // corefinements rather than one ever-growing result taking all n.
    std::vector<Solid> round;
    round.reserve(solids.size());
    for (const Mesh& m : solids) round.push_back(toSolid(m, where));
    solids.clear();
    std::size_t done = 0;
    const std::size_t total = round.size() - 1;
    while (round.size() > 1) {
        std::vector<Solid> next;
        next.reserve((round.size() + 1) / 2);
        for (std::size_t i = 0; i + 1 < round.size(); i += 2) {
            reportProgress("exact union", done++, total);
            next.push_back(combine(std::move(round[i]), std::move(round[i + 1]), Boolean::Union, where));
        }
        if (round.size() % 2 == 1) next.push_back(std::move(round.back()));
        round = std::move(next);
    }
    return toMesh(round.front());
}

namespace {

// A union's or a difference's operands after the first, gathered into
// groups whose members' boxes are apart: a group's solids side by side are
// their union, so each group takes part in one boolean (a block less 256
// balls: a few dozen corefinements of the block, not 256). The boxes hold
// the interval approximations of the exact points, so solids in boxes
// that do not touch do not touch either.
struct ApartGroups {
    struct Group {
        Solid solid;
        std::vector<CGAL::Bbox_3> boxes;
    };
    std::vector<Group> groups;
    std::size_t empty = 0;  // operands that enclose nothing, left out

    void add(Solid s) {
        // A solid that encloses nothing adds nothing, and would make its
        // group's mesh one that corefinement cannot take.
        if (s.number_of_faces() == 0 || zeroVolume(s)) {
            ++empty;
            return;
        }
        const CGAL::Bbox_3 box = PMP::bbox(s);
        for (Group& g : groups) {
            if (std::none_of(g.boxes.begin(), g.boxes.end(), [&](const CGAL::Bbox_3& b) { return CGAL::do_overlap(b, box); })) {
                appendSolid(s, g.solid);
                g.boxes.push_back(box);
                return;
            }
        }
        groups.push_back(Group{std::move(s), {box}});
    }
};

// The operands of a node's boolean, in order: its children, but a
// difference takes the children of a union among its subtrahends in the
// union's place, down through unions of unions (a - (b + c) = a - b - c).
// The union is then never built: a block less groups of bars (the Menger
// sponge's) is cut by each group's bars in turn, the same solid 12 % sooner
// than cut by their union, whose corefinement meets every crossing of two
// bars, inside the block or not. The booleans are as many either way.
std::vector<int> operandsOf(const scene::Tree& tree, const scene::Node& n) {
    if (n.kind != scene::NodeKind::Difference || n.children.size() < 2) return n.children;
    std::vector<int> operands{n.children.front()};
    std::vector<int> todo(n.children.rbegin(), n.children.rend() - 1);  // the next subtrahend last
    while (!todo.empty()) {
        const int index = todo.back();
        todo.pop_back();
        const scene::Node& child = tree.nodes[static_cast<std::size_t>(index)];
        if (child.kind == scene::NodeKind::Union) todo.insert(todo.end(), child.children.rbegin(), child.children.rend());
        else operands.push_back(index);
    }
    return operands;
}

// The subtree's result, exact throughout: points are rounded to doubles only
// once, at the end (toMesh). Walks the subtree with an explicit stack of the
// operations under way, so a chain of any depth costs no C++ stack.
Solid evaluate(const scene::Tree& tree, int node, const std::vector<Mesh>& leafMeshes, const ObjectMesh& objectMesh,
               Steps& steps) {
    struct Pending {
        const scene::Node* node;
        std::vector<int> children;  // the boolean's operands (operandsOf)
        std::size_t next = 0;       // the operand to evaluate next
        Solid result;
        std::string what;
        Frame frame, outer;  // the frame the node's result is made in, and its parent's
        ApartGroups operands;  // a union's or difference's operands after the first
    };
    const Frames plan = frames(tree, node, leafMeshes, objectMesh);
    std::vector<Pending> stack;
    std::optional<Solid> done;  // the result of the node just finished
    auto enter = [&](int index, Frame outer) {
        const scene::Node& n = tree.nodes[static_cast<std::size_t>(index)];
        if (n.kind == scene::NodeKind::Leaf) {
            done = leafSolid(tree.leaves[static_cast<std::size_t>(n.leaf)], plan.chainOfLeaf.at(n.leaf),
                             leafMeshes[static_cast<std::size_t>(n.leaf)], n.where, outer, objectMesh);
            return;
        }
        stack.push_back(Pending{&n, operandsOf(tree, n), 0, Solid{}, std::string("exact ") + scene::kindName(n.kind),
                                plan.ofNode.at(index), outer, {}});
    };
    enter(node, Frame{});
    while (!stack.empty()) {
        Pending& top = stack.back();
        const scene::Node& n = *top.node;
        if (done) {
            // The result of operand top.next - 1.
            if (top.next == 1) {
                top.result = std::move(*done);
            } else if (n.kind == scene::NodeKind::Intersection) {
                reportProgress(top.what.c_str(), steps.done++, steps.total);
                top.result = combine(std::move(top.result), std::move(*done), Boolean::Intersection, n.where);
            } else {
                top.operands.add(std::move(*done));
            }
            done.reset();
        }
        if (top.next < top.children.size()) {
            enter(top.children[top.next++], top.frame);
            continue;
        }
        const Boolean op = n.kind == scene::NodeKind::Difference ? Boolean::Difference : Boolean::Union;
        steps.done += top.operands.empty;
        for (ApartGroups::Group& group : top.operands.groups) {
            reportProgress(top.what.c_str(), steps.done, steps.total);
            steps.done += group.boxes.size();
            top.result = combine(std::move(top.result), std::move(group.solid), op, n.where);
        }
        moveOut(top.result, top.frame, top.outer);
        done = std::move(top.result);
        stack.pop_back();
    }
    return std::move(*done);
}

}  // namespace
}  // namespace strata::exact
