#pragma once
// What every pass needs to know about the view: the camera of the contract
// turned into float matrices, near and far planes fitted to the scene, and
// screen rectangles. OpenGL's window coordinates: rows count from the bottom.

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/mesh/Mesh.h"

namespace strata::render {

// A rectangle of pixels, [x, x + width) by [y, y + height), y from the bottom row.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
    bool intersects(const PixelRect& o) const {
        return x < o.x + o.width && o.x < x + width && y < o.y + o.height && o.y < y + height;
    }
    // The pixels in both (empty when they do not meet).
    PixelRect intersection(const PixelRect& o) const {
        const int x0 = std::max(x, o.x), y0 = std::max(y, o.y);
        const int x1 = std::min(x + width, o.x + o.width), y1 = std::min(y + height, o.y + o.height);
        return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
    }
    // The least rectangle holding both (an empty one adds nothing).
    PixelRect bounding(const PixelRect& o) const {
        if (o.empty()) return *this;
        if (empty()) return o;
        const int x0 = std::min(x, o.x), y0 = std::min(y, o.y);
        const int x1 = std::max(x + width, o.x + o.width), y1 = std::max(y + height, o.y + o.height);
        return {x0, y0, x1 - x0, y1 - y0};
    }
    // `margin` pixels more on every side (empty stays empty).
    PixelRect grown(int margin) const {
        return empty() ? *this : PixelRect{x - margin, y - margin, width + 2 * margin, height + 2 * margin};
    }
};

struct ViewSetup {
    int width = 0, height = 0;
    bool orthographic = false;
    double nearPlane = 0.0, farPlane = 0.0;  // view depths dot(P - eye, f)
    glm::dmat4 viewProjectionD{1.0};
    glm::mat4 viewProjection{1.0f};
    glm::vec3 eye{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
    glm::dvec3 eyeD{0.0}, forwardD{0.0};
    glm::vec2 halfExtent{0.0f};  // perspective: tan(fov/2) * (W/H, 1)
    double coincidence = 0.0;    // coincidenceTolerance (Camera.h) of the scene's box in this view
};

// Near = max(a small fraction of the scene's size, its nearest depth less a
// margin), so nothing is clipped but by the near plane when the eye is inside
// the scene; far beyond the farthest depth. Throws strata::Error on a camera
// that cannot make an image (zero size, eye == center, bad field of view).
ViewSetup makeView(const camera::Camera& camera, const mesh::Bounds& sceneBounds);

// Whether all of `box` lies beyond the near plane: then every ray starts
// outside every solid in it.
bool beyondNearPlane(const ViewSetup& view, const mesh::Bounds& box);

// The pixels that `box` can cover (with a pixel of margin), clamped to the
// frame; the whole frame when the box reaches the near plane.
PixelRect screenRect(const ViewSetup& view, const mesh::Bounds& box);

// The pixels that the triangles over `vertices` can cover (with a pixel of
// margin): tighter than the box's rectangle. The whole frame when a vertex
// lies at or before the near plane.
PixelRect screenRect(const ViewSetup& view, std::span<const glm::vec3> vertices);

// A convex polygon on the screen (frame pixels, counter-clockwise).
using ScreenHull = std::vector<glm::dvec2>;

// The rectangle above, and a convex hull of `vertices` on the screen: every
// pixel centre their triangles cover lies inside it. A long, thin solid
// seen aslant covers a small part of its rectangle, and the hull says
// which. Both from one projection of the vertices: what a frame asks of
// each leaf. The hull is their own up to 64 vertices, past that the
// sixteen-sided polygon of their extents in eight directions and their
// opposites. Empty (unknown: use the rectangle) when a vertex lies at or
// before the near plane, or past `mostHullVertices` of them (0: no hull).
struct ScreenBounds {
    PixelRect rect;
    ScreenHull hull;
};
ScreenBounds screenBounds(const ViewSetup& view, std::span<const glm::vec3> vertices, std::size_t mostHullVertices);

// The least and greatest x of `hull` within the rows y0 <= y <= y1; false
// when the hull does not reach those rows.
bool hullSpan(const ScreenHull& hull, double y0, double y1, double& x0, double& x1);

}  // namespace strata::render
