#include "Orbit.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "strata/core/Error.h"

namespace strata::view {
namespace {

double radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }
double degrees(double radians) { return radians * (180.0 / std::numbers::pi); }

// The smallest distance zooming may reach: below it the eye would sit on the centre.
constexpr double kMinDistance = 1e-6;

struct PresetAngles {
    Preset preset;
    const char* name;
    double tilt, turn;  // OpenSCAD's $vpr x and z for MainWindow::viewAngle*()
};
constexpr std::array<PresetAngles, 7> kPresets{{
    {Preset::Top, "top", 0.0, 0.0},
    {Preset::Bottom, "bottom", 180.0, 0.0},
    {Preset::Left, "left", 90.0, -90.0},
    {Preset::Right, "right", 90.0, 90.0},
    {Preset::Front, "front", 90.0, 0.0},
    {Preset::Back, "back", 90.0, 180.0},
    {Preset::Diagonal, "diagonal", 55.0, 25.0},
}};

// The sine and cosine of an angle in degrees, exact within 1e-9 degrees of
// a multiple of 90 (the preset views, and angles read back from them):
// std::cos(pi / 2) is 6e-17, which would put noise such as 1e-14 into the
// eye and the --camera text where OpenSCAD writes 0.
glm::dvec2 sinCosDegrees(double angle) {
    const double quarters = std::round(angle / 90.0);
    if (std::abs(angle - 90.0 * quarters) < 1e-9) {
        switch (((static_cast<long long>(quarters) % 4) + 4) % 4) {
            case 0: return {0.0, 1.0};
            case 1: return {1.0, 0.0};
            case 2: return {0.0, -1.0};
            default: return {-1.0, 0.0};
        }
    }
    return {std::sin(radians(angle)), std::cos(radians(angle))};
}

// The eye offset from the centre for OpenSCAD's gimbal with no roll:
// Rz(rz) * Rx(rx - 90) * (0, -d, 0), as camera::cameraFromArguments places it.
glm::dvec3 offsetFor(double tilt, double turn, double distance) {
    const glm::dvec2 t = sinCosDegrees(tilt), z = sinCosDegrees(turn);
    return distance * glm::dvec3(t.x * z.x, -t.x * z.y, t.y);
}

}  // namespace

const char* presetName(Preset preset) {
    for (const PresetAngles& p : kPresets)
        if (p.preset == preset) return p.name;
    return "diagonal";
}

Preset presetFromName(std::string_view name) {
    for (const PresetAngles& p : kPresets)
        if (name == p.name) return p.preset;
    throw Error("unknown view '" + std::string(name) +
                "' (valid: top, bottom, left, right, front, back, diagonal)");
}

double Orbit::distance() const { return glm::length(eye - center); }

double Orbit::tiltDegrees() const {
    const double d = distance();
    return d > 0.0 ? degrees(std::acos(std::clamp((eye.z - center.z) / d, -1.0, 1.0))) : 90.0;
}

double Orbit::turnDegrees() const {
    const glm::dvec3 o = eye - center;
    // Straight above or below there is no turn to read; the contract then takes
    // +Y as up, which is the turn 0 view.
    if (std::hypot(o.x, o.y) < 1e-12 * distance()) return 0.0;
    return degrees(std::atan2(o.x, -o.y));
}

void Orbit::orbit(double dx, double dy) {
    // OpenSCAD adds the drag to object_rot; $vpr is its negation (x: 90 - rot).
    const double tilt = std::clamp(tiltDegrees() - kDegreesPerPixel * dy, 0.0, 180.0);
    const double turn = turnDegrees() - kDegreesPerPixel * dx;
    eye = center + offsetFor(tilt, turn, distance());
}

void Orbit::pan(double dx, double dy, int viewWidth, int viewHeight) {
    const camera::Camera c = camera(camera::Camera{});
    const double d = distance();
    const glm::dvec3 move = -c.right() * (dx * kPanPerView * d / std::max(viewWidth, 1)) +
                            c.up() * (dy * kPanPerView * d / std::max(viewHeight, 1));
    eye += move;
    center += move;
}

