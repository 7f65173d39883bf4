#include "ExportParts.h"

#include <algorithm>
#include <cmath>

#include "strata/core/Error.h"
#include "strata/exact/Exact.h"
#include "strata/io/ExportFormats.h"
#include "strata/io/FlatWriter.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/FlatEvaluation.h"

namespace strata::exporting {

// The exact result as every file holds it: points rounded to single
// precision, what STL and 3MF keep (OFF and OBJ get the same points, so
// every format carries one mesh). Exact corners closer together than a
// rounding step (at a seam where curved faces meet at a shallow angle, or
// faces flush before a rotation that are a hair apart after it) land on one
// point or on one line, and the triangles between them would have no area
// or cross their neighbours: such points become one vertex, and triangles
// without area are removed with the mesh kept closed (dropDegenerateTriangles).
void roundForFile(mesh::Mesh& mesh) {
    // Component by component: GCC 12 at -O3 dropped the rounding of x and y
    // when the vector was rebuilt from floats in one expression.
    for (glm::dvec3& p : mesh.positions) {
        for (int k = 0; k < 3; ++k) p[k] = static_cast<double>(static_cast<float>(p[k]));
    }
    mesh::dropDegenerateTriangles(mesh);
    // Rounding can bring points together or change their order, and a
    // result that does not come through the exact room's conversion (a
    // hull's) comes in its library's order: the file is put in the order of
    // what it holds, so that one result is one file.
    mesh::canonicalOrder(mesh);
}

io::StagedFile stageFlatExport(const scene::Tree& tree, const std::string& path) {
    if (!tree.isFlat()) {
        throw Error(SourceLocation{tree.source, 0, 0},
                    "a 3D model has no 2D drawing to export (export it as " + io::extensionList(io::ExportKind::Mesh) + ")");
    }
    const flat::Outlines outlines = model::flatResult(tree);
    if (outlines.empty()) throw Error(SourceLocation{tree.source, 0, 0}, "the 2D result is empty: nothing to export");
    return io::stageFlat(path, outlines);
}

StagedExport stageExactMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                            const glm::vec4& faceColor) {
    requireSolidModel(tree);
    mesh::Mesh result;
    if (tree.root >= 0) result = exact::exactResult(tree, tree.root, model.leafMeshes, model::objectMesh);
    roundForFile(result);
    // Rounded, a triangle lies within a few float steps of its leaf's face,
    // no longer on it: colours are found within that reach.
    double largest = 0.0;
    for (const glm::dvec3& p : result.positions) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const double reach = std::ldexp(largest, -21);
    StagedExport out;
    out.file = stageResultMesh(tree, model, path, result, faceColor, reach);
    out.triangles = result.triangles.size();
    return out;
}

}  // namespace strata::exporting
