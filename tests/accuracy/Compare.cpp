#include "Compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"

namespace strata::accuracy {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// Angle between two directions in degrees, accurate for small angles
// (atan2 of |a x b| and a . b, in double). 180 when either is zero or not finite.
double angleDegrees(const glm::vec3& a, const glm::vec3& b) {
    const glm::dvec3 da(a), db(b);
    const double la = glm::length(da), lb = glm::length(db);
    if (!(la > 0.0) || !(lb > 0.0) || !std::isfinite(la) || !std::isfinite(lb)) return 180.0;
    return std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db)) * kRadToDeg;
}

bool isHit(const AovView& image, std::size_t k) { return image.leaf[k] >= 0; }

// Rays and pixel footprints of the camera, for the depth-step test.
class Geometry {
public:
    explicit Geometry(const camera::Camera& camera) : camera_(camera), forward_(camera.forward()) {
        const double t = std::tan(camera.fovDegrees * std::numbers::pi / 360.0);
        if (camera.projection == camera::Projection::Perspective) {
            perspectiveScale_ = 2.0 * t / camera.height;
        } else {
            orthoFootprint_ = 2.0 * glm::length(camera.center - camera.eye) * t / camera.height;
        }
    }

    // The world point at view depth `depth` on pixel (i, j)'s ray.
    glm::dvec3 point(int i, int j, double depth) const {
        const camera::Ray ray = camera_.ray(i, j);
        const double along = glm::dot(ray.direction, forward_);
        return ray.origin + ray.direction * (depth / along);
    }

    // Size of one pixel, in world units, at view depth `depth`.
    double footprint(double depth) const {
        return camera_.projection == camera::Projection::Perspective ? std::abs(depth) * perspectiveScale_
                                                                    : orthoFootprint_;
    }

private:
    camera::Camera camera_;
    glm::dvec3 forward_;
    double perspectiveScale_ = 0.0;
    double orthoFootprint_ = 0.0;
};

// What separates pixels p = (i, j) and q = (i2, j2) of one image: a
// silhouette, leaf boundary, crease or depth step (EdgeKind::Edge), a facet
// boundary (EdgeKind::FacetBoundary), or nothing.
EdgeKind discontinuity(const AovView& image, const Geometry& geometry, const CompareOptions& options, int i, int j,
                       int i2, int j2) {
    const std::size_t p = static_cast<std::size_t>(j) * image.width + i;
    const std::size_t q = static_cast<std::size_t>(j2) * image.width + i2;
    const bool hp = isHit(image, p), hq = isHit(image, q);
    if (hp != hq) return EdgeKind::Edge;
    if (!hp) return EdgeKind::None;
    if (image.leaf[p] != image.leaf[q]) return EdgeKind::Edge;
    const double angle = angleDegrees(image.normal[p], image.normal[q]);
    if (angle > options.creaseDegrees) return EdgeKind::Edge;
    const double zp = image.depth[p], zq = image.depth[q];
    if (!std::isfinite(zp) || !std::isfinite(zq)) return EdgeKind::Edge;
    const glm::dvec3 P = geometry.point(i, j, zp), Q = geometry.point(i2, j2, zq);
    const glm::dvec3 np = glm::dvec3(image.normal[p]), nq = glm::dvec3(image.normal[q]);
    const double offPlane = std::max(std::abs(glm::dot(Q - P, glm::normalize(np))),
                                     std::abs(glm::dot(P - Q, glm::normalize(nq))));
    const double threshold =
        options.stepPixels * geometry.footprint(std::max(zp, zq)) + options.depthTolerance;
    if (!(offPlane <= threshold)) return EdgeKind::Edge;
    return angle > options.facetDegrees ? EdgeKind::FacetBoundary : EdgeKind::None;
}

void markEdges(const AovView& image, const Geometry& geometry, const CompareOptions& options,
               std::vector<EdgeKind>& mask) {
    const int w = image.width, h = image.height;
    // Each unordered neighbour pair once: right, down-left, down, down-right.
    constexpr int kDi[4] = {1, -1, 0, 1};
    constexpr int kDj[4] = {0, 1, 1, 1};
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            for (int n = 0; n < 4; ++n) {
                const int i2 = i + kDi[n], j2 = j + kDj[n];
                if (i2 < 0 || i2 >= w || j2 >= h) continue;
                const EdgeKind kind = discontinuity(image, geometry, options, i, j, i2, j2);
                if (kind == EdgeKind::None) continue;
                EdgeKind& a = mask[static_cast<std::size_t>(j) * w + i];
                EdgeKind& b = mask[static_cast<std::size_t>(j2) * w + i2];
                a = std::max(a, kind);
                b = std::max(b, kind);
            }
        }
    }
}