void Orbit::moveAlongView(double dy, int viewHeight) {
    const camera::Camera c = camera(camera::Camera{});
    const glm::dvec3 move = c.forward() * (dy * kPanPerView * distance() / std::max(viewHeight, 1));
    eye += move;
    center += move;
}

void Orbit::zoom(double notches) {
    const double d = distance();
    const double scaled = std::max(d * std::pow(kZoomPerNotch, notches), kMinDistance);
    eye = center + (eye - center) * (scaled / d);
}

void Orbit::zoomAt(double notches, double x, double y, int width, int height, double fovDegrees) {
    const camera::Camera c = camera(camera::Camera{});
    const double before = distance();
    zoom(notches);
    const double after = distance();
    const double w = std::max(width, 1), h = std::max(height, 1);
    const double ratio = before / after - 1.0;
    const double screenX = 2.0 * (x + 0.5) / w - 1.0;  // -1..1, left to right
    const double screenY = 1.0 - 2.0 * (y + 0.5) / h;  // -1..1, bottom to top
    const double halfHeight = after * std::tan(radians(fovDegrees / 2.0));
    const glm::dvec3 move =
        c.right() * (ratio * screenX * (w / h) * halfHeight) + c.up() * (ratio * screenY * halfHeight);
    eye += move;
    center += move;
}

void Orbit::zoomDrag(double dy) { zoom(-dy * kNotchesPerZoomPixel); }

void Orbit::preset(Preset preset) {
    for (const PresetAngles& p : kPresets)
        if (p.preset == preset) eye = center + offsetFor(p.tilt, p.turn, distance());
}

void Orbit::recenter(const glm::dvec3& point) {
    eye = point + (eye - center);
    center = point;
}

camera::Camera Orbit::camera(const camera::Camera& base) const {
    camera::Camera c = base;
    c.eye = eye;
    c.center = center;
    return c;
}

Orbit fittedOrbit(const mesh::Bounds& bounds, const camera::Camera& base) {
    Orbit orbit = orbitFromCamera(camera::defaultCamera(bounds, base));
    // OpenSCAD backs off until the box's sphere fits the vertical field of
    // view. A view narrower than it is tall (beside a wide panel) would then
    // cut the sphere off at its sides: there the distance fits the
    // horizontal field instead, the narrower of the two.
    if (base.width > 0 && base.width < base.height) {
        const double half = base.fovDegrees * std::numbers::pi / 360.0;
        const double halfAcross = std::atan(double(base.width) / base.height * std::tan(half));
        orbit.eye = orbit.center + (orbit.eye - orbit.center) * (std::sin(half) / std::sin(halfAcross));
    }
    return orbit;
}

Orbit viewAll(const Orbit& orbit, const mesh::Bounds& bounds, const camera::Camera& base) {
    const Orbit fitted = fittedOrbit(bounds, base);
    Orbit result;
    result.center = fitted.center;
    result.eye = fitted.center + offsetFor(orbit.tiltDegrees(), orbit.turnDegrees(), fitted.distance());
    return result;
}

Orbit orbitFromCamera(const camera::Camera& camera) { return Orbit{camera.eye, camera.center}; }

glm::dvec3 pointAtDepth(const camera::Camera& camera, int i, int j, double depth) {
    const camera::Ray ray = camera.ray(i, j);
    const glm::dvec3 f = camera.forward();
    // Solve dot(origin + t * dir - eye, f) = depth for t.
    const double t = (depth - glm::dot(ray.origin - camera.eye, f)) / glm::dot(ray.direction, f);
    return ray.origin + t * ray.direction;
}

std::string cameraArgument(const camera::Camera& camera) {
    const std::array<double, 6> numbers{camera.eye.x,    camera.eye.y,    camera.eye.z,
                                        camera.center.x, camera.center.y, camera.center.z};
    std::string text = "--camera=";
    for (std::size_t k = 0; k < numbers.size(); ++k) {
        std::array<char, 32> buffer{};
        // Shortest round trip: strtod in strata-render reads back the same double.
        const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), numbers[k]);
        if (k > 0) text += ',';
        text.append(buffer.data(), ec == std::errc() ? end : buffer.data());
    }
    return text;
}

}  // namespace strata::view
