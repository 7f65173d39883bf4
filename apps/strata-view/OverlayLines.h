#pragma once
// What the 3D view draws over the CSG image, as line segments, in pure math
// (no GL) so the rules can be unit-tested: OpenSCAD's axes and scale markers
// (GLView::showAxes, showScalemarkers), its small axis cross in the corner
// (GLView::showSmallaxes), and the triangle edges of the leaves for
// "show edges". Overlay.cpp draws them.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/mesh/Mesh.h"

namespace strata::view {

// A segment in world space. OpenSCAD draws the negative half of each axis,
// and its ticks, dashed (glLineStipple(3, 0xAAAA): 3 pixels on, 3 off).
struct WorldSegment {
    glm::dvec3 a, b;
    bool dashed = false;
};

// The scale markers' spacing at camera distance `distance`: a tenth of the
// power of ten at or below it, so it changes only when the view grows or
// shrinks tenfold (OpenSCAD: pow(10, floor(log10(l))) / 10).
double scaleTickSpacing(double distance);

// The axes through the origin as long as the camera distance in each
// direction, and with `ticks` OpenSCAD's scale markers on them: every
// scaleTickSpacing from the origin out to the distance, distance / 60 long,
// every tenth distance / 30; X's ticks point to -Y, Y's and Z's to -X.
std::vector<WorldSegment> axisSegments(double distance, bool ticks);

// A number written beside a scale marker: the tick on `axis` (0 X, 1 Y,
// 2 Z) at signed position `at`, and its text.
struct ScaleLabel {
    int axis = 0;
    double at = 0.0;
    std::string text;
};

// The numbers OpenSCAD writes beside the scale markers at camera distance
// `distance`, on every half axis: at each major tick (every tenth), and, while
// the distance is under three times the power of ten below it (few major
// ticks in view), at every second tick too. The text is the tick's distance
// from the origin as C's %g writes it (six significant digits), with a minus
// sign on the negative halves.
std::vector<ScaleLabel> scaleLabels(double distance);

// The labels' characters as line segments, in the plane of the axis and the
// direction its ticks point away from: X's in the XY plane on the +Y side,
// reading along +X seen from above; Y's in the XY plane on the +X side,
// reading along -Y; Z's in the XZ plane on the +X side, reading along -Z
// (seen from the front). With u = distance / 60 (a short tick's length) each
// character is u / 2 wide on a pitch of 3u / 4, and spans u / 4 to 5u / 4
// from the axis, its middle bar at 7u / 8 (OpenSCAD's proportions); the
// first character from the origin is centred on the tick, the rest further
// out. Digits are drawn on six points (two columns, three rows), as a
// seven-segment display would; also '-', '.', 'e' and '+'.
std::vector<WorldSegment> scaleLabelSegments(double distance);

// A segment in the view's pixels (x right, y up from the bottom-left corner).
struct ScreenSegment {
    glm::dvec2 a, b;
    glm::vec3 color;
};

// OpenSCAD's small axis cross: its origin a tenth of the view in from the
// lower-left corner, each axis 1/18 of the view's height long in an
// orthographic view turned as the camera, red X, green Y, blue Z, and the
// letters X, Y, Z (6 pixels tall, in `labelColor`) just past their ends.
std::vector<ScreenSegment> gizmoSegments(const camera::Camera& camera, const glm::vec3& labelColor);

// Each edge of the mesh's triangles once, as pairs of points.
void appendMeshEdges(const mesh::Mesh& mesh, std::vector<glm::vec3>& points);

// OpenSCAD's "axes-color" of a colour scheme (its color-schemes/render/*.json;
// black for the built-in Cornfield).
glm::vec3 axesColor(std::string_view scheme);

}  // namespace strata::view
