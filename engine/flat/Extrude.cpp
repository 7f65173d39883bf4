#include "strata/flat/Extrude.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "CapTriangulation.h"
#include "strata/core/DegreeTrig.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"
#include "strata/mesh/Primitives.h"
#include "strata/mesh/VertexBudget.h"

namespace strata::flat {

using mesh::Mesh;
using mesh::fragmentsFromR;
using mesh::kMaxVertices;

namespace {

constexpr double kGridFine = 0.00000095367431640625;  // 2^-20, OpenSCAD's GRID_FINE
constexpr double kPi = 3.14159265358979323846;        // M_PI
constexpr double kDegToRad = kPi / 180.0;              // M_DEG2RAD

std::size_t pointCount(const Outlines& shape) {
    std::size_t n = 0;
    for (const Outline& o : shape.outlines) n += o.points.size();
    return n;
}

void checkSize(const char* what, std::size_t rings, std::size_t perRing) {
    if (perRing != 0 && rings > kMaxVertices / perRing) {
        throw Error(std::string(what) + ": too many slices (" + std::to_string(rings) + " rings of " +
                    std::to_string(perRing) + " points, at most " + std::to_string(kMaxVertices) + " vertices)");
    }
}

// A 2D affine map as OpenSCAD builds it for a slice: Scaling(s) * rotate_degrees(-angle).
struct SliceMap {
    double a, b, c, d;  // rows (a b), (c d)
    SliceMap(glm::dvec2 scale, double angle) {
        const double s = sinDegrees(-angle), co = cosDegrees(-angle);
        a = scale.x * co;
        b = scale.x * -s;
        c = scale.y * s;
        d = scale.y * co;
    }
    glm::dvec2 operator()(const glm::dvec2& p) const { return {a * p.x + b * p.y, c * p.x + d * p.y}; }
};

// Euclidean lengths compared as OpenSCAD's sgn_vdiff does: equal within 10 ppm.
int lengthOrder(const glm::dvec2& u, const glm::dvec2& v) {
    constexpr double ratio = 1e5;
    const double l1 = std::sqrt(u.x * u.x + u.y * u.y);
    const double l2 = std::sqrt(v.x * v.x + v.y * v.y);
    const double scale = l1 + l2;
    const double diff = 2 * std::fabs(l1 - l2) * ratio;
    return diff > scale ? (l1 < l2 ? -1 : 1) : 0;
}

double helixLength(double rSquared, double height, double twist) {
    const double t = twist * kDegToRad;
    const double c = height / t;
    return t * std::sqrt(rSquared + c * c);
}

double archimedesLength(double a, double theta) {
    return 0.5 * a * (theta * std::sqrt(1 + theta * theta) + std::asinh(theta));
}

int helixSlices(double rSquared, double height, double twist, const scene::Fragments& f) {
    twist = std::fabs(twist);
    const int minSlices = std::max(static_cast<int>(std::ceil(twist / 120.0)), 1);
    if (std::sqrt(rSquared) < kGridFine || std::isinf(f.fn) || std::isnan(f.fn)) return minSlices;
    if (f.fn > 0.0) return std::max(static_cast<int>(std::ceil(twist / 360.0 * f.fn)), minSlices);
    const int faSlices = static_cast<int>(std::ceil(twist / f.fa));
    const int fsSlices = static_cast<int>(std::ceil(helixLength(rSquared, height, twist) / f.fs));
    return std::max(std::min(faSlices, fsSlices), minSlices);
}

int conicalHelixSlices(double rSquared, double height, double twist, double scale, const scene::Fragments& f) {
    twist = std::fabs(twist);
    const double r = std::sqrt(rSquared);
    const int minSlices = std::max(static_cast<int>(std::ceil(twist / 120.0)), 1);
    if (r < kGridFine || std::isinf(f.fn) || std::isnan(f.fn)) return minSlices;
    if (f.fn > 0.0) return std::max(static_cast<int>(std::ceil(twist * f.fn / 360)), minSlices);
    const double rads = twist * kDegToRad;
    const double end = scale > 1 ? rads * scale / (scale - 1) : rads / (1 - scale);
    const double start = end - rads;
    const double a = r / end;
    const double spiral = archimedesLength(a, end) - archimedesLength(a, start);
    const double total = std::sqrt(spiral * spiral + height * height);
    const int fsSlices = static_cast<int>(std::ceil(total / f.fs));
    const int faSlices = static_cast<int>(std::ceil(twist / f.fa));
    return std::max(std::min(faSlices, fsSlices), minSlices);
}

int diagonalSlices(double deltaSquared, double height, const scene::Fragments& f) {
    if (std::sqrt(deltaSquared) < kGridFine || std::isinf(f.fn) || std::isnan(f.fn)) return 1;
    if (f.fn > 0.0) return std::max(static_cast<int>(f.fn), 1);
    return std::max(static_cast<int>(std::ceil(std::sqrt(deltaSquared + height * height) / f.fs)), 1);
}

// Appends a cap of `ring` (points in the shape's outline order, at height z or
// through `place`) to the mesh; facing up unless `down`.
template <typename Place>
void addCap(Mesh& mesh, const Outlines& shapeAtRing, uint32_t ringBase, bool down, Place place) {
    reportProgress("extrusion: triangulating its caps", 0, 0);
    const detail::CapTriangles cap = detail::triangulateCap(shapeAtRing);
    const std::size_t own = pointCount(shapeAtRing);
    std::vector<uint32_t> index(cap.points.size());
    for (std::size_t k = 0; k < cap.points.size(); ++k) {
        if (k < own) {
            index[k] = ringBase + static_cast<uint32_t>(k);
        } else {
            index[k] = static_cast<uint32_t>(mesh.positions.size());
            mesh.positions.push_back(place(cap.points[k]));
        }
    }
    for (const auto& t : cap.triangles) {
        if (down) mesh.triangles.push_back({index[t[0]], index[t[2]], index[t[1]]});
        else mesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
}

double signedVolume(const Mesh& mesh) {
    double v = 0.0;
    for (const auto& t : mesh.triangles) {
        const glm::dvec3& a = mesh.positions[t[0]];
        const glm::dvec3& b = mesh.positions[t[1]];
        const glm::dvec3& c = mesh.positions[t[2]];
        v += glm::dot(a, glm::cross(b, c));
    }
    return v;
}

void orientOutward(Mesh& mesh) {
    if (signedVolume(mesh) < 0.0) {
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    }
}

}  // namespace

int linearExtrudeSlices(const scene::LinearExtrude& e, const Outlines& shape) {
    if (e.hasSlices) return std::max(e.slices, 1);
    if (e.hasTwist) {
        double maxR2 = 0.0;
        for (const Outline& o : shape.outlines)
            for (const glm::dvec2& v : o.points) maxR2 = std::fmax(maxR2, v.x * v.x + v.y * v.y);
        if ((e.scale.x == 1.0 && e.scale.y == 1.0) || e.scale.x != e.scale.y)
            return helixSlices(maxR2, e.height * e.direction.z, e.twist, e.fragments);
        return conicalHelixSlices(maxR2, e.height * e.direction.z, e.twist, e.scale.x, e.fragments);
    }
    if (e.scale.x != e.scale.y) {
        double maxDelta2 = 0.0;
        for (const Outline& o : shape.outlines)
            for (const glm::dvec2& v : o.points) {
                const glm::dvec2 d = v - v * e.scale;
                maxDelta2 = std::fmax(maxDelta2, d.x * d.x + d.y * d.y);
            }
        return diagonalSlices(maxDelta2, e.height * e.direction.z, e.fragments);
    }
    return 1;
}

Mesh linearExtrude(const scene::LinearExtrude& e, const Outlines& shape) {
    Mesh mesh;
    const std::size_t perRing = pointCount(shape);
    if (!(e.height > 0.0) || perRing == 0) return mesh;
    // The top is moved by height * direction (straight up in 2021.01); the
    // newer dialect writes vectors, h1 and h2, and rings at h1 + (h2 - h1) j/n.
    const glm::dvec3 full = e.height * e.direction;
    const glm::dvec3 h1 = e.center ? -full / 2.0 : glm::dvec3(0.0);
    const glm::dvec3 h2 = e.center ? full - full / 2.0 : full;
    const int slicesInt = linearExtrudeSlices(e, shape);
    const auto slices = static_cast<std::size_t>(slicesInt);
    checkSize("linear_extrude", slices + 1, perRing);
    const double n = static_cast<double>(slices);

    // Rings j = 0..slices: the shape scaled and turned as slice j's map does it.
    std::vector<glm::dvec2> scales(slices + 1);
    std::vector<glm::dvec3> heights(slices + 1);
    std::vector<double> twists(slices + 1);
    mesh.positions.reserve((slices + 1) * perRing);
    std::vector<glm::dvec2> turned;  // each ring's points before the rise: what the diagonal choice sees
    turned.reserve((slices + 1) * perRing);
    for (std::size_t j = 0; j <= slices; ++j) {
        const double jd = static_cast<double>(j);
        twists[j] = e.twist * jd / n;
        heights[j] = h1 + (h2 - h1) * jd / n;  // per axis, as glm computes it
        scales[j] = {1 - (1 - e.scale.x) * jd / n, 1 - (1 - e.scale.y) * jd / n};
        const SliceMap map(scales[j], twists[j]);
        for (const Outline& o : shape.outlines)
            for (const glm::dvec2& p : o.points) {
                const glm::dvec2 q = map(p);
                turned.push_back(q);
                mesh.positions.emplace_back(q.x + heights[j].x, q.y + heights[j].y, heights[j].z);
            }
    }
    auto at = [&](std::size_t ring, std::size_t k) { return static_cast<uint32_t>(ring * perRing + k); };
    auto xy = [&](uint32_t v) { return turned[v]; };

    // Side walls, slice by slice, with OpenSCAD's diagonal choice (add_slice).
    for (std::size_t j = 0; j < slices; ++j) {
        const bool anyZero = scales[j + 1].x == 0 || scales[j + 1].y == 0;
        const bool anyNonZero = scales[j + 1].x != 0 || scales[j + 1].y != 0;
        const bool backTwist = twists[j + 1] <= twists[j];
        std::size_t first = 0;
        for (const Outline& o : shape.outlines) {
            const std::size_t m = o.points.size();
            const bool flip = (!o.positive) != backTwist;
            for (std::size_t i = 1; i <= m; ++i) {
                const uint32_t prev1 = at(j, first + i - 1), curr1 = at(j, first + i % m);
                const uint32_t prev2 = at(j + 1, first + i - 1), curr2 = at(j + 1, first + i % m);
                const int order = lengthOrder(xy(prev1) - xy(curr2), xy(curr1) - xy(prev2));
                const bool splitFirst = order == -1 || (order == 0 && !flip);
                const bool second = !anyZero || (anyNonZero && xy(prev2) != xy(curr2));
                // OpenSCAD's triangles are clockwise seen from outside; these are reversed.
                if (splitFirst != anyZero) {
                    mesh.triangles.push_back({prev1, curr1, curr2});
                    if (second) mesh.triangles.push_back({curr2, prev2, prev1});
                } else {
                    mesh.triangles.push_back({prev1, curr1, prev2});
                    if (second) mesh.triangles.push_back({prev2, curr1, curr2});
                }
            }
            first += m;
        }
    }

    // Caps: the bottom facing down; the top (left out when a scale is 0) facing up.
    auto lift = [&](std::size_t ring) {
        return [&, ring](const glm::dvec2& p) {
            return glm::dvec3(p.x + heights[ring].x, p.y + heights[ring].y, heights[ring].z);
        };
    };
    addCap(mesh, shape, at(0, 0), true, lift(0));
    if (e.scale.x > 0 && e.scale.y > 0) {
        Outlines top = shape;
        std::size_t k = 0;
        for (Outline& o : top.outlines)
            for (glm::dvec2& p : o.points) p = xy(at(slices, k++));
        addCap(mesh, top, at(slices, 0), false, lift(slices));
    }
    orientOutward(mesh);
    return mesh;
}

Mesh rotateExtrude(const scene::RotateExtrude& e, const Outlines& shape) {
    Mesh mesh;
    const std::size_t perRing = pointCount(shape);
    if (e.angle == 0 || perRing == 0) return mesh;
    double minX = 0, maxX = 0;
    for (const Outline& o : shape.outlines)
        for (const glm::dvec2& v : o.points) {
            minX = std::fmin(minX, v.x);
            maxX = std::fmax(maxX, v.x);
            if ((maxX - minX) > maxX && (maxX - minX) > std::fabs(minX)) {
                char range[96];
                std::snprintf(range, sizeof range, "%.2f -> %.2f", minX, maxX);
                throw Error(std::string("all points for rotate_extrude() must have the same X coordinate sign (range is ") +
                            range + ")");
            }
        }
    const int fragments = static_cast<int>(
        std::fmax(fragmentsFromR(maxX - minX, e.fragments) * std::fabs(e.angle) / 360, 1));
    const auto sections = static_cast<std::size_t>(fragments);
    const bool closed = e.angle == 360;
    const std::size_t rings = closed ? sections : sections + 1;
    checkSize("rotate_extrude", rings, perRing);

    // Ring j as (x * cx, x * cy, y): 2021.01 writes (x sin a, x cos a) with a
    // from -90 (full turns) or 90 (partial ones); the newer dialect
    // (x cos a, x sin a) with a from `start`. Either is a turn about z.
    auto factors = [&](std::size_t j) {
        const double jd = static_cast<double>(j), n = static_cast<double>(sections);
        if (e.hasStart) {
            const double a = e.start + jd * e.angle / n;
            return glm::dvec2(cosDegrees(a), sinDegrees(a));
        }
        const double a = closed ? -90 + jd * 360.0 / n : 90 - jd * e.angle / n;
        return glm::dvec2(sinDegrees(a), cosDegrees(a));
    };
    mesh.positions.reserve(rings * perRing);
    for (std::size_t j = 0; j < rings; ++j) {
        const glm::dvec2 f = factors(j);
        for (const Outline& o : shape.outlines)
            for (const glm::dvec2& v : o.points) mesh.positions.emplace_back(v.x * f.x, v.x * f.y, v.y);
    }
    auto at = [&](std::size_t ring, std::size_t k) { return static_cast<uint32_t>((ring % rings) * perRing + k); };

    // 2021.01 lists a ring's points backwards where it flips the faces, which
    // moves the diagonal of each side quad (the quads are planar trapezoids,
    // so the surface is the same either way).
    const bool otherDiagonal = !e.hasStart && ((minX >= 0 && e.angle > 0 && !closed) || (minX < 0 && (e.angle < 0 || closed)));
    for (std::size_t j = 0; j < sections; ++j) {
        std::size_t first = 0;
        for (const Outline& o : shape.outlines) {
            const std::size_t m = o.points.size();
            for (std::size_t i = 0; i < m; ++i) {
                const uint32_t a0 = at(j, first + i), a1 = at(j, first + (i + 1) % m);
                const uint32_t b0 = at(j + 1, first + i), b1 = at(j + 1, first + (i + 1) % m);
                if (otherDiagonal) {
                    mesh.triangles.push_back({a1, a0, b0});
                    mesh.triangles.push_back({b0, b1, a1});
                } else {
                    mesh.triangles.push_back({a0, b1, a1});
                    mesh.triangles.push_back({a0, b0, b1});
                }
            }
            first += m;
        }
    }
    if (!closed) {
        // A wall triangle (a0, b1, a1) faces out when x and the sweep turn
        // the same way about +z; a cap laid counter-clockwise in the shape's
        // plane faces against the sweep, so the first cap is laid that way and
        // the last one reversed: the mesh is consistent either way round, and
        // orientOutward turns it outward.
        auto place = [&](std::size_t ring) {
            const glm::dvec2 f = factors(ring);
            return [f](const glm::dvec2& p) { return glm::dvec3(p.x * f.x, p.x * f.y, p.y); };
        };
        addCap(mesh, shape, at(0, 0), false, place(0));
        addCap(mesh, shape, at(sections, 0), true, place(sections));
    }
    orientOutward(mesh);
    return mesh;
}

Mesh flatSlab(const Outlines& shape) {
    scene::LinearExtrude slab;
    slab.height = 1.0;
    slab.center = true;
    return linearExtrude(slab, shape);
}

}  // namespace strata::flat
