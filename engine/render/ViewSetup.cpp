#include "ViewSetup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"

namespace strata::render {

using camera::Camera;
using camera::Projection;
using camera::coincidenceTolerance;

namespace {

// A fraction of the scene's diagonal: the smallest near plane, and the margin
// that keeps the nearest and farthest faces off the clip planes.
constexpr double kNearFloor = 1e-6;
constexpr double kMargin = 1e-3;

std::array<glm::dvec3, 8> corners(const mesh::Bounds& b) {
    std::array<glm::dvec3, 8> c;
    for (int k = 0; k < 8; ++k) {
        c[static_cast<std::size_t>(k)] = {(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                          (k & 4) ? b.max.z : b.min.z};
    }
    return c;
}

}  // namespace

ViewSetup makeView(const Camera& camera, const mesh::Bounds& sceneBounds) {
    if (camera.width <= 0 || camera.height <= 0) {
        throw Error("camera: image size must be positive, got " + std::to_string(camera.width) + "x" +
                    std::to_string(camera.height));
    }
    if (!(camera.fovDegrees > 0.0 && camera.fovDegrees < 180.0)) {
        throw Error("camera: field of view must be between 0 and 180 degrees");
    }
    const double distance = glm::length(camera.center - camera.eye);
    if (!(distance > 0.0) || !std::isfinite(distance)) throw Error("camera: eye and center must differ");

    ViewSetup view;
    view.width = camera.width;
    view.height = camera.height;
    view.orthographic = camera.projection == Projection::Orthographic;
    view.eyeD = camera.eye;
    view.forwardD = camera.forward();

    double nearest = std::numeric_limits<double>::infinity();
    double farthest = -nearest;
    double size = 1.0;
    if (!sceneBounds.empty()) {
        for (const glm::dvec3& c : corners(sceneBounds)) {
            const double d = camera.viewDepth(c);
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
        }
        size = std::max(sceneBounds.diagonal(), 1e-30);
    } else {
        nearest = 1.0;
        farthest = 2.0;
    }
    // The eye may sit far from a tiny scene: keep the planes' scale sensible.
    const double scale = std::max(size, 1e-9 * std::max(std::abs(nearest), std::abs(farthest)));
    view.nearPlane = std::max(kNearFloor * scale, nearest - kMargin * scale);
    view.farPlane = std::max(farthest + kMargin * scale, view.nearPlane * 2.0);

    const glm::dmat4 vp = camera.projectionMatrix(view.nearPlane, view.farPlane) * camera.viewMatrix();
    view.viewProjectionD = vp;
    view.viewProjection = glm::mat4(vp);
    view.eye = glm::vec3(camera.eye);
    view.forward = glm::vec3(camera.forward());
    view.right = glm::vec3(camera.right());
    view.up = glm::vec3(camera.up());
    const double t = std::tan(camera.fovDegrees * std::numbers::pi / 360.0);
    view.halfExtent = glm::vec2(static_cast<float>(t * camera.width / camera.height), static_cast<float>(t));
    view.coincidence = coincidenceTolerance(camera, sceneBounds);
    return view;
}

namespace {

// The projection to frame pixels as three rows, x' = (a . p) / (w . p), so
// that a vertex costs three dot products and a division: a frame projects
// every vertex of every leaf on the CPU, a million of them in a large model.
struct Projector {
    glm::dvec4 x, y, w;    // homogeneous rows, already scaled to pixels
    glm::dvec3 forward;    // view depth: dot(p, forward) - dot(eye, forward)
    double nearDepth = 0;  // dot(eye, forward) + near: at or before it, a point is clipped

    explicit Projector(const ViewSetup& view) {
        const glm::dmat4& m = view.viewProjectionD;  // column-major: m[column][row]
        const auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
        w = row(3);
        // (clip.x / clip.w + 1) / 2 * width = (clip.x + clip.w) * width / 2 / clip.w
        x = (row(0) + w) * (0.5 * view.width);
        y = (row(1) + w) * (0.5 * view.height);
        forward = view.forwardD;
        nearDepth = glm::dot(view.eyeD, view.forwardD) + view.nearPlane;
    }

    // `p` in frame pixels; false (q untouched) at or before the near plane.
    bool toScreen(const glm::dvec3& p, glm::dvec2& q) const {
        if (glm::dot(p, forward) <= nearDepth) return false;
        const glm::dvec4 h(p, 1.0);
        const double inv = 1.0 / glm::dot(w, h);
        q = {glm::dot(x, h) * inv, glm::dot(y, h) * inv};
        return true;
    }
};

// Accumulates the screen rectangle of points; `whole` once one reaches the near plane.
struct RectBuilder {
    const ViewSetup& view;
    Projector proj{view};
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    bool whole = false;

    // Projects `p`; false (and `whole`) at or before the near plane.
    bool add(const glm::dvec3& p, glm::dvec2& q) {
        if (!proj.toScreen(p, q)) {
            whole = true;
            return false;
        }
        x0 = std::min(x0, q.x);
        x1 = std::max(x1, q.x);
        y0 = std::min(y0, q.y);
        y1 = std::max(y1, q.y);
        return true;
    }

