#include "strata/remesh/Remesh.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/core/Threads.h"

namespace strata::remesh {

namespace {

// Where the grid's planes sit against the box's faces, in cells: 1 - 1/phi,
// far from every simple fraction that round model coordinates would hit.
constexpr double kGridOffset = 0.3819660112501051;

// The widest field of view the sampling cameras take; a grid too wide for it
// at one cell's distance moves the eye back.
constexpr double kWidestFovDegrees = 150.0;

glm::dvec3 unitAxis(int a) {
    glm::dvec3 e(0.0);
    e[a] = 1.0;
    return e;
}

// One axis's rays while they are filled, one list per grid line.
using RayLists = std::vector<std::vector<contour::Crossing>>;

contour::DexelRays pack(const RayLists& lists) {
    contour::DexelRays rays;
    rays.first.reserve(lists.size() + 1);
    std::size_t total = 0;
    for (const auto& list : lists) total += list.size();
    rays.crossings.reserve(total);
    for (const auto& list : lists) {
        rays.first.push_back(static_cast<std::uint32_t>(rays.crossings.size()));
        rays.crossings.insert(rays.crossings.end(), list.begin(), list.end());
    }
    rays.first.push_back(static_cast<std::uint32_t>(rays.crossings.size()));
    return rays;
}

// The grid's other two axes for rays along `a`.
struct RayAxes {
    int u = 0, v = 0;
};

RayAxes rayAxes(int a) { return {(a + 1) % 3, (a + 2) % 3}; }

// The orthographic camera that looks along +a with one pixel centre on each
// grid line of the other two axes, and, per pixel column and row, the grid
// index along the axis it runs on.
struct AxisView {
    camera::Camera camera;
    int columnAxis = 0, rowAxis = 0;  // the grid axes that columns and rows step along
    std::vector<int> columnIndex, rowIndex;
};

int axisOf(const glm::dvec3& direction) {
    for (int k = 0; k < 3; ++k) {
        if (std::abs(std::abs(direction[k]) - 1.0) < 1e-9) return k;
    }
    throw Error("export: the sampling camera is not aligned with the grid");
}

// The grid index of world coordinate `x` along axis k; must lie on a grid line.
int gridIndex(const contour::DexelGrid& grid, int k, double x) {
    const double at = (x - grid.origin[k]) / grid.spacing;
    const double index = std::round(at);
    if (std::abs(at - index) > 1e-6 || index < 0 || index >= grid.count[k]) {
        throw Error("export: a sampling ray misses the grid lines");
    }
    return static_cast<int>(index);
}

// The box the grid's vertices span.
mesh::Bounds gridBox(const contour::DexelGrid& grid) {
    mesh::Bounds box;
    box.extend(grid.origin);
    box.extend(grid.origin + grid.spacing * glm::dvec3(grid.count - 1));
    return box;
}

AxisView axisView(const contour::DexelGrid& grid, int a) {
    const mesh::Bounds box = gridBox(grid);
    const glm::dvec3 size = box.max - box.min;
    const glm::dvec3 center = box.min + size * 0.5;
    AxisView view;
    camera::Camera& camera = view.camera;
    camera.projection = camera::Projection::Orthographic;
    // Look from one cell before the grid's first plane; the basis the camera
    // derives from +a decides which grid axis runs along the columns.
    camera.center = center;
    camera.eye = center - unitAxis(a) * (size[a] * 0.5 + grid.spacing);
    view.columnAxis = axisOf(camera.right());
    view.rowAxis = axisOf(camera.up());
    camera.width = grid.count[view.columnAxis];
    camera.height = grid.count[view.rowAxis];
    // A pixel is one cell: the half height of the view is height / 2 cells.
    const double halfHeight = camera.height * grid.spacing * 0.5;
    double distance = glm::length(camera.center - camera.eye);
    const double widest = std::tan(kWidestFovDegrees * 0.5 * M_PI / 180.0);
    if (halfHeight / distance > widest) {
        distance = halfHeight / widest;
        camera.eye = center - unitAxis(a) * distance;
    }
    camera.fovDegrees = 2.0 * std::atan(halfHeight / distance) * 180.0 / M_PI;
    for (int i = 0; i < camera.width; ++i)
        view.columnIndex.push_back(gridIndex(grid, view.columnAxis, camera.ray(i, 0).origin[view.columnAxis]));
    for (int j = 0; j < camera.height; ++j)
        view.rowIndex.push_back(gridIndex(grid, view.rowAxis, camera.ray(0, j).origin[view.rowAxis]));
    return view;
}

// Ray index of grid line (iu, iv) for rays along `a` (Dexels.h).
std::size_t rayIndex(const contour::DexelGrid& grid, int a, int iu, int iv) {
    return static_cast<std::size_t>(iu) +
           static_cast<std::size_t>(iv) * static_cast<std::size_t>(grid.count[rayAxes(a).u]);
}

std::size_t rayCount(const contour::DexelGrid& grid, int a) {
    const RayAxes axes = rayAxes(a);
    return static_cast<std::size_t>(grid.count[axes.u]) * static_cast<std::size_t>(grid.count[axes.v]);
}

}  // namespace

contour::DexelGrid gridFor(const mesh::Bounds& box, int resolution) {
    if (resolution < kLeastResolution || resolution > kMostResolution) {
        throw Error("export: the resolution must be " + std::to_string(kLeastResolution) + " to " +
                    std::to_string(kMostResolution) + " cells, got " + std::to_string(resolution));
    }
    if (box.empty()) throw Error("export: the result is empty: nothing to export");
    const glm::dvec3 size = box.max - box.min;
    const double longest = std::max({size.x, size.y, size.z});
    if (!(longest > 0.0) || !std::isfinite(longest)) throw Error("export: the result has no extent to sample");
    contour::DexelGrid grid;
    grid.spacing = longest / resolution;
    grid.origin = box.min - glm::dvec3(1.0 + kGridOffset) * grid.spacing;
    for (int k = 0; k < 3; ++k) {
        grid.count[k] = static_cast<int>(std::ceil((box.max[k] - grid.origin[k]) / grid.spacing)) + 2;
    }
    return grid;
}

contour::Dexels sampleOnGpu(render::Renderer& renderer, const contour::DexelGrid& grid,
                            const render::RenderSettings& settings) {
    contour::Dexels dexels;
    dexels.grid = grid;
    for (int a = 0; a < 3; ++a) {
        reportProgress("export: sampling", static_cast<std::size_t>(a), 3);
        const AxisView view = axisView(grid, a);
        const RayAxes axes = rayAxes(a);
        const bool columnsAlongU = view.columnAxis == axes.u;
        RayLists lists(rayCount(grid, a));
        const double eye = view.camera.eye[a];
        std::size_t unresolved = 0;
        auto onRound = [&](const render::ResultRound& round) {
            unresolved += round.unresolved;
            for (int y = 0; y < round.height; ++y) {
                const int row = view.rowIndex[static_cast<std::size_t>(round.y + y)];
                for (int x = 0; x < round.width; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(round.width) +
                                          static_cast<std::size_t>(x);
                    const float depth = round.depth[i];
                    if (!std::isfinite(depth)) continue;
                    const int column = view.columnIndex[static_cast<std::size_t>(round.x + x)];
                    const std::size_t r = columnsAlongU ? rayIndex(grid, a, column, row) : rayIndex(grid, a, row, column);
                    std::vector<contour::Crossing>& list = lists[r];
                    list.push_back({eye + static_cast<double>(depth), round.normal[i], list.size() % 2 == 0});
                }
            }
        };
        renderer.sampleResult(view.camera, settings, onRound);
        if (unresolved > 0) {
            throw Error("export: " + std::to_string(unresolved) +
                        " rays cross more surfaces than this driver lets one shader walk (llvmpipe's loop limit); "
                        "export with --reference, or at a lower --export-resolution");
        }
        dexels.axes[static_cast<std::size_t>(a)] = pack(lists);
    }
    reportProgress("export: sampling", 3, 3);
    return dexels;
}

contour::Dexels sampleWithReference(const reference::ReferenceScene& scene, const contour::DexelGrid& grid,
                                    int threads) {
    contour::Dexels dexels;
    dexels.grid = grid;
    const int workers = threads > 0 ? threads : hardwareThreads();
    for (int a = 0; a < 3; ++a) {
        reportProgress("export: sampling", static_cast<std::size_t>(a), 3);
        const RayAxes axes = rayAxes(a);
        RayLists lists(rayCount(grid, a));
        // Each ray starts a cell before the grid and is traced from change to
        // change in exact arithmetic. Two changes closer than the
        // coincidence tolerance of the GPU's view along this axis are then
        // one place where nothing changes, and both go: the faces where two
        // operands of a union touch, a rounding apart once transformed, are
        // no gap (the GPU's result peel does not see one either).
        const double start = grid.origin[a] - grid.spacing;
        const double coincidence = camera::coincidenceTolerance(axisView(grid, a).camera, gridBox(grid));
        std::atomic<std::size_t> next{0};
        auto work = [&] {
            for (std::size_t r = next++; r < lists.size(); r = next++) {
                const int iu = static_cast<int>(r % static_cast<std::size_t>(grid.count[axes.u]));
                const int iv = static_cast<int>(r / static_cast<std::size_t>(grid.count[axes.u]));
                camera::Ray ray;
                ray.origin[a] = start;
                ray.origin[axes.u] = grid.origin[axes.u] + grid.spacing * iu;
                ray.origin[axes.v] = grid.origin[axes.v] + grid.spacing * iv;
                ray.direction = unitAxis(a);
                double t = 0.0;
                for (;;) {
                    const reference::RayHit hit = scene.trace(ray, t, 0.0);
                    if (!hit.hit()) break;
                    std::vector<contour::Crossing>& list = lists[r];
                    if (!list.empty() && start + hit.t - list.back().at <= coincidence) {
                        list.pop_back();
                    } else {
                        list.push_back({start + hit.t, glm::vec3(hit.normal), list.size() % 2 == 0});
                    }
                    t = hit.t;
                }
            }
        };
        runOnThreads(workers, work);
        dexels.axes[static_cast<std::size_t>(a)] = pack(lists);
    }
    reportProgress("export: sampling", 3, 3);
    return dexels;
}

}  // namespace strata::remesh
