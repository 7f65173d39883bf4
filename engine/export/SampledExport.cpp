#include "ExportParts.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "strata/camera/ViewBounds.h"
#include "strata/contour/Contour.h"
#include "strata/core/Error.h"
#include "strata/core/Timing.h"
#include "strata/exact/Crossings.h"
#include "strata/gpu/Context.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"

namespace strata::exporting {

namespace {

using Clock = std::chrono::steady_clock;

contour::Dexels sample(const scene::Tree& tree, const model::Model& model, const contour::DexelGrid& grid,
                       const ExportSettings& settings) {
    if (settings.reference) return remesh::sampleWithReference(reference::ReferenceScene(tree, model), grid);
    gpu::Context context;  // made first, destroyed last
    render::Renderer renderer;
    renderer.setScene(tree, model);
    // Auto peeling, whatever --layers says: a ray missing a layer would
    // lose changes of the result, and the mesh its surfaces.
    return remesh::sampleOnGpu(renderer, grid, render::RenderSettings{});
}

// Bytes a triangle of the export costs until the file is written: its share
// of the vertices (24 bytes each, about half a vertex per triangle), its
// indices (12), a colour where 3MF asks (16) and its encoding (50 in binary
// STL, up to about 60 in OFF or OBJ text).
constexpr double kBytesPerTriangle = 24.0 * 0.5 + 12.0 + 16.0 + 60.0;

// The memory this process may still take: the smaller of the machine's
// physical memory and its address-space limit (ulimit -v), halved for what
// else lives in it.
double memoryAtHand() {
    double bytes = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
    struct rlimit limit {};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        bytes = std::min(bytes, static_cast<double>(limit.rlim_cur));
    return bytes * 0.5;
}

// Each grid edge that changes sign holds one crossing and gives one quad,
// two triangles: the samples say how large the mesh will be before it is
// built. Refuses, naming the resolution, a mesh that would not fit.
void checkMeshFits(const contour::Dexels& dexels, int resolution, const SourceLocation& scene) {
    std::size_t crossings = 0;
    for (const contour::DexelRays& rays : dexels.axes) crossings += rays.crossings.size();
    const double triangles = 2.0 * static_cast<double>(crossings);
    const double bytes = triangles * kBytesPerTriangle;
    if (bytes > memoryAtHand()) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "export at %d cells would make about %.0f million triangles (%.1f GiB); "
                      "give a lower --export-resolution",
                      resolution, triangles / 1e6, bytes / (1024.0 * 1024.0 * 1024.0));
        throw Error(scene, text);
    }
}

// Refuses, in one line, an image whose grid is too coarse for a wall or a
// gap of the solid: the contour would lose it and still be closed.
void checkNothingBelowGrid(const contour::Dexels& dexels, int resolution, const SourceLocation& scene) {
    const std::optional<contour::FeatureBelowGrid> lost = contour::featureBelowGrid(dexels);
    if (!lost) return;
    // A grid whose cell is two thirds of the thinnest feature sees it on every ray.
    const double needed = std::ceil(1.5 * resolution * dexels.grid.spacing / lost->thickness);
    char text[400];
    const int n = std::snprintf(text, sizeof text,
                                "export: a %s %.3g %s near (%.4g, %.4g, %.4g) is thinner than a cell (%.3g at %d cells) "
                                "and would be %s; ",
                                lost->wall ? "wall" : "gap", lost->thickness, lost->wall ? "thick" : "wide", lost->where.x,
                                lost->where.y, lost->where.z, dexels.grid.spacing, resolution,
                                lost->wall ? "lost" : "filled");
    if (needed <= remesh::kMostResolution)
        std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n),
                      "give --export-resolution %.0f or more, or export the exact result (without --export-sampled)", needed);
    else
        std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n),
                      "no resolution up to %d sees it: export the exact result (without --export-sampled)",
                      remesh::kMostResolution);
    throw Error(scene, text);
}

