#include "strata/camera/Camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"

namespace strata::camera {

namespace {

// OpenSCAD 2021.01, src/Camera.cc: resetView() and viewAll().
constexpr double kDefaultDistance = 140.0;
constexpr glm::dvec3 kDefaultRotation{55.0, 0.0, 25.0};

double radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }

// Rotation by `degrees` about a coordinate axis, as glRotated does (counter-
// clockwise looking down the axis towards the origin), applied to column vectors.
glm::dvec3 rotateX(const glm::dvec3& v, double degrees) {
    const double c = std::cos(radians(degrees)), s = std::sin(radians(degrees));
    return {v.x, c * v.y - s * v.z, s * v.y + c * v.z};
}
glm::dvec3 rotateY(const glm::dvec3& v, double degrees) {
    const double c = std::cos(radians(degrees)), s = std::sin(radians(degrees));
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}
glm::dvec3 rotateZ(const glm::dvec3& v, double degrees) {
    const double c = std::cos(radians(degrees)), s = std::sin(radians(degrees));
    return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

// OpenSCAD's gimbal camera (GLView::setupCamera, then paintGL's glTranslated):
//   modelview = lookAt((0,-d,0), 0, +Z) * Rx(90 - rx) * Ry(-ry) * Rz(-rz) * T(-vpt)
// where rx, ry, rz is $vpr and vpt is $vpt (Camera::setVpr / setVpt). The world
// point that lands on the look-at eye is R^T (0,-d,0) + vpt, the one that lands
// on its centre is vpt. R^T = Rz(rz) * Ry(ry) * Rx(rx - 90).
// The contract's camera is eye and center with world Z up, so a roll (ry != 0)
// moves the eye as OpenSCAD does but does not turn the image about the view
// axis; OpenSCAD's own vector form (Camera::setup) never rolls either.
void placeGimbal(Camera& camera, const glm::dvec3& vpt, const glm::dvec3& vpr, double distance) {
    glm::dvec3 offset{0.0, -distance, 0.0};
    offset = rotateX(offset, vpr.x - 90.0);
    offset = rotateY(offset, vpr.y);
    offset = rotateZ(offset, vpr.z);
    camera.center = vpt;
    camera.eye = vpt + offset;
}

void checkFieldOfView(double fovDegrees) {
    if (!(fovDegrees > 0.0 && fovDegrees < 180.0)) {
        throw Error("camera: field of view must be between 0 and 180 degrees, got " +
                    std::to_string(fovDegrees));
    }
}

}  // namespace

glm::dvec3 Camera::forward() const { return glm::normalize(center - eye); }

glm::dvec3 Camera::right() const {
    const glm::dvec3 f = forward();
    glm::dvec3 r = glm::cross(f, glm::dvec3(0.0, 0.0, 1.0));
    // Looking straight up or down: the contract takes (0,1,0) as up instead.
    if (glm::length(r) < 1e-12) r = glm::cross(f, glm::dvec3(0.0, 1.0, 0.0));
    return glm::normalize(r);
}

glm::dvec3 Camera::up() const { return glm::cross(right(), forward()); }

Ray Camera::ray(int i, int j) const {
    const glm::dvec3 f = forward(), r = right(), u = cross(r, f);
    const double x = 2.0 * (i + 0.5) / width - 1.0;
    const double y = 1.0 - 2.0 * (j + 0.5) / height;
    const double t = std::tan(radians(fovDegrees) / 2.0);
    const double a = static_cast<double>(width) / height;
    if (projection == Projection::Perspective) {
        return Ray{eye, glm::normalize(f + x * t * a * r + y * t * u)};
    }
    const double h = glm::length(center - eye) * t;
    return Ray{eye + x * h * a * r + y * h * u, f};
}

double Camera::viewDepth(const glm::dvec3& p) const { return glm::dot(p - eye, forward()); }

double coincidenceTolerance(const Camera& camera, const mesh::Bounds& box) {
    auto largest = [](const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); };
    double scale = largest(camera.eye);
    if (!box.empty()) {
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 corner{(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                    (k & 4) ? box.max.z : box.min.z};
            scale = std::max({scale, largest(corner), std::abs(camera.viewDepth(corner))});
        }
    }
    constexpr double kFraction = 1.0 / 1048576.0;
    return std::max(scale * kFraction, std::numeric_limits<double>::min());
}