void checkImage(const AovView& image, const camera::Camera& camera, const char* what) {
    const std::size_t n = static_cast<std::size_t>(std::max(image.width, 0)) * std::max(image.height, 0);
    if (image.width != camera.width || image.height != camera.height) {
        throw Error(std::string("accuracy: the ") + what + " image is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ", the camera's " + std::to_string(camera.width) + "x" +
                    std::to_string(camera.height));
    }
    if (image.depth.size() != n || image.normal.size() != n || image.leaf.size() != n ||
        (!image.cut.empty() && image.cut.size() != n)) {
        throw Error(std::string("accuracy: the ") + what + " image's AOVs do not hold W*H pixels");
    }
}

std::string percent(double fraction) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f%%", 100.0 * fraction);
    return buf;
}

}  // namespace

AovView view(const render::Frame& frame, std::span<const std::uint8_t> cut) {
    return {frame.width, frame.height, frame.depth, frame.normal, frame.leaf, cut};
}

AovView view(const reference::ReferenceImage& image) {
    static_assert(sizeof(int) == sizeof(std::int32_t));
    return {image.width, image.height, image.depth, image.normal,
            std::span<const std::int32_t>(reinterpret_cast<const std::int32_t*>(image.leaf.data()), image.leaf.size()),
            image.cut};
}

CompareOptions optionsForScene(double boundsDiagonal) {
    CompareOptions options;
    options.depthTolerance = 1e-4 * boundsDiagonal;
    return options;
}

const char* verdictName(Verdict v) {
    switch (v) {
        case Verdict::Agree: return "agree";
        case Verdict::Coverage: return "coverage";
        case Verdict::Depth: return "depth";
        case Verdict::Normal: return "normal";
        case Verdict::Leaf: return "leaf";
        case Verdict::Cut: return "cut";
    }
    return "?";
}

void DisagreementCounts::add(Verdict v) {
    switch (v) {
        case Verdict::Agree: break;
        case Verdict::Coverage: ++coverage; break;
        case Verdict::Depth: ++depth; break;
        case Verdict::Normal: ++normal; break;
        case Verdict::Leaf: ++leaf; break;
        case Verdict::Cut: ++cut; break;
    }
}

double CompareResult::agreement() const {
    if (nonEdgePixels == 0) return 1.0;
    return static_cast<double>(nonEdgePixels - nonEdge.total()) / static_cast<double>(nonEdgePixels);
}

double CompareResult::edgeDisagreement() const {
    return pixels == 0 ? 0.0 : static_cast<double>(edge.total()) / static_cast<double>(pixels);
}

std::string CompareResult::summary() const {
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "%dx%d: non-edge agreement %s of %zu pixels (bound >= %s; disagreeing: %zu coverage, %zu depth, "
                  "%zu normal (%zu a neighbour's), %zu leaf, %zu cut); edge pixels %zu, of which %zu disagree = %s of the image (bound <= %s; "
                  "%zu coverage, %zu depth, %zu normal (%zu a neighbour's), %zu leaf, %zu cut); "
                  "max non-edge |dz| %.3g (tolerance %.3g), max normal error %.3g deg; covered %zu gpu / %zu "
                  "reference",
                  width, height, percent(agreement()).c_str(), nonEdgePixels, percent(options.minAgreement).c_str(),
                  nonEdge.coverage, nonEdge.depth, nonEdge.normal, nonEdgeNeighbourNormal, nonEdge.leaf, nonEdge.cut, edgePixels, edge.total(),
                  percent(edgeDisagreement()).c_str(), percent(options.maxEdgeDisagreement).c_str(), edge.coverage,
                  edge.depth, edge.normal, edgeNeighbourNormal, edge.leaf, edge.cut, maxDepthError,
                  options.depthTolerance, maxNormalErrorDegrees, coveredGpu, coveredReference);
    std::string s = buf;
    if (!agreementHolds()) s += " -- NON-EDGE AGREEMENT BELOW BOUND";
    if (!edgeBoundHolds()) s += " -- EDGE DISAGREEMENT ABOVE BOUND";
    return s;
}

std::vector<EdgeKind> edgeMask(const camera::Camera& camera, const AovView& image, const CompareOptions& options) {
    checkImage(image, camera, "given");
    std::vector<EdgeKind> mask(static_cast<std::size_t>(image.width) * image.height, EdgeKind::None);
    markEdges(image, Geometry(camera), options, mask);
    return mask;
}

