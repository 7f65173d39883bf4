#include "strata/model/Hull.h"

#include <cstdio>
#include <memory>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <glm/geometric.hpp>

#include "strata/core/Error.h"
#include "strata/model/Model.h"

namespace strata::model {

using mesh::Mesh;

namespace {

constexpr std::size_t kMaxHullPoints = std::size_t(1) << 24;

// Qhull's state, freed however the call ends.
class Qhull {
public:
    Qhull() {
        // Qhull writes its diagnostics to a FILE*: keep them in memory, out of the user's terminal.
        errors_ = open_memstream(&errorText_, &errorSize_);
        qh_zero(&qh_, errors_);
    }
    ~Qhull() {
        qh_freeqhull(&qh_, !qh_ALL);
        int curlong = 0, totlong = 0;
        qh_memfreeshort(&qh_, &curlong, &totlong);
        if (errors_ != nullptr) std::fclose(errors_);
        std::free(errorText_);
    }
    Qhull(const Qhull&) = delete;
    Qhull& operator=(const Qhull&) = delete;

    qhT* get() { return &qh_; }
    FILE* errors() { return errors_; }

private:
    qhT qh_{};
    FILE* errors_ = nullptr;
    char* errorText_ = nullptr;
    std::size_t errorSize_ = 0;
};

[[noreturn]] void tooManyHullPoints(std::size_t count) {
    throw Error("hull: too many points (" + std::to_string(count) + ", at most " + std::to_string(kMaxHullPoints) + ")");
}

}  // namespace

Mesh convexHull(const std::vector<glm::dvec3>& points) {
    Mesh mesh;
    if (points.size() < 4) return mesh;
    if (points.size() > kMaxHullPoints) tooManyHullPoints(points.size());
    std::vector<coordT> coords;
    coords.reserve(points.size() * 3);
    for (const glm::dvec3& p : points) coords.insert(coords.end(), {p.x, p.y, p.z});

    Qhull q;
    qhT* qh = q.get();
    // Qt: triangulated facets; no joggle, so every corner is an input point.
    char options[] = "qhull Qt";
    const int status =
        qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr, q.errors());
    if (status != 0) return mesh;  // flat or degenerate input: no volume

    // Corners are input points: keep them by index, renumbered in order of use.
    std::vector<int> index(points.size(), -1);
    facetT* facet = nullptr;
    FORALLfacets {
        if (facet->upperdelaunay) continue;
        std::array<uint32_t, 3> tri{};
        int k = 0;
        vertexT* vertex = nullptr;
        vertexT** vertexp = nullptr;
        FOREACHvertex_(facet->vertices) {
            if (k == 3) break;
            const int id = qh_pointid(qh, vertex->point);
            if (id < 0 || static_cast<std::size_t>(id) >= points.size()) continue;
            if (index[static_cast<std::size_t>(id)] < 0) {
                index[static_cast<std::size_t>(id)] = static_cast<int>(mesh.positions.size());
                mesh.positions.push_back(points[static_cast<std::size_t>(id)]);
            }
            tri[static_cast<std::size_t>(k++)] = static_cast<uint32_t>(index[static_cast<std::size_t>(id)]);
        }
        if (k != 3) continue;
        // Counter-clockwise seen from outside: along the facet's outward normal.
        const glm::dvec3 n = glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                                        mesh.positions[tri[2]] - mesh.positions[tri[0]]);
        const glm::dvec3 outward(facet->normal[0], facet->normal[1], facet->normal[2]);
        if (glm::dot(n, outward) < 0.0) std::swap(tri[1], tri[2]);
        mesh.triangles.push_back(tri);
    }
    return mesh;
}

Mesh tessellate(const scene::Hull& hull) {
    std::vector<glm::dvec3> points;
    for (const scene::Leaf& part : hull.parts) {
        const Mesh m = leafMesh(part);
        // Refused as soon as the parts made so far pass the budget, before
        // the rest are made.
        if (m.positions.size() > kMaxHullPoints - points.size()) tooManyHullPoints(points.size() + m.positions.size());
        points.insert(points.end(), m.positions.begin(), m.positions.end());
    }
    for (const scene::Leaf& summand : hull.summands) {
        const Mesh m = leafMesh(summand);
        // A part that makes no mesh adds nothing to its operand's union (the
        // parser leaves out parts and operands empty by their parameters).
        if (m.positions.empty()) return Mesh{};
        points = pointSums(points, m.positions);
    }
    return convexHull(points);
}

std::vector<glm::dvec3> pointSums(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
    if (!b.empty() && a.size() > kMaxHullPoints / b.size()) {
        throw Error("minkowski: too many points (" + std::to_string(a.size()) + " x " + std::to_string(b.size()) + ")");
    }
    std::vector<glm::dvec3> sums;
    sums.reserve(a.size() * b.size());
    for (const glm::dvec3& p : a)
        for (const glm::dvec3& q : b) sums.push_back(p + q);
    return sums;
}

}  // namespace strata::model
