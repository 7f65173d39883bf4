#pragma once
// The accuracy comparison: the GPU frame against the CPU reference,
// pixel by pixel, for one scene and camera.
//
// Per pixel (both images W*H, row 0 at the top, index j*W + i):
//   coverage  both hit or both miss (hit: leaf id >= 0);
//   depth     |dz| <= depthTolerance (1e-4 of the scene's bounding-box
//             diagonal); a miss must have depth +inf;
//   normal    within normalToleranceDegrees (1 degree);
//   leaf      the same leaf id;
//   cut       the same cut bit (the leaf acts subtracted there and its face
//             takes the cut-face colour), where both images carry one.
// A pixel AGREES when all five hold. The first that fails names its verdict,
// in that order. The shaded colour is a function of the normal, the leaf and
// the cut bit (and of the neighbours' normals: the outline), so a pixel that
// agrees in all five is shaded alike.
//
// Edge pixels are counted apart. They are defined by the REFERENCE image
// alone (the CPU reference is the oracle; a GPU image must not be able to
// excuse its own errors by making edges of them). In the reference image,
// two of the 8 neighbours are separated by
//   - an EDGE when coverage differs, or the leaf id differs, or the normals
//     differ by more than creaseDegrees (30), or the depth steps: either
//     pixel's surface point lies off the other's tangent plane by more than
//     stepPixels pixel footprints (+ the depth tolerance);
//   - else a FACET BOUNDARY when the normals differ by more than
//     facetDegrees (1, the normal tolerance): every boundary between two
//     facets of a tessellated sphere, cylinder or torus.
//
//      . . . . .      x: a silhouette between two pixel rows
//      . . . . .      e: edge pixels, within one pixel of it
//      e e e e e
//     -x-x-x-x-x-
//      e e e e e
//
// A pixel beside an edge is an EDGE PIXEL, whatever its verdict. A pixel
// beside a facet boundary (and no edge) is an edge pixel when its only
// disagreement is its normal, by at most creaseDegrees: the pixel centre
// lies on the boundary (or on a sliver facet, or at a vertex where several
// meet), and the rasterizer and the exact ray test gave it to different
// facets of the same smooth surface. Any other disagreement there (coverage,
// depth, leaf, cut, a normal further off) counts as a non-edge one: the
// depth, the coverage and the leaf are continuous across a facet boundary,
// so only the facet may differ.
//
// So a GPU pixel that differs next to a reference silhouette (a silhouette
// one pixel off, a GPU pixel covered where the reference is not) is at an
// edge; a GPU pixel that differs away from the reference's edges (a pinhole,
// a speckle of another leaf, a wrong region) is not, whatever edges the GPU
// image itself has.
//
// The bounds (both must hold for passed()):
//   - agreement >= minAgreement (99.99%) of the NON-edge pixels; at 96x96
//     that allows no disagreement at all, at 128x128 one;
//   - disagreeing EDGE pixels <= maxEdgeDisagreement (1%) of the whole image.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/camera/Camera.h"
#include "strata/reference/RayCaster.h"
#include "strata/render/Renderer.h"

