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

#include "strata/camera/Camera.h"
#include "strata/mesh/Mesh.h"

namespace strata::view {

enum class Preset { Top, Bottom, Left, Right, Front, Back, Diagonal };

// "top", "bottom", "left", "right", "front", "back", "diagonal"; nullptr-free.
const char* presetName(Preset preset);
// Throws strata::Error("unknown view 'x' (valid: top, ...)").
Preset presetFromName(std::string_view name);

// OpenSCAD's mouse rules (QGLView::mouseMoveEvent, QGLView::wheelEvent,
// Camera::zoom in 2021.01). Every drag's pixels are first scaled by 0.7; then
//   left drag          turns by 1 degree per scaled pixel (0.7 per pixel);
//   right drag         pans by 3 * distance per view width (height) per scaled
//                      pixel: 2.1 * distance per view width of mouse travel;
//   middle drag        moves the centre (and the eye with it) along the view
//                      axis by the same 2.1 * distance per view height of
//                      vertical travel, the distance kept: down comes closer;
//   shift + right or middle drag  zooms by -12 * scaled pixels in wheel units;
//   wheel              scales the distance by 0.9 per 120 units (one notch),
//                      towards the cursor (the "mouse centric zoom"
//                      preference, on by default): the centre moves so the
//                      point under the cursor in the centre's plane stays put.
// So a zoom drag is 12 * 0.7 / 120 = 0.07 notches per pixel, down moving away.
inline constexpr double kDragScale = 0.7;
inline constexpr double kDegreesPerPixel = kDragScale;
inline constexpr double kZoomPerNotch = 0.9;
inline constexpr double kWheelUnitsPerNotch = 120.0;
inline constexpr double kZoomUnitsPerDrag = 12.0;
inline constexpr double kNotchesPerZoomPixel = kZoomUnitsPerDrag * kDragScale / kWheelUnitsPerNotch;
inline constexpr double kPanPerView = 3.0 * kDragScale;

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
    // Middle drag by dy pixels (y down) in a view viewHeight tall: moves eye and
    // centre together along the view axis, forward when dragging down; the
    // distance stays. OpenSCAD ignores the horizontal part of this drag.
    void moveAlongView(double dy, int viewHeight);
    // Wheel notches (positive: closer); the centre stays.
    void zoom(double notches);
    // Wheel notches with the cursor at pixel (x, y) (row 0 at the top) of a
    // view width x height with vertical field of view fovDegrees: the zoom,
    // then OpenSCAD's QGLView::zoomCursor shift of the centre in the view plane.
    void zoomAt(double notches, double x, double y, int width, int height, double fovDegrees);
    // Shift + right (or middle) drag by dy pixels, y down: down moves away.
    void zoomDrag(double dy);
    // One of OpenSCAD's View menu angles, keeping centre and distance.
    void preset(Preset preset);
    // Makes `point` the centre, keeping the view direction and distance
    // (OpenSCAD's double click).
    void recenter(const glm::dvec3& point);

    // The contract's camera with this eye and centre; the rest from `base`.
    camera::Camera camera(const camera::Camera& base) const;
};

// OpenSCAD's default view fitted to `bounds` (camera::defaultCamera); in a
// view narrower than it is tall, backed off further until the box's sphere
// fits the width too.
Orbit fittedOrbit(const mesh::Bounds& bounds, const camera::Camera& base);
// "View all": the fitted centre and distance, but this orbit's angles.
Orbit viewAll(const Orbit& orbit, const mesh::Bounds& bounds, const camera::Camera& base);
Orbit orbitFromCamera(const camera::Camera& camera);

// The world point seen at pixel (i, j) (row 0 at the top) at view depth
// `depth` (the depth AOV's dot(P - eye, f)).
glm::dvec3 pointAtDepth(const camera::Camera& camera, int i, int j, double depth);

// "--camera=EX,EY,EZ,CX,CY,CZ" exactly as strata-render reads it, each number
// the shortest decimal that reads back to the same double.
std::string cameraArgument(const camera::Camera& camera);

}  // namespace strata::view
