// The contract's camera (docs/contract.md, "Camera") and OpenSCAD's
// --camera forms. Expected values are worked out by hand or from OpenSCAD's
// own named views, not by calling the code under test.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "strata/camera/Camera.h"
#include "strata/core/Error.h"

using strata::camera::Camera;
using strata::camera::Projection;

namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << "x";
    EXPECT_NEAR(actual.y, expected.y, tolerance) << "y";
    EXPECT_NEAR(actual.z, expected.z, tolerance) << "z";
}

// A camera looking along +Y from (0,-10,0): f = +Y, r = +X, u = +Z.
Camera frontCamera(int width, int height, double fov, Projection projection) {
    Camera camera;
    camera.eye = {0.0, -10.0, 0.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = width;
    camera.height = height;
    camera.fovDegrees = fov;
    camera.projection = projection;
    return camera;
}

}  // namespace

TEST(Camera, BasisFollowsTheContract) {
    const Camera camera = frontCamera(512, 512, 22.5, Projection::Perspective);
    expectNear(camera.forward(), {0, 1, 0});
    expectNear(camera.right(), {1, 0, 0});
    expectNear(camera.up(), {0, 0, 1});
}

TEST(Camera, LookingStraightDownTakesYAsUp) {
    Camera camera;
    camera.eye = {1.0, 2.0, 30.0};
    camera.center = {1.0, 2.0, -4.0};
    expectNear(camera.forward(), {0, 0, -1});
    // r = cross(f, (0,1,0)) = cross((0,0,-1),(0,1,0)) = (1,0,0); u = cross(r, f) = (0,1,0).
    expectNear(camera.right(), {1, 0, 0});
    expectNear(camera.up(), {0, 1, 0});
}

TEST(Camera, CentrePixelOfAnOddImageLooksAlongForward) {
    Camera camera;
    camera.eye = {3.0, -7.0, 5.0};
    camera.center = {-1.0, 2.0, 0.5};
    camera.width = 101;
    camera.height = 51;
    const auto ray = camera.ray(50, 25);
    expectNear(ray.origin, camera.eye, 0.0);
    expectNear(ray.direction, camera.forward(), 1e-15);
}

TEST(Camera, CornerPixelDirectionsWorkedOutByHand) {
    // W=4, H=2, fov 90: t = 1, a = 2. Pixel (0,0): x = 1/4 - 1 = -0.75, y = 1 - 1/2 = 0.5,
    // direction ~ f + x*t*a*r + y*t*u = (-1.5, 1, 0.5).
    const Camera camera = frontCamera(4, 2, 90.0, Projection::Perspective);
    expectNear(camera.ray(0, 0).direction, glm::normalize(glm::dvec3(-1.5, 1.0, 0.5)));
    // Pixel (3,1), bottom right: x = 7/4 - 1 = 0.75, y = 1 - 3/2 = -0.5.
    expectNear(camera.ray(3, 1).direction, glm::normalize(glm::dvec3(1.5, 1.0, -0.5)));
    // Pixel (2,0): x = 5/4 - 1 = 0.25.
    expectNear(camera.ray(2, 0).direction, glm::normalize(glm::dvec3(0.5, 1.0, 0.5)));
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 4; ++i) {
            EXPECT_NEAR(glm::length(camera.ray(i, j).direction), 1.0, 1e-15);
        }
    }
}

TEST(Camera, OrthographicRaysStartOnTheEyePlane) {
    // h = |C - E| * t = 10 * 1 = 10, a = 2.
    const Camera camera = frontCamera(4, 2, 90.0, Projection::Orthographic);
    const auto corner = camera.ray(0, 0);  // x = -0.75, y = 0.5
    expectNear(corner.origin, {-0.75 * 10 * 2, -10.0, 0.5 * 10});
    expectNear(corner.direction, {0, 1, 0});
    const auto other = camera.ray(3, 1);  // x = 0.75, y = -0.5
    expectNear(other.origin, {15.0, -10.0, -5.0});
    expectNear(other.direction, {0, 1, 0});
}

TEST(Camera, ViewDepthIsAlongForwardNotAlongTheRay) {
    const Camera camera = frontCamera(4, 2, 90.0, Projection::Perspective);
    EXPECT_DOUBLE_EQ(camera.viewDepth({7.0, 5.0, -3.0}), 15.0);
    const auto ray = camera.ray(0, 0);
    // The ray reaches the plane y = 0 (depth 10) at distance 10 / dot(d, f).
    const double t = 10.0 / ray.direction.y;
    EXPECT_NEAR(camera.viewDepth(ray.origin + t * ray.direction), 10.0, 1e-12);
}