namespace strata::accuracy {

// The AOVs that are compared, borrowed from a render::Frame or a
// reference::ReferenceImage (or made up by a test).
struct AovView {
    int width = 0;
    int height = 0;
    std::span<const float> depth;        // W*H; +inf on a miss
    std::span<const glm::vec3> normal;   // W*H; unit, world space
    std::span<const std::int32_t> leaf;  // W*H; -1 on a miss
    // W*H; 1 where the visible leaf acts subtracted (its cut-face colour
    // shows). Empty: not known, and the cut is not compared.
    std::span<const std::uint8_t> cut;
};

// A Frame carries no cut bit (shownCut() reads it back from the shading);
// `cut`, when given, is W*H values for it.
AovView view(const render::Frame& frame, std::span<const std::uint8_t> cut = {});
AovView view(const reference::ReferenceImage& image);

struct CompareOptions {
    double depthTolerance = 0.0;          // world units; required > 0
    double normalToleranceDegrees = 1.0;
    // A larger normal change between neighbours of the reference image is a
    // crease, an edge. Above the facet angles of the corpus's curved
    // primitives ($fn >= 16: 22.5 deg): their facet boundaries are not edges
    // for every verdict, only for a swapped facet (facetDegrees).
    double creaseDegrees = 30.0;
    // A larger normal change (up to creaseDegrees) is a facet boundary. The
    // normal tolerance: two facets whose normals could fail the normal check
    // when swapped are a facet boundary, so every one of a curved surface is.
    double facetDegrees = 1.0;
    double stepPixels = 0.5;              // a larger off-plane step (in pixel footprints) is a depth edge
    double minAgreement = 0.9999;         // of the non-edge pixels
    double maxEdgeDisagreement = 0.01;    // of all pixels
};

// The accuracy suite's bounds for a scene: depth tolerance 1e-4 of the bounding-box diagonal.
CompareOptions optionsForScene(double boundsDiagonal);

// What separates a pixel from its neighbours in the reference image.
enum class EdgeKind : std::uint8_t { None = 0, FacetBoundary = 1, Edge = 2 };

enum class Verdict : std::uint8_t { Agree, Coverage, Depth, Normal, Leaf, Cut };
const char* verdictName(Verdict v);

struct DisagreementCounts {
    std::size_t coverage = 0, depth = 0, normal = 0, leaf = 0, cut = 0;
    std::size_t total() const { return coverage + depth + normal + leaf + cut; }
    void add(Verdict v);
};

struct CompareResult {
    int width = 0, height = 0;
    std::size_t pixels = 0;
    std::size_t coveredReference = 0, coveredGpu = 0;
    std::size_t edgePixels = 0, nonEdgePixels = 0;
    DisagreementCounts nonEdge;     // disagreements among non-edge pixels
    DisagreementCounts edge;        // disagreements among edge pixels
    // Of nonEdge.normal and edge.normal: pixels whose GPU normal is (within
    // tolerance) the reference normal of a neighbour, on the same leaf: the
    // ray passes within rounding of the boundary between two facets and the
    // paths chose different facets. Beside a facet boundary or an edge of
    // the reference they are edge pixels and count against the edge bound.
    std::size_t nonEdgeNeighbourNormal = 0;
    std::size_t edgeNeighbourNormal = 0;
    std::size_t facetBoundaryPixels = 0;  // beside a facet boundary of the reference and no edge
    std::size_t facetSwaps = 0;           // of those, edge pixels: the GPU shows the neighbouring facet
    double maxDepthError = 0.0;     // world units, over non-edge pixels that both hit
    double maxNormalErrorDegrees = 0.0;  // over non-edge pixels whose coverage and depth agree
    std::vector<Verdict> verdict;   // W*H
    std::vector<std::uint8_t> edgeMask;  // W*H; 1 for edge pixels (as counted: facet swaps included)
    std::vector<EdgeKind> edgeKind;      // W*H; the reference image's edgeMask()
    CompareOptions options;

    double agreement() const;            // agreeing non-edge pixels / non-edge pixels (1 when none)
    double edgeDisagreement() const;     // disagreeing edge pixels / pixels
    bool agreementHolds() const { return agreement() >= options.minAgreement; }
    bool edgeBoundHolds() const { return edgeDisagreement() <= options.maxEdgeDisagreement; }
    bool passed() const { return agreementHolds() && edgeBoundHolds(); }
    // One paragraph: the figures against the bounds, and which ones fail.
    std::string summary() const;
};

// Compares `gpu` with `reference`, both rendered with `camera` (whose rays
// and footprints the depth-step test uses). Throws strata::Error when the
// sizes differ from each other or from the camera's.
CompareResult compare(const camera::Camera& camera, const AovView& gpu, const AovView& reference,
                      const CompareOptions& options);

// What each pixel of one image is beside (the strongest of its 8
// neighbours' separations), as compare() computes it for the reference image.
std::vector<EdgeKind> edgeMask(const camera::Camera& camera, const AovView& image, const CompareOptions& options);

}  // namespace strata::accuracy