// Where `written`, a contour as the file will hold it (roundForFile),
// crosses itself or has an edge that is not between exactly two triangles
// running it opposite ways: a box around each such place, for the contour
// to untangle.
std::vector<mesh::Bounds> tanglesIn(const mesh::Mesh& written) {
    const auto boxOf = [&](std::initializer_list<std::uint32_t> corners) {
        mesh::Bounds box;
        for (const std::uint32_t v : corners) box.extend(written.positions[v]);
        return box;
    };
    std::vector<mesh::Bounds> tangles;
    for (const auto& [a, b] : exact::crossingTriangles(written)) {
        const auto& ta = written.triangles[a];
        const auto& tb = written.triangles[b];
        mesh::Bounds box = boxOf({ta[0], ta[1], ta[2]});
        const mesh::Bounds other = boxOf({tb[0], tb[1], tb[2]});
        // They meet where their boxes overlap.
        box.min = glm::max(box.min, other.min);
        box.max = glm::min(box.max, other.max);
        tangles.push_back(box);
    }
    // Per undirected edge: the triangles running it low to high, high to low.
    std::unordered_map<std::uint64_t, std::array<int, 2>> uses;
    for (const auto& t : written.triangles) {
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            ++uses[(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b)][a < b ? 0 : 1];
        }
    }
    for (const auto& [key, n] : uses) {
        if (n[0] == 1 && n[1] == 1) continue;
        tangles.push_back(boxOf({std::uint32_t(key >> 32), std::uint32_t(key & 0xffffffffu)}));
    }
    return tangles;
}

}  // namespace

StagedExport stageSampledMesh(const scene::Tree& tree, const model::Model& model, const std::string& path,
                              const ExportSettings& settings) {
    requireSolidModel(tree);
    const mesh::Bounds box = camera::viewBounds(tree, model);
    StagedExport out;
    mesh::Mesh result;  // stays empty where there is nothing to sample
    double reach = 0.0;
    if (tree.root >= 0 && !box.empty()) {
        auto t = Clock::now();
        const contour::DexelGrid grid = remesh::gridFor(box, settings.resolution);
        const contour::Dexels dexels = sample(tree, model, grid, settings);
        out.sampleMs = msSince(t);
        checkMeshFits(dexels, settings.resolution, SourceLocation{tree.source, 0, 0});
        checkNothingBelowGrid(dexels, settings.resolution, SourceLocation{tree.source, 0, 0});
        t = Clock::now();
        // Every face of the result lies on a leaf's plane: the contour
        // rebuilds its flat regions on them.
        const contour::PlaneTable planes = contour::PlaneTable::fromMeshes(model.leafMeshes);
        // Each merged mesh the contour hands over is rounded as the file
        // holds it: points a hair apart in double precision can round to
        // one float (the menger sponge's coincident walls), as the exact
        // mesh's do. Where that would cross itself, the contour moves the
        // vertices there back to their crossings' means and hands over the
        // next; the last one handed over is the one it returns, so its
        // rounded copy is the result.
        std::vector<mesh::Bounds> left;
        contour::contour(dexels, &planes, [&](const mesh::Mesh& contoured) {
            result = contoured;
            roundForFile(result);
            left = tanglesIn(result);
            return left;
        });
        if (!left.empty()) {
            const glm::dvec3 where = left.front().center();
            char text[300];
            std::snprintf(text, sizeof text,
                          "warning: the sampled export crosses itself in %zu places (one near (%.4g, %.4g, %.4g)); "
                          "the exact export (without --export-sampled) does not",
                          left.size(), where.x, where.y, where.z);
            out.warnings.push_back(Warning{std::string(tree.source) + ": " + text});
        }
        out.contourMs = msSince(t);
        reach = grid.spacing;
    }
    out.file = stageResultMesh(tree, model, path, result, settings.faceColor, reach);
    out.triangles = result.triangles.size();
    return out;
}

}  // namespace strata::exporting
