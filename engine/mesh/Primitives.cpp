#include "strata/mesh/Primitives.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "strata/core/DegreeTrig.h"
#include "PolygonTriangulation.h"
#include "strata/mesh/VertexBudget.h"

// Tessellation follows OpenSCAD 2021.01, src/primitives.cc
// (PrimitiveNode::createGeometry) and src/calc.cc (get_fragments_from_r); the
// polygons it builds are split into triangles as its preview renderer does
// (src/renderer.cc, Renderer::render_surface): a quad (0,1,2,3) into (0,1,3)
// and (2,3,1), a larger polygon into a fan around its vertex average.

namespace strata::mesh {
namespace {

constexpr double kGridFine = 0.00000095367431640625;  // 2^-20, OpenSCAD's GRID_FINE
constexpr double kMinimumFaFs = 0.01;                  // OpenSCAD clamps $fa and $fs to this
constexpr double kPi = 3.14159265358979323846;         // M_PI

// Builds a mesh from polygons listed counter-clockwise seen from outside.
class PolygonMesh {
public:
    uint32_t addVertex(const glm::dvec3& p) {
        mesh_.positions.push_back(p);
        return static_cast<uint32_t>(mesh_.positions.size() - 1);
    }

    void addPolygon(const std::vector<uint32_t>& loop) {
        const std::size_t n = loop.size();
        if (n == 3) {
            mesh_.triangles.push_back({loop[0], loop[1], loop[2]});
        } else if (n == 4) {
            mesh_.triangles.push_back({loop[0], loop[1], loop[3]});
            mesh_.triangles.push_back({loop[2], loop[3], loop[1]});
        } else if (n > 4) {
            glm::dvec3 sum(0.0);
            for (uint32_t i : loop) {
                const glm::dvec3& p = mesh_.positions[i];
                sum.x += p.x;
                sum.y += p.y;
                sum.z += p.z;
            }
            const double count = static_cast<double>(n);
            const uint32_t center = addVertex({sum.x / count, sum.y / count, sum.z / count});
            for (std::size_t j = 1; j <= n; ++j) mesh_.triangles.push_back({center, loop[j - 1], loop[j % n]});
        }
    }