    PixelRect rect() const;
};

PixelRect RectBuilder::rect() const {
    if (whole) return {0, 0, view.width, view.height};
    if (!(x0 <= x1)) return {};
    const int ix0 = static_cast<int>(std::clamp(std::floor(x0) - 1.0, 0.0, double(view.width)));
    const int iy0 = static_cast<int>(std::clamp(std::floor(y0) - 1.0, 0.0, double(view.height)));
    const int ix1 = static_cast<int>(std::clamp(std::ceil(x1) + 1.0, 0.0, double(view.width)));
    const int iy1 = static_cast<int>(std::clamp(std::ceil(y1) + 1.0, 0.0, double(view.height)));
    return {ix0, iy0, ix1 - ix0, iy1 - iy0};
}

}  // namespace

bool beyondNearPlane(const ViewSetup& view, const mesh::Bounds& box) {
    if (box.empty()) return true;
    for (const glm::dvec3& c : corners(box)) {
        if (glm::dot(c - view.eyeD, view.forwardD) <= view.nearPlane) return false;
    }
    return true;
}

PixelRect screenRect(const ViewSetup& view, const mesh::Bounds& box) {
    if (box.empty()) return {};
    RectBuilder builder{view};
    glm::dvec2 q;
    for (const glm::dvec3& c : corners(box)) builder.add(c, q);
    return builder.rect();
}

PixelRect screenRect(const ViewSetup& view, std::span<const glm::vec3> vertices) {
    return screenBounds(view, vertices, 0).rect;
}

namespace {

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain over `points` (sorted here): the lower hull left
// to right, then the upper right to left, collinear points dropped.
ScreenHull monotoneChain(std::vector<glm::dvec2>& points) {
    std::sort(points.begin(), points.end(),
              [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 3) return ScreenHull(points.begin(), points.end());
    ScreenHull hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);  // the last point is the first
    return hull;
}

}  // namespace

ScreenBounds screenBounds(const ViewSetup& view, std::span<const glm::vec3> vertices, std::size_t mostHullVertices) {
    const bool wantHull = vertices.size() <= mostHullVertices;
    // Up to kExactHullVertices vertices (a box, a thin bar), the hull of the
    // points themselves; past that, the sixteen-sided polygon of their
    // extents in as many directions, which holds the hull and hugs a
    // sphere's outline within 2 % of its radius, for a fifth of the time.
    constexpr std::size_t kExactHullVertices = 64;
    constexpr int kDirections = 8;  // and their opposites
    static const std::array<glm::dvec2, kDirections> directions = [] {
        std::array<glm::dvec2, kDirections> d{};
        for (int k = 0; k < kDirections; ++k) {
            const double angle = std::numbers::pi * k / kDirections;
            d[static_cast<std::size_t>(k)] = {std::cos(angle), std::sin(angle)};
        }
        d[0] = {1.0, 0.0};  // exactly x and y: the rectangle's extents, sides along rows and columns
        d[kDirections / 2] = {0.0, 1.0};
        return d;
    }();
    const bool exact = wantHull && vertices.size() <= kExactHullVertices;
    const bool bounded = wantHull && !exact;  // the sixteen-sided bound
    static thread_local std::vector<glm::dvec2> points;
    points.clear();
    std::array<double, kDirections> most, least;
    most.fill(-std::numeric_limits<double>::infinity());
    least.fill(std::numeric_limits<double>::infinity());
    RectBuilder rect{view};
    for (const glm::vec3& v : vertices) {
        glm::dvec2 q;
        if (!rect.add(glm::dvec3(v), q)) return {rect.rect(), {}};
        if (exact) points.push_back(q);
        if (!bounded) continue;
        for (std::size_t k = 1; k < kDirections; ++k) {  // x and y (0 and 4): the rectangle's
            if (k == kDirections / 2) continue;
            const double along = directions[k].x * q.x + directions[k].y * q.y;
            most[k] = along > most[k] ? along : most[k];
            least[k] = along < least[k] ? along : least[k];
        }
    }
    ScreenBounds out{rect.rect(), {}};
    if (exact) {
        out.hull = monotoneChain(points);
    } else if (bounded) {
        most[0] = rect.x1;
        least[0] = rect.x0;
        most[kDirections / 2] = rect.y1;
        least[kDirections / 2] = rect.y0;
        // The corner between each side and the next, counter-clockwise: side
        // k (0..15) lies on dot(d, p) = reach, d the k-th direction of the
        // circle, reach its extent (an opposite's is minus the least).
        auto side = [&](std::size_t k) {
            return k < kDirections ? std::pair{directions[k], most[k]}
                                   : std::pair{-directions[k - kDirections], -least[k - kDirections]};
        };
        out.hull.reserve(2 * kDirections);
        for (std::size_t k = 0; k < 2 * kDirections; ++k) {
            const auto [a, ra] = side(k);
            const auto [b, rb] = side((k + 1) % (2 * kDirections));
            const double det = a.x * b.y - a.y * b.x;
            out.hull.emplace_back((ra * b.y - rb * a.y) / det, (a.x * rb - b.x * ra) / det);
        }
    }
    return out;
}

bool hullSpan(const ScreenHull& hull, double y0, double y1, double& x0, double& x1) {
    x0 = std::numeric_limits<double>::infinity();
    x1 = -x0;
    // Every edge (a point for a hull of one) clipped to the rows.
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
        const double lo = std::max(std::min(a.y, b.y), y0), hi = std::min(std::max(a.y, b.y), y1);
        if (lo > hi) continue;
        for (const double y : {lo, hi}) {
            const double x = a.y == b.y ? a.x : a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y);
            x0 = std::min({x0, x, a.y == b.y ? b.x : x});
            x1 = std::max({x1, x, a.y == b.y ? b.x : x});
        }
    }
    return x0 <= x1;
}

}  // namespace strata::render
