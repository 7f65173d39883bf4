#pragma once
// The viewer's camera as OpenSCAD's mouse moves it, in pure math (no GL, no
// window) so it can be unit-tested. The camera is kept as the contract's eye and
// centre (docs/contract.md, "Camera"), not as angles: what the viewer draws and
// what it reports as --camera= are then the same numbers, bit for bit, and
// strata-render given that argument draws the same pixels.
//
// Angles follow OpenSCAD's $vpr with no roll: rx is the tilt from the top view
// (0 looks straight down, 90 level, 180 straight up), rz the turn about Z.

#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "strata/geometry/Mesh.h"
#include "strata/camera/Camera.h"

namespace strata::view {

enum class Preset { Top, Bottom, Left, Right, Front, Back, Diagonal };

// "top", "bottom", "left", "right", "front", "back", "diagonal"; nullptr-free.
const char* presetName(Preset preset);
// Throws strata::Error("unknown view 'x' (valid: top, ...)").
Preset presetFromName(std::string_view name);

// OpenSCAD's mouse factors (QGLView::mouseMoveEvent, Camera::zoom): 0.7 degrees
// per pixel of drag, one wheel notch scales the distance by 0.9, a zoom drag
// of 10 pixels counts as one notch, a pan drag moves 3 * distance per view width.
inline constexpr double kDegreesPerPixel = 0.7;
inline constexpr double kZoomPerNotch = 0.9;
inline constexpr double kPixelsPerZoomNotch = 10.0;
inline constexpr double kPanPerView = 3.0;

struct Orbit {
    glm::dvec3 eye{0.0, -140.0, 0.0};
    glm::dvec3 center{0.0, 0.0, 0.0};

    double distance() const;
    double tiltDegrees() const;  // rx
    double turnDegrees() const;  // rz

    // Left drag by (dx, dy) pixels, y down: turns about the centre. The tilt
    // stops at the poles (0 and 180) because the contract's camera keeps Z up
    // and would flip the image past them.
    void orbit(double dx, double dy);
    // Right drag by (dx, dy) pixels in a view of viewWidth x viewHeight: moves
    // eye and centre together so the model follows the mouse.
    void pan(double dx, double dy, int viewWidth, int viewHeight);
    // Wheel notches (positive: closer); the centre stays.
    void zoom(double notches);
    // Middle drag by dy pixels, y down: down moves away, as OpenSCAD's shift-drag does.
    void zoomDrag(double dy);
    // One of OpenSCAD's View menu angles, keeping centre and distance.
    void preset(Preset preset);
    // Makes `point` the centre, keeping the view direction and distance
    // (OpenSCAD's double click).
    void recenter(const glm::dvec3& point);

    // The contract's camera with this eye and centre; the rest from `base`.
    render::Camera camera(const render::Camera& base) const;
};

// OpenSCAD's default view fitted to `bounds` (render::defaultCamera).
Orbit fittedOrbit(const geometry::Bounds& bounds, const render::Camera& base);
// "View all": the fitted centre and distance, but this orbit's angles.
Orbit viewAll(const Orbit& orbit, const geometry::Bounds& bounds, const render::Camera& base);
Orbit orbitFromCamera(const render::Camera& camera);

// The world point seen at pixel (i, j) (row 0 at the top) at view depth
// `depth` (the depth AOV's dot(P - eye, f)).
glm::dvec3 pointAtDepth(const render::Camera& camera, int i, int j, double depth);

// "--camera=EX,EY,EZ,CX,CY,CZ" exactly as strata-render reads it, each number
// the shortest decimal that reads back to the same double.
std::string cameraArgument(const render::Camera& camera);

}  // namespace strata::view