// Projecting points of a pixel's ray through projectionMatrix * viewMatrix must
// land on that pixel's centre (rows counted from the top), at the right depth.
TEST(Camera, MatricesAgreeWithRays) {
    for (Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        Camera camera;
        camera.eye = {12.0, -31.0, 17.0};
        camera.center = {1.0, 2.0, -3.0};
        camera.width = 64;
        camera.height = 48;
        camera.fovDegrees = 30.0;
        camera.projection = projection;
        const glm::dmat4 view = camera.viewMatrix();
        const glm::dmat4 clipFromWorld = camera.projectionMatrix(0.5, 500.0);
        for (auto [i, j] : {std::pair{0, 0}, std::pair{63, 47}, std::pair{10, 40}, std::pair{32, 24}}) {
            const auto ray = camera.ray(i, j);
            for (double s : {1.0, 20.0, 60.0}) {
                const glm::dvec3 p = ray.origin + s * ray.direction;
                const glm::dvec4 eye = view * glm::dvec4(p, 1.0);
                EXPECT_NEAR(-eye.z, camera.viewDepth(p), 1e-9);
                const glm::dvec4 clip = clipFromWorld * eye;
                const double px = (clip.x / clip.w + 1.0) / 2.0 * camera.width;
                const double rowFromTop = (1.0 - clip.y / clip.w) / 2.0 * camera.height;
                EXPECT_NEAR(px, i + 0.5, 1e-9);
                EXPECT_NEAR(rowFromTop, j + 0.5, 1e-9);
            }
        }
    }
}

TEST(Camera, PerspectiveDepthMapsNearAndFarToTheClipRange) {
    const Camera camera = frontCamera(8, 8, 45.0, Projection::Perspective);
    const glm::dmat4 m = camera.projectionMatrix(2.0, 100.0) * camera.viewMatrix();
    const glm::dvec4 nearPoint = m * glm::dvec4(0.0, -8.0, 0.0, 1.0);   // depth 2
    const glm::dvec4 farPoint = m * glm::dvec4(0.0, 90.0, 0.0, 1.0);    // depth 100
    EXPECT_NEAR(nearPoint.z / nearPoint.w, -1.0, 1e-12);
    EXPECT_NEAR(farPoint.z / farPoint.w, 1.0, 1e-12);
}

TEST(Camera, VectorFormTakesEyeAndCenter) {
    Camera base;
    base.fovDegrees = 40.0;
    base.width = 320;
    const Camera camera = strata::camera::cameraFromArguments({1, 2, 3, 4, 5, 6}, base);
    expectNear(camera.eye, {1, 2, 3}, 0.0);
    expectNear(camera.center, {4, 5, 6}, 0.0);
    EXPECT_EQ(camera.fovDegrees, 40.0);
    EXPECT_EQ(camera.width, 320);
}

// OpenSCAD 2021.01's named views (mainwin.cc) set object_rot directly; with
// $vpr = (90 - ox, -oy, -oz) they are: top (0,0,0), front (90,0,0),
// right (90,0,90), back (90,0,180), diagonal (55,0,25).
TEST(Camera, GimbalFormMatchesOpenScadNamedViews) {
    const Camera base;
    struct View {
        double rx, ry, rz;
        glm::dvec3 eyeDirection;
    };
    const View views[] = {
        {0, 0, 0, {0, 0, 1}},     // top
        {90, 0, 0, {0, -1, 0}},   // front
        {90, 0, 90, {1, 0, 0}},   // right
        {90, 0, 180, {0, 1, 0}},  // back
        {90, 0, 270, {-1, 0, 0}}, // left
        {180, 0, 0, {0, 0, -1}},  // bottom
    };
    for (const View& v : views) {
        const Camera camera = strata::camera::cameraFromArguments({1, 2, 3, v.rx, v.ry, v.rz, 50}, base);
        expectNear(camera.center, {1, 2, 3}, 1e-12);
        expectNear(camera.eye, glm::dvec3(1, 2, 3) + 50.0 * v.eyeDirection, 1e-12);
    }
}

