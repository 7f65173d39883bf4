// A leaf's screen rectangle and hull (ViewSetup.h, screenBounds) against
// the vertices' own projection, worked out here with the view's matrix: the
// hull must hold every projected vertex, be their exact convex hull up to
// 64 vertices, and hug a sphere's outline past that.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "ViewSetup.h"

using namespace strata;

namespace {

render::ViewSetup viewOf(camera::Projection projection) {
    camera::Camera camera;
    camera.width = 640;
    camera.height = 480;
    camera.eye = {30.0, -40.0, 25.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.projection = projection;
    mesh::Bounds box;
    box.extend(glm::dvec3(-12.0));
    box.extend(glm::dvec3(12.0));
    return render::makeView(camera, box);
}

glm::dvec2 project(const render::ViewSetup& view, const glm::vec3& v) {
    const glm::dvec4 clip = view.viewProjectionD * glm::dvec4(glm::dvec3(v), 1.0);
    return {(clip.x / clip.w + 1.0) * 0.5 * view.width, (clip.y / clip.w + 1.0) * 0.5 * view.height};
}

// How far `p` lies outside the counter-clockwise polygon (0 inside).
double outside(const render::ScreenHull& hull, const glm::dvec2& p) {
    double most = 0.0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
        const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
        const glm::dvec2 edge = b - a;
        const double length = std::hypot(edge.x, edge.y);
        if (length == 0.0) continue;
        const double right = (edge.y * (p.x - a.x) - edge.x * (p.y - a.y)) / length;  // > 0: to the right, outside
        most = std::max(most, right);
    }
    return most;
}

std::vector<glm::vec3> randomPoints(unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-6.0f, 6.0f);
    std::vector<glm::vec3> out;
    for (int i = 0; i < count; ++i) out.emplace_back(u(rng), u(rng) * 0.2f, u(rng));
    return out;
}

std::vector<glm::vec3> sphere(double radius, int rings, int sides) {
    std::vector<glm::vec3> out;
    for (int i = 0; i < rings; ++i) {
        const double polar = std::numbers::pi * (i + 0.5) / rings;
        for (int j = 0; j < sides; ++j) {
            const double around = 2.0 * std::numbers::pi * j / sides;
            out.emplace_back(radius * std::sin(polar) * std::cos(around), radius * std::sin(polar) * std::sin(around),
                             radius * std::cos(polar));
        }
    }
    return out;
}

constexpr camera::Projection kProjections[] = {camera::Projection::Perspective, camera::Projection::Orthographic};

}  // namespace

TEST(ScreenBounds, HoldEveryVertexAndAreTheExactHullUpTo64Vertices) {
    for (camera::Projection p : kProjections) {
        const render::ViewSetup view = viewOf(p);
        for (unsigned seed = 1; seed <= 20; ++seed) {
            const std::vector<glm::vec3> points = randomPoints(seed, 3 + static_cast<int>(seed * 3));
            const render::ScreenBounds b = render::screenBounds(view, points, 4096);
            ASSERT_GE(b.hull.size(), 3u);
            double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
            for (const glm::vec3& v : points) {
                const glm::dvec2 q = project(view, v);
                EXPECT_LE(outside(b.hull, q), 1e-9) << "seed " << seed;
                x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
            }
            // The rectangle: the extents, a pixel of margin, clamped to the frame.
            EXPECT_EQ(b.rect.x, std::max(0, static_cast<int>(std::floor(x0)) - 1));
            EXPECT_EQ(b.rect.y, std::max(0, static_cast<int>(std::floor(y0)) - 1));
            EXPECT_EQ(b.rect.x + b.rect.width, std::min(view.width, static_cast<int>(std::ceil(x1)) + 1));
            EXPECT_EQ(b.rect.y + b.rect.height, std::min(view.height, static_cast<int>(std::ceil(y1)) + 1));
            // Exact up to 64 vertices: each corner is a projected vertex.
            for (const glm::dvec2& corner : b.hull) {
                bool found = false;
                for (const glm::vec3& v : points) found = found || glm::length(project(view, v) - corner) < 1e-9;
                EXPECT_TRUE(found) << "seed " << seed << ": a corner that is no vertex";
            }
            // The same hull at the limit of vertices, none past it.
            EXPECT_EQ(render::screenBounds(view, points, points.size()).hull, b.hull);
            EXPECT_TRUE(render::screenBounds(view, points, points.size() - 1).hull.empty());
            EXPECT_EQ(render::screenBounds(view, points, 0).rect.width, b.rect.width);
        }
    }
}

TEST(ScreenBounds, ManyVerticesTakeASixteenSidedBoundThatHugsASphere) {
    for (camera::Projection p : kProjections) {
        const render::ViewSetup view = viewOf(p);
        const std::vector<glm::vec3> ball = sphere(5.0, 24, 48);  // 1,152 vertices
        const render::ScreenBounds b = render::screenBounds(view, ball, 4096);
        ASSERT_EQ(b.hull.size(), 16u);
        // Holds every vertex.
        glm::dvec2 centre(0.0);
        for (const glm::vec3& v : ball) {
            EXPECT_LE(outside(b.hull, project(view, v)), 1e-9);
            centre += project(view, v);
        }
        centre /= static_cast<double>(ball.size());
        // And hugs the outline: each corner lies within 3 % of the outline's
        // farthest vertex from the centre (a circle's 16-gon: 2 %; a
        // perspective outline is an ellipse, nearly a circle here).
        double radius = 0.0;
        for (const glm::vec3& v : ball) radius = std::max(radius, glm::length(project(view, v) - centre));
        for (const glm::dvec2& corner : b.hull) EXPECT_LE(glm::length(corner - centre), radius * 1.03);
    }
}

TEST(ScreenBounds, AVertexAtTheNearPlaneGivesTheWholeFrameAndNoHull) {
    const render::ViewSetup view = viewOf(camera::Projection::Perspective);
    std::vector<glm::vec3> points = randomPoints(7, 20);
    points.push_back(glm::vec3(view.eyeD + view.forwardD * (view.nearPlane * 0.5)));
    const render::ScreenBounds b = render::screenBounds(view, points, 4096);
    EXPECT_EQ(b.rect.x, 0);
    EXPECT_EQ(b.rect.y, 0);
    EXPECT_EQ(b.rect.width, view.width);
    EXPECT_EQ(b.rect.height, view.height);
    EXPECT_TRUE(b.hull.empty());
}