glm::dmat4 Camera::viewMatrix() const {
    // gluLookAt: rows r, u, -f, then the eye moved to the origin. glm is column-major: m[col][row].
    const glm::dvec3 f = forward(), r = right(), u = cross(r, f);
    glm::dmat4 m(1.0);
    for (int k = 0; k < 3; ++k) {
        m[k][0] = r[k];
        m[k][1] = u[k];
        m[k][2] = -f[k];
    }
    m[3][0] = -glm::dot(r, eye);
    m[3][1] = -glm::dot(u, eye);
    m[3][2] = glm::dot(f, eye);
    return m;
}

glm::dmat4 Camera::projectionMatrix(double zNear, double zFar) const {
    const double t = std::tan(radians(fovDegrees) / 2.0);
    const double a = static_cast<double>(width) / height;
    glm::dmat4 m(0.0);
    if (projection == Projection::Perspective) {
        // gluPerspective(fov, a, near, far)
        m[0][0] = 1.0 / (t * a);
        m[1][1] = 1.0 / t;
        m[2][2] = (zFar + zNear) / (zNear - zFar);
        m[2][3] = -1.0;
        m[3][2] = 2.0 * zFar * zNear / (zNear - zFar);
        return m;
    }
    // glOrtho(-h*a, h*a, -h, h, near, far)
    const double h = glm::length(center - eye) * t;
    m[0][0] = 1.0 / (h * a);
    m[1][1] = 1.0 / h;
    m[2][2] = -2.0 / (zFar - zNear);
    m[3][2] = -(zFar + zNear) / (zFar - zNear);
    m[3][3] = 1.0;
    return m;
}

Camera cameraFromArguments(const std::vector<double>& numbers, const Camera& base) {
    if (numbers.size() != 6 && numbers.size() != 7) {
        throw Error("--camera: expected 6 numbers (eye, center) or 7 (translate, rotate, distance), got " +
                    std::to_string(numbers.size()));
    }
    for (double v : numbers) {
        if (!std::isfinite(v)) throw Error("--camera: numbers must be finite");
    }
    Camera camera = base;
    if (numbers.size() == 6) {
        camera.eye = {numbers[0], numbers[1], numbers[2]};
        camera.center = {numbers[3], numbers[4], numbers[5]};
        if (camera.eye == camera.center) throw Error("--camera: eye and center must differ");
    } else {
        if (!(numbers[6] > 0.0)) throw Error("--camera: distance must be positive");
        placeGimbal(camera, {numbers[0], numbers[1], numbers[2]}, {numbers[3], numbers[4], numbers[5]}, numbers[6]);
    }
    return camera;
}

Camera defaultCamera(const mesh::Bounds& bounds, const Camera& base) {
    checkFieldOfView(base.fovDegrees);
    Camera camera = base;
    // Camera::viewAll with autocenter: centre on the box, and back off until a
    // sphere around the box (radius half its diagonal) fits the vertical field
    // of view. An empty box keeps resetView()'s distance at the origin; so does a
    // box of no size, where OpenSCAD would put the eye on the centre.
    glm::dvec3 target{0.0};
    double distance = kDefaultDistance;
    if (!bounds.empty()) {
        target = bounds.center();
        const double radius = glm::length(bounds.max - bounds.min) / 2.0;
        if (radius > 0.0) distance = radius / std::sin(radians(base.fovDegrees) / 2.0);
    }
    placeGimbal(camera, target, kDefaultRotation, distance);
    return camera;
}

}  // namespace strata::camera