TEST(Camera, DefaultGimbalLooksFromFrontRightAbove) {
    // $vpr = (55, 0, 25): 55 degrees down from the zenith, turned 25 degrees
    // towards +X from the front: the eye sits along
    // (sin55 sin25, -sin55 cos25, cos55) from the centre.
    const Camera camera = strata::camera::cameraFromArguments({0, 0, 0, 55, 0, 25, 140}, Camera{});
    const glm::dvec3 expected{std::sin(deg(55)) * std::sin(deg(25)), -std::sin(deg(55)) * std::cos(deg(25)),
                              std::cos(deg(55))};
    expectNear(camera.eye, 140.0 * expected, 1e-10);
    // So +X runs mostly right and +Y away and slightly right, as in OpenSCAD's window.
    EXPECT_GT(camera.right().x, 0.9);
    EXPECT_GT(camera.right().y, 0.4);
}

// OpenSCAD's Camera::setup turns the vector form into a gimbal view:
// vpt = center, distance = |center - eye|, $vpr = (90 + atan2(dz, |dxy|), 0, atan2(dy, dx) - 90)
// with dir = center - eye. Both forms must then give the same eye.
TEST(Camera, VectorAndGimbalFormsAgree) {
    const glm::dvec3 eye{-20.0, 35.0, 12.0}, center{3.0, -4.0, 1.5};
    const glm::dvec3 dir = center - eye;
    const double rx = 90.0 + std::atan2(dir.z, std::hypot(dir.x, dir.y)) * 180.0 / kPi;
    const double rz = std::atan2(dir.y, dir.x) * 180.0 / kPi - 90.0;
    const Camera gimbal = strata::camera::cameraFromArguments(
        {center.x, center.y, center.z, rx, 0.0, rz, glm::length(dir)}, Camera{});
    expectNear(gimbal.eye, eye, 1e-10);
    expectNear(gimbal.center, center, 0.0);
}

TEST(Camera, BadArgumentsThrow) {
    using strata::camera::cameraFromArguments;
    EXPECT_THROW(cameraFromArguments({1, 2, 3}, Camera{}), strata::Error);
    EXPECT_THROW(cameraFromArguments({1, 2, 3, 4, 5, 6, 7, 8}, Camera{}), strata::Error);
    EXPECT_THROW(cameraFromArguments({1, 2, 3, 1, 2, 3}, Camera{}), strata::Error);  // eye == center
    EXPECT_THROW(cameraFromArguments({0, 0, 0, 55, 0, 25, 0}, Camera{}), strata::Error);
    EXPECT_THROW(cameraFromArguments({0, 0, 0, 55, 0, 25, -3}, Camera{}), strata::Error);
    EXPECT_THROW(cameraFromArguments({0, 0, NAN, 1, 1, 1}, Camera{}), strata::Error);
    EXPECT_THROW(cameraFromArguments({0, 0, INFINITY, 1, 1, 1}, Camera{}), strata::Error);
}

TEST(Camera, DefaultViewFitsTheBoundsLikeOpenScadViewAll) {
    // Camera::viewAll with autocenter: centre on the box; distance = (|diagonal| / 2) / sin(fov / 2).
    strata::mesh::Bounds bounds;
    bounds.min = {0.0, -2.0, 1.0};
    bounds.max = {10.0, 4.0, 5.0};
    Camera base;
    base.fovDegrees = 22.5;
    const Camera camera = strata::camera::defaultCamera(bounds, base);
    const glm::dvec3 centre{5.0, 1.0, 3.0};
    const double radius = std::sqrt(10.0 * 10.0 + 6.0 * 6.0 + 4.0 * 4.0) / 2.0;
    const double distance = radius / std::sin(deg(22.5 / 2.0));
    expectNear(camera.center, centre, 1e-12);
    EXPECT_NEAR(glm::length(camera.eye - camera.center), distance, 1e-9);
    const glm::dvec3 direction{std::sin(deg(55)) * std::sin(deg(25)), -std::sin(deg(55)) * std::cos(deg(25)),
                               std::cos(deg(55))};
    expectNear(glm::normalize(camera.eye - camera.center), direction, 1e-12);
    EXPECT_EQ(camera.fovDegrees, 22.5);

    // A wider field of view comes closer.
    base.fovDegrees = 60.0;
    EXPECT_NEAR(glm::length(strata::camera::defaultCamera(bounds, base).eye - centre), radius / 0.5, 1e-9);
}

TEST(Camera, DefaultViewOfNothingIsOpenScadsResetView) {
    const Camera camera = strata::camera::defaultCamera(strata::mesh::Bounds{}, Camera{});
    expectNear(camera.center, {0, 0, 0}, 0.0);
    EXPECT_NEAR(glm::length(camera.eye), 140.0, 1e-10);
    EXPECT_THROW(strata::camera::defaultCamera(strata::mesh::Bounds{}, Camera{.fovDegrees = 0.0}), strata::Error);
}
