// strata-view's camera math (apps/strata-view/Orbit.h): OpenSCAD's gimbal
// angles, its mouse factors, and the --camera= argument's exact round trip.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "Orbit.h"
#include "strata/core/Error.h"

using namespace strata;
using view::Orbit;
using view::Preset;

namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// The eye camera::cameraFromArguments places for OpenSCAD's gimbal form.
glm::dvec3 gimbalEye(const glm::dvec3& center, double rx, double rz, double distance) {
    return camera::cameraFromArguments({center.x, center.y, center.z, rx, 0.0, rz, distance}, camera::Camera{}).eye;
}

}  // namespace

TEST(Orbit, PresetsMatchOpenScadGimbalAngles) {
    const glm::dvec3 c{1, 2, 3};
    Orbit orbit{c + glm::dvec3(0, -10, 0), c};
    const struct {
        Preset preset;
        double rx, rz;
    } cases[] = {{Preset::Top, 0, 0},     {Preset::Bottom, 180, 0}, {Preset::Left, 90, -90}, {Preset::Right, 90, 90},
                 {Preset::Front, 90, 0},  {Preset::Back, 90, 180},  {Preset::Diagonal, 55, 25}};
    for (const auto& k : cases) {
        orbit.preset(k.preset);
        expectNear(orbit.eye, gimbalEye(c, k.rx, k.rz, 10.0));
        expectNear(orbit.center, c);
    }
    orbit.preset(Preset::Left);
    EXPECT_LT(orbit.eye.x, c.x - 9.9);  // the left view looks from -X
    orbit.preset(Preset::Top);
    EXPECT_GT(orbit.eye.z, c.z + 9.9);
}

TEST(Orbit, PresetsPutTheEyeExactlyOnTheAxes) {
    // No 1e-14 where OpenSCAD writes 0: the six axis views land on exact
    // coordinates, and the --camera text has no exponent in it.
    const glm::dvec3 c{1, 2, 3};
    Orbit orbit{c + glm::dvec3(0, -10, 0), c};
    const struct {
        Preset preset;
        glm::dvec3 offset;
    } cases[] = {{Preset::Top, {0, 0, 10}},    {Preset::Bottom, {0, 0, -10}}, {Preset::Left, {-10, 0, 0}},
                 {Preset::Right, {10, 0, 0}},  {Preset::Front, {0, -10, 0}},  {Preset::Back, {0, 10, 0}}};
    for (const auto& k : cases) {
        orbit.preset(k.preset);
        EXPECT_EQ(orbit.eye, c + k.offset) << view::presetName(k.preset);
        const std::string arg = view::cameraArgument(orbit.camera(camera::Camera{}));
        EXPECT_EQ(arg.find('e', 9), std::string::npos) << arg;
        // Fitting the view keeps the angles read back from the eye exact too.
        mesh::Bounds b;
        b.extend(glm::dvec3(-1, -2, -3));
        b.extend(glm::dvec3(5, 4, 3));
        const Orbit all = view::viewAll(orbit, b, camera::Camera{});
        const glm::dvec3 direction = (all.eye - all.center) / all.distance();
        EXPECT_EQ(direction, k.offset / 10.0) << view::presetName(k.preset);
    }
}

TEST(Orbit, PresetNamesRoundTripAndUnknownIsAnError) {
    for (Preset p : {Preset::Top, Preset::Bottom, Preset::Left, Preset::Right, Preset::Front, Preset::Back,
                     Preset::Diagonal})
        EXPECT_EQ(view::presetFromName(view::presetName(p)), p);
    EXPECT_THROW(view::presetFromName("sideways"), Error);
}

TEST(Orbit, DragTurnsByOpenScadFactorAboutTheCentre) {
    Orbit orbit{gimbalEye({0, 0, 0}, 60, 30, 50), {0, 0, 0}};
    orbit.orbit(10, -20);  // OpenSCAD: $vpr.z -= 0.7 dx, $vpr.x -= 0.7 dy
    expectNear(orbit.eye, gimbalEye({0, 0, 0}, 60 + 14, 30 - 7, 50));
    EXPECT_NEAR(orbit.distance(), 50, 1e-9);
    EXPECT_NEAR(orbit.tiltDegrees(), 74, 1e-9);
    EXPECT_NEAR(orbit.turnDegrees(), 23, 1e-9);
}

TEST(Orbit, TiltStopsAtThePoles) {
    Orbit orbit{{0, -10, 0}, {0, 0, 0}};
    orbit.orbit(0, 1000);  // drag far down: towards the top view, no further
    EXPECT_NEAR(orbit.tiltDegrees(), 0, 1e-9);
    expectNear(orbit.eye, {0, 0, 10});
    orbit.orbit(0, -5000);
    EXPECT_NEAR(orbit.tiltDegrees(), 180, 1e-9);
}