CompareResult compare(const camera::Camera& camera, const AovView& gpu, const AovView& reference,
                      const CompareOptions& options) {
    checkImage(gpu, camera, "GPU");
    checkImage(reference, camera, "reference");
    if (!(options.depthTolerance > 0.0)) throw Error("accuracy: the depth tolerance must be positive");

    CompareResult r;
    r.options = options;
    r.width = camera.width;
    r.height = camera.height;
    r.pixels = static_cast<std::size_t>(r.width) * r.height;
    r.verdict.assign(r.pixels, Verdict::Agree);
    r.edgeMask.assign(r.pixels, 0);

    const bool compareCut = !gpu.cut.empty() && !reference.cut.empty();
    // The reference's edges only: the GPU image's own discontinuities are
    // what is being judged, and must not excuse themselves.
    r.edgeKind.assign(r.pixels, EdgeKind::None);
    markEdges(reference, Geometry(camera), options, r.edgeKind);

    for (std::size_t k = 0; k < r.pixels; ++k) {
        const bool hg = isHit(gpu, k), hr = isHit(reference, k);
        r.coveredGpu += hg ? 1 : 0;
        r.coveredReference += hr ? 1 : 0;
        Verdict v = Verdict::Agree;
        double depthError = 0.0, normalError = 0.0;
        bool normalCompared = false;
        if (hg != hr) {
            v = Verdict::Coverage;
        } else if (!hg) {
            // Both miss: the contract's miss is depth +inf.
            if (!(std::isinf(gpu.depth[k]) && gpu.depth[k] > 0)) v = Verdict::Depth;
        } else {
            const double dz = std::abs(static_cast<double>(gpu.depth[k]) - static_cast<double>(reference.depth[k]));
            depthError = std::isnan(dz) ? std::numeric_limits<double>::infinity() : dz;
            if (!(depthError <= options.depthTolerance)) {
                v = Verdict::Depth;
            } else {
                normalError = angleDegrees(gpu.normal[k], reference.normal[k]);
                normalCompared = true;
                if (!(normalError <= options.normalToleranceDegrees)) {
                    v = Verdict::Normal;
                } else if (gpu.leaf[k] != reference.leaf[k]) {
                    v = Verdict::Leaf;
                } else if (compareCut && (gpu.cut[k] != 0) != (reference.cut[k] != 0)) {
                    v = Verdict::Cut;
                }
            }
        }
        r.verdict[k] = v;
        bool neighbour = false;  // the GPU normal is a neighbouring reference pixel's, on the same leaf
        if (v == Verdict::Normal) {
            const int i = static_cast<int>(k % r.width), j = static_cast<int>(k / r.width);
            for (int dj = -1; dj <= 1 && !neighbour; ++dj) {
                for (int di = -1; di <= 1 && !neighbour; ++di) {
                    const int i2 = i + di, j2 = j + dj;
                    if ((di == 0 && dj == 0) || i2 < 0 || j2 < 0 || i2 >= r.width || j2 >= r.height) continue;
                    const std::size_t q = static_cast<std::size_t>(j2) * r.width + i2;
                    neighbour = reference.leaf[q] == gpu.leaf[k] &&
                                angleDegrees(gpu.normal[k], reference.normal[q]) <= options.normalToleranceDegrees;
                }
            }
        }
        // Beside a facet boundary only the facet may differ: a normal within
        // the crease angle (another facet of the same smooth surface) at the
        // right depth (the verdict order has checked coverage and depth), on
        // the right leaf with the right cut bit, is an edge disagreement;
        // anything else counts.
        const EdgeKind kind = r.edgeKind[k];
        const bool facetSwap = kind == EdgeKind::FacetBoundary && v == Verdict::Normal &&
                               normalError <= options.creaseDegrees && gpu.leaf[k] == reference.leaf[k] &&
                               !(compareCut && (gpu.cut[k] != 0) != (reference.cut[k] != 0));
        const bool edge = kind == EdgeKind::Edge || facetSwap;
        r.edgeMask[k] = edge ? 1 : 0;
        if (kind == EdgeKind::FacetBoundary) ++r.facetBoundaryPixels;
        if (facetSwap) ++r.facetSwaps;
        if (neighbour) ++(edge ? r.edgeNeighbourNormal : r.nonEdgeNeighbourNormal);
        if (!edge) {
            r.maxDepthError = std::max(r.maxDepthError, depthError);
            if (normalCompared) r.maxNormalErrorDegrees = std::max(r.maxNormalErrorDegrees, normalError);
        }
        if (edge) {
            ++r.edgePixels;
            r.edge.add(v);
        } else {
            ++r.nonEdgePixels;
            r.nonEdge.add(v);
        }
    }
    return r;
}

}  // namespace strata::accuracy