    Mesh take() { return std::move(mesh_); }

private:
    Mesh mesh_;
};

// OpenSCAD's generate_circle: n points from +X, counter-clockwise seen from +Z.
std::vector<glm::dvec2> circle(double r, int fragments) {
    std::vector<glm::dvec2> points(static_cast<std::size_t>(fragments));
    for (int i = 0; i < fragments; ++i) {
        const double phi = (360.0 * i) / fragments;
        points[static_cast<std::size_t>(i)] = {r * cosDegrees(phi), r * sinDegrees(phi)};
    }
    return points;
}

void checkSize(const char* what, std::size_t vertices) {
    if (vertices > kMaxVertices) {
        throw Error(std::string(what) + ": too many fragments (" + std::to_string(vertices) +
                    " vertices, at most " + std::to_string(kMaxVertices) + ")");
    }
}

}  // namespace

int fragmentsFromR(double r, const scene::Fragments& f) {
    // OpenSCAD clamps $fa and $fs when the primitive is instantiated.
    const double fs = f.fs < kMinimumFaFs ? kMinimumFaFs : f.fs;
    const double fa = f.fa < kMinimumFaFs ? kMinimumFaFs : f.fa;
    const double fn = f.fn;
    if (r < kGridFine || std::isinf(fn) || std::isnan(fn)) return 3;
    if (fn > 0.0) {
        // Truncation as OpenSCAD's static_cast; clamped first so the cast is defined.
        return static_cast<int>(std::min(fn >= 3 ? fn : 3.0, 2.0e9));
    }
    return static_cast<int>(std::ceil(std::fmax(std::fmin(360.0 / fa, r * 2 * kPi / fs), 5)));
}

Mesh tessellate(const scene::Cube& cube) {
    const glm::dvec3 s = cube.size;
    if (!(s.x > 0 && s.y > 0 && s.z > 0) || std::isinf(s.x) || std::isinf(s.y) || std::isinf(s.z)) return {};
    double x1 = 0, y1 = 0, z1 = 0, x2 = s.x, y2 = s.y, z2 = s.z;
    if (cube.center) {
        x1 = -s.x / 2, x2 = s.x / 2;
        y1 = -s.y / 2, y2 = s.y / 2;
        z1 = -s.z / 2, z2 = s.z / 2;
    }
    PolygonMesh m;
    // Corners in the order OpenSCAD first emits them (top face, then bottom).
    const uint32_t a = m.addVertex({x1, y1, z2}), b = m.addVertex({x2, y1, z2});
    const uint32_t c = m.addVertex({x2, y2, z2}), d = m.addVertex({x1, y2, z2});
    const uint32_t e = m.addVertex({x1, y2, z1}), f = m.addVertex({x2, y2, z1});
    const uint32_t g = m.addVertex({x2, y1, z1}), h = m.addVertex({x1, y1, z1});
    m.addPolygon({a, b, c, d});  // top
    m.addPolygon({e, f, g, h});  // bottom
    m.addPolygon({h, g, b, a});  // side1 (y = y1)
    m.addPolygon({g, f, c, b});  // side2 (x = x2)
    m.addPolygon({f, e, d, c});  // side3 (y = y2)
    m.addPolygon({e, h, a, d});  // side4 (x = x1)
    return m.take();
}

Mesh tessellate(const scene::Sphere& sphere) {
    const double r = sphere.r;
    if (!(r > 0) || std::isinf(r)) return {};
    const int fragments = fragmentsFromR(r, sphere.fragments);
    const int rings = (fragments + 1) / 2;
    const auto n = static_cast<uint32_t>(fragments);
    checkSize("sphere", std::size_t(n) * std::size_t(rings) + 2);

    PolygonMesh m;
    // Ring i at polar angle 180*(i + 0.5)/rings from +Z; vertex k of ring i
    // gets index i*n + k.
    for (int i = 0; i < rings; ++i) {
        const double phi = (180.0 * (i + 0.5)) / rings;
        const double ringR = r * sinDegrees(phi);
        const double z = r * cosDegrees(phi);
        for (const auto& p : circle(ringR, fragments)) m.addVertex({p.x, p.y, z});
    }
    auto at = [n](int ring, uint32_t k) { return static_cast<uint32_t>(ring) * n + k % n; };

    std::vector<uint32_t> top(n);
    for (uint32_t k = 0; k < n; ++k) top[k] = at(0, k);
    m.addPolygon(top);

    // Bands, in OpenSCAD's zig-zag order: alternately a triangle with its edge
    // on the lower ring and one with its edge on the upper ring.
    for (int i = 0; i + 1 < rings; ++i) {
        uint32_t r1i = 0, r2i = 0;
        while (r1i < n || r2i < n) {
            const bool stepUpper = r2i >= n || (r1i < n && r1i < r2i);
            if (stepUpper) {
                m.addPolygon({at(i + 1, r2i), at(i, r1i + 1), at(i, r1i)});
                ++r1i;
            } else {
                m.addPolygon({at(i + 1, r2i), at(i + 1, r2i + 1), at(i, r1i)});
                ++r2i;
            }
        }
    }

    std::vector<uint32_t> bottom(n);
    for (uint32_t k = 0; k < n; ++k) bottom[k] = at(rings - 1, n - 1 - k);
    m.addPolygon(bottom);
    return m.take();
}

Mesh tessellate(const scene::Cylinder& cylinder) {
    const double h = cylinder.h, r1 = cylinder.r1, r2 = cylinder.r2;
    if (!(h > 0) || std::isinf(h) || !(r1 >= 0) || !(r2 >= 0) || !(r1 > 0 || r2 > 0) || std::isinf(r1) ||
        std::isinf(r2)) {
        return {};
    }
    const int fragments = fragmentsFromR(std::fmax(r1, r2), cylinder.fragments);
    const auto n = static_cast<uint32_t>(fragments);
    checkSize("cylinder", 2 * std::size_t(n) + 2);
    const double z1 = cylinder.center ? -h / 2 : 0.0;
    const double z2 = cylinder.center ? h / 2 : h;

    // A radius of 0 collapses its circle into one apex vertex at the axis.
    PolygonMesh m;
    std::vector<uint32_t> bottom(n), top(n);
    auto ring = [&](double r, double z, std::vector<uint32_t>& ids) {
        if (r > 0) {
            const auto pts = circle(r, fragments);
            for (uint32_t k = 0; k < n; ++k) ids[k] = m.addVertex({pts[k].x, pts[k].y, z});
        } else {
            std::fill(ids.begin(), ids.end(), m.addVertex({0.0, 0.0, z}));
        }
    };
    ring(r1, z1, bottom);
    ring(r2, z2, top);

    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = (i + 1) % n;
        if (r1 == r2) {
            m.addPolygon({bottom[j], top[j], top[i], bottom[i]});
        } else {
            if (r1 > 0) m.addPolygon({bottom[j], top[i], bottom[i]});
            if (r2 > 0) m.addPolygon({bottom[j], top[j], top[i]});
        }
    }
    if (r1 > 0) {
        std::vector<uint32_t> loop(bottom.rbegin(), bottom.rend());
        m.addPolygon(loop);
    }
    if (r2 > 0) m.addPolygon(top);
    return m.take();
}

Mesh tessellate(const scene::Polyhedron& polyhedron) {
    Mesh mesh;
    mesh.positions = polyhedron.points;
    const auto pointCount = polyhedron.points.size();
    std::vector<uint32_t> loop;
    for (std::size_t f = 0; f < polyhedron.faces.size(); ++f) {
        const auto& face = polyhedron.faces[f];
        loop.clear();
        // OpenSCAD lists faces clockwise seen from outside: reverse them.
        for (auto it = face.rbegin(); it != face.rend(); ++it) {
            if (*it < 0 || static_cast<std::size_t>(*it) >= pointCount) {
                throw Error("polyhedron: faces[" + std::to_string(f) + "] uses point " + std::to_string(*it) +
                            ", but there are " + std::to_string(pointCount) + " points");
            }
            loop.push_back(static_cast<uint32_t>(*it));
        }
        detail::triangulatePolygon(mesh.positions, loop, mesh.triangles);
    }
    return mesh;
}

}  // namespace strata::mesh