// OpenSCAD 2021.01, QGLView::wheelEvent and Camera::zoom: one notch is 120
// units of angleDelta, and distance *= 0.9^(units / 120).
TEST(Orbit, WheelScalesTheDistanceByPointNinePerNotch) {
    Orbit orbit{{0, -100, 0}, {0, 0, 5}};
    const double d = orbit.distance();
    orbit.zoom(2);
    EXPECT_NEAR(orbit.distance(), d * std::pow(0.9, 240.0 / 120.0), 1e-9);
    expectNear(orbit.center, {0, 0, 5});
    orbit.zoom(1e6);  // never onto the centre
    EXPECT_GT(orbit.distance(), 0.0);
}

// QGLView::zoomCursor: after the zoom, ratio = old / new - 1, sx = 2 (x +
// 0.5) / w - 1, sy = 1 - 2 (y + 0.5) / h, half = new * tan(fov / 2); the object
// moves by -(ratio sx aspect half) right and -(ratio sy half) up, so the centre
// moves by as much the other way, and the point under the cursor in the
// centre's plane stays where it was on the screen.
TEST(Orbit, WheelZoomsTowardsTheCursor) {
    Orbit orbit{{0, -100, 0}, {0, 0, 0}};
    orbit.zoomAt(1, 299.5, 49.5, 400, 200, 22.5);  // one notch in at (+0.5, +0.5) of the view
    const double after = 100 * 0.9, ratio = 100 / after - 1.0;
    const double half = after * std::tan(22.5 / 2 * std::numbers::pi / 180);
    expectNear(orbit.center, {ratio * 0.5 * 2.0 * half, 0, ratio * 0.5 * half});
    EXPECT_NEAR(orbit.distance(), after, 1e-9);
    // The centre-plane point at that pixel before, (0.5 * 2 * h0, 0, 0.5 * h0) with
    // h0 = 100 tan(fov / 2), is still at (0.5, 0.5) of the view.
    const double h0 = 100 * std::tan(22.5 / 2 * std::numbers::pi / 180);
    const glm::dvec3 p{0.5 * 2.0 * h0, 0, 0.5 * h0};
    EXPECT_NEAR((p.x - orbit.center.x) / (2.0 * half), 0.5, 1e-12);
    EXPECT_NEAR((p.z - orbit.center.z) / half, 0.5, 1e-12);
}

// QGLView::mouseMoveEvent with shift held: dy_scaled = 0.7 * dy, then
// Camera::zoom(-12 * dy_scaled): distance *= 0.9^(-12 * 0.7 * dy / 120).
TEST(Orbit, ShiftDragZoomsAsOpenScad) {
    Orbit orbit{{0, -100, 0}, {0, 0, 5}};
    const double d = orbit.distance();
    orbit.zoomDrag(100);  // 100 px down: 0.9^-7 = 2.09 times farther
    EXPECT_NEAR(orbit.distance(), d * std::pow(0.9, -12.0 * 0.7 * 100 / 120.0), 1e-9);
    EXPECT_NEAR(orbit.distance() / d, 2.0908, 1e-4);
    expectNear(orbit.center, {0, 0, 5});
    orbit.zoomDrag(-100);
    EXPECT_NEAR(orbit.distance(), d, 1e-9);
}

// Right drag: mx = 0.7 * dx * 3 * distance / width along the view's right,
// mz = -0.7 * dy * 3 * distance / height along its up, added to the object's
// translation; the centre (minus that translation) moves the other way.
TEST(Orbit, PanMovesEyeAndCentreAsOpenScad) {
    Orbit orbit{{0, -40, 0}, {0, 0, 0}};
    orbit.pan(100, 50, 400, 200);  // right and down: the model follows, the camera goes left and up
    expectNear(orbit.center, {-0.7 * 100 * 3.0 * 40 / 400, 0, 0.7 * 50 * 3.0 * 40 / 200});
    expectNear(orbit.eye - orbit.center, {0, -40, 0});
    // 2.1 distances per view width: a drag across the whole view.
    Orbit across{{0, -10, 0}, {0, 0, 0}};
    across.pan(640, 0, 640, 480);
    expectNear(across.center, {-21, 0, 0});
}

// Middle drag: my = -0.7 * dy * 3 * distance / height along the view axis
// (mx locked at 0), added to the object's translation: the centre moves
// forward by 0.7 * dy * 3 * distance / height, the distance stays.
TEST(Orbit, MiddleDragMovesTheCentreAlongTheViewAxis) {
    Orbit orbit{{0, -40, 30}, {0, 0, 30}};
    orbit.moveAlongView(60, 300);
    const double step = 0.7 * 60 * 3.0 * 40 / 300;
    expectNear(orbit.center, {0, step, 30});
    expectNear(orbit.eye, {0, -40 + step, 30});
    EXPECT_NEAR(orbit.distance(), 40, 1e-9);
    Orbit tilted{{0, -30, 40}, {0, 0, 0}};  // distance 50
    tilted.moveAlongView(-100, 500);         // up: back along the axis
    expectNear(tilted.center, glm::dvec3(0, 30, -40) / 50.0 * (0.7 * -100 * 3.0 * 50 / 500));
    EXPECT_NEAR(tilted.distance(), 50, 1e-9);
}

