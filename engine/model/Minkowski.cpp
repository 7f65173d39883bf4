#include "strata/model/Minkowski.h"

#include <string>
#include <variant>
#include <vector>

#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/exact/Exact.h"
#include "strata/exact/ResultCache.h"
#include "strata/model/Hull.h"
#include "strata/model/Model.h"

namespace strata::model {

using mesh::Mesh;
using exact::exactUnion;

namespace {

constexpr std::size_t kMaxHulls = 4096;

using Part = std::vector<glm::dvec3>;

// An operand's solid leaves in world space: 2D objects among them take no
// part (the parser has warned of them), nor do empty ones.
std::vector<const Mesh*> solidMeshes(const scene::Tree& operand, const Model& model) {
    std::vector<const Mesh*> meshes;
    for (int l : operand.leavesUnder(operand.root)) {
        if (std::holds_alternative<scene::FlatSlab>(operand.leaves[static_cast<std::size_t>(l)].primitive)) continue;
        const Mesh& mesh = model.leafMeshes[static_cast<std::size_t>(l)];
        if (!mesh.triangles.empty()) meshes.push_back(&mesh);
    }
    return meshes;
}

}  // namespace

Mesh minkowskiSum(const scene::MinkowskiSum& sum) {
    // An operand is the union of its leaves, and a sum distributes over a
    // union: its parts are its leaves' parts.
    std::vector<Model> models;
    models.reserve(sum.operands.size());  // operands point into the models
    std::vector<std::vector<const Mesh*>> operands;
    exact::ContentKey key;
    key.mix(0x6d696e6b6f77736bull);  // "minkowsk": apart from exactResult's keys
    for (const auto& operand : sum.operands) {
        models.push_back(buildModel(*operand));
        std::vector<const Mesh*> meshes = solidMeshes(*operand, models.back());
        // OpenSCAD leaves an empty operand out of the sum (an empty
        // intersection, a cube of size 0), rather than making the sum empty.
        if (meshes.empty()) continue;
        operands.push_back(std::move(meshes));
        key.mix(operands.back().size());
        for (const Mesh* m : operands.back()) key.mix(*m);
    }
    if (operands.empty()) return Mesh{};
    // The sum of one solid is that solid, as OpenSCAD's applyMinkowski
    // returns a lone child untouched: not cut into convex parts and united
    // again (minutes for a turned extrusion that CGAL's corefinement balks at).
    if (operands.size() == 1 && operands[0].size() == 1) return *operands[0][0];
    if (std::optional<Mesh> known = exact::cachedResult(key.value())) return std::move(*known);

    std::vector<std::vector<Part>> parts(operands.size());
    std::size_t hulls = 1;
    std::size_t meshes = 0, split = 0;
    for (const auto& operand : operands) meshes += operand.size();
    for (std::size_t i = 0; i < operands.size(); ++i) {
        for (const Mesh* m : operands[i]) {
            reportProgress("minkowski: convex parts", split++, meshes);
            for (Part& p : exact::convexParts(*m, SourceLocation{})) parts[i].push_back(std::move(p));
        }
        hulls *= parts[i].size();
        if (parts[i].empty()) return Mesh{};
        if (hulls > kMaxHulls) {
            throw Error("minkowski: the convex parts of its operands make more than " + std::to_string(kMaxHulls) +
                        " sums");
        }
    }
    // One hull per choice of a part from each operand.
    std::vector<Mesh> pieces;
    std::vector<std::size_t> choice(parts.size(), 0);
    for (std::size_t k = 0; k < hulls; ++k) {
        reportProgress("minkowski: hulls", k, hulls);
        Part points = parts[0][choice[0]];
        for (std::size_t i = 1; i < parts.size(); ++i) points = pointSums(points, parts[i][choice[i]]);
        Mesh piece = convexHull(points);
        if (!piece.triangles.empty()) pieces.push_back(std::move(piece));
        for (std::size_t i = 0; i < parts.size() && ++choice[i] == parts[i].size(); ++i) choice[i] = 0;
    }
    Mesh result = pieces.size() == 1 ? std::move(pieces.front()) : exactUnion(std::move(pieces), SourceLocation{});
    exact::keepResult(key.value(), result);
    return result;
}

}  // namespace strata::model
