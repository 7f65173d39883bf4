#pragma once
// The quadratic error function of dual contouring: the point that is nearest,
// in the least-squares sense, to the tangent planes of a patch's crossings.

#include <array>
#include <span>

#include <glm/vec3.hpp>

namespace strata::contour {

// One crossing of the surface with a cell edge: where, and the outward unit
// normal there.
struct HermiteSample {
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0};
};

// Eigenvalues of AᵀA below this fraction of the largest are treated as zero.
// The eigenvalues count, roughly, how many crossings see each direction of
// normal: a flat patch has one large eigenvalue, an edge two, a corner three.
// On a curved surface the spread of normals across a cell of size h and
// curvature k gives eigenvalues about (k h)² of the largest; below 0.01 (a
// tenth in singular values) the patch is read as flat and its vertex stays at
// the mass point, where tangent-plane intersections would only add noise.
// A sharp corner whose faces each give at least one crossing in twelve still
// keeps all three directions (1/12 > 0.01 for perpendicular faces).
inline constexpr double kQefRelativeEigenvalueCutoff = 0.01;

struct QefSolution {
    glm::dvec3 point{0.0};  // the minimizer nearest the mass point
    int rank = 0;           // eigenvalues kept: 1 flat, 2 an edge, 3 a corner
    double residual = 0.0;  // sum of squared distances of `point` from the planes
};

// The minimizer of sum (n_i · (x - p_i))² nearest the samples' mass point:
// the mass point moved by the truncated pseudo-inverse, so flat directions
// stay at the mass point and sharp edges and corners come out exactly.
// Samples must not be empty.
QefSolution minimizeQef(std::span<const HermiteSample> samples);

// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations:
// values[i] belongs to the column vector vectors[i].
struct SymmetricEigen {
    std::array<double, 3> values{};
    std::array<glm::dvec3, 3> vectors{};
};
SymmetricEigen symmetricEigen(const std::array<std::array<double, 3>, 3>& matrix);

}  // namespace strata::contour