TEST(Orbit, RecentreKeepsDirectionAndDistance) {
    Orbit orbit{{3, -40, 2}, {1, 1, 1}};
    const glm::dvec3 offset = orbit.eye - orbit.center;
    orbit.recenter({5, 6, 7});
    expectNear(orbit.center, {5, 6, 7});
    expectNear(orbit.eye - orbit.center, offset);
}

TEST(Orbit, PointAtDepthLiesOnThePixelsRayAtThatViewDepth) {
    for (camera::Projection p : {camera::Projection::Perspective, camera::Projection::Orthographic}) {
        camera::Camera cam;
        cam.eye = {4, -30, 9};
        cam.center = {0, 1, 2};
        cam.width = 64;
        cam.height = 48;
        cam.projection = p;
        const glm::dvec3 point = view::pointAtDepth(cam, 50, 7, 25.0);
        EXPECT_NEAR(cam.viewDepth(point), 25.0, 1e-9);
        const camera::Ray ray = cam.ray(50, 7);
        EXPECT_NEAR(glm::length(glm::cross(point - ray.origin, ray.direction)), 0.0, 1e-9);
    }
}

TEST(Orbit, FittedViewIsStrataRendersDefaultCamera) {
    mesh::Bounds b;
    b.extend(glm::dvec3(-1, -2, -3));
    b.extend(glm::dvec3(5, 4, 3));
    camera::Camera base;
    const camera::Camera expected = camera::defaultCamera(b, base);
    const Orbit fitted = view::fittedOrbit(b, base);
    EXPECT_EQ(fitted.eye, expected.eye);
    EXPECT_EQ(fitted.center, expected.center);
    Orbit top = fitted;
    top.preset(Preset::Top);
    const Orbit all = view::viewAll(top, b, base);  // keeps the angles, fits centre and distance
    expectNear(all.center, b.center());
    EXPECT_NEAR(all.distance(), fitted.distance(), 1e-9);
    EXPECT_NEAR(all.tiltDegrees(), 0.0, 1e-6);
}

TEST(Orbit, AViewNarrowerThanTallFitsTheBoxsSphereAcross) {
    mesh::Bounds b;
    b.extend(glm::dvec3(-30, -3, -3));
    b.extend(glm::dvec3(30, 3, 3));
    const double radius = glm::length(b.max - b.min) / 2;
    camera::Camera base;
    base.width = 300;
    base.height = 600;
    // The sphere's edge touches the view's sides: its angular radius seen
    // from the eye is half the horizontal field.
    const double halfAcross = std::atan(300.0 / 600.0 * std::tan(base.fovDegrees * std::numbers::pi / 360.0));
    const Orbit fitted = view::fittedOrbit(b, base);
    EXPECT_NEAR(fitted.distance(), radius / std::sin(halfAcross), 1e-9 * radius);
    expectNear(fitted.center, b.center());
    // The direction is OpenSCAD's default all the same.
    const camera::Camera openscad = camera::defaultCamera(b, base);
    expectNear(glm::normalize(fitted.eye - fitted.center), glm::normalize(openscad.eye - openscad.center));
    // As wide as tall or wider: OpenSCAD's distance exactly.
    base.width = 600;
    EXPECT_EQ(view::fittedOrbit(b, base).eye, camera::defaultCamera(b, base).eye);
}

TEST(Orbit, CameraArgumentReadsBackToTheSameDoubles) {
    camera::Camera cam;
    cam.eye = {0.1 + 0.2, -1.0 / 3.0, 1e-300};
    cam.center = {-0.0, 123456789.123456789, 2.5};
    const std::string arg = view::cameraArgument(cam);
    ASSERT_TRUE(arg.starts_with("--camera="));
    std::stringstream parts(arg.substr(9));
    std::vector<double> numbers;
    for (std::string part; std::getline(parts, part, ',');) numbers.push_back(std::strtod(part.c_str(), nullptr));
    ASSERT_EQ(numbers.size(), 6u);
    EXPECT_EQ(glm::dvec3(numbers[0], numbers[1], numbers[2]), cam.eye);
    EXPECT_EQ(glm::dvec3(numbers[3], numbers[4], numbers[5]), cam.center);
    EXPECT_EQ(view::cameraArgument(camera::cameraFromArguments(numbers, cam)), arg);
}
