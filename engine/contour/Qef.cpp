#include "Qef.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace strata::contour {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Jacobi converges quadratically; a 3×3 matrix needs a handful of sweeps.
// The cap only guards against a NaN that never settles.
constexpr int kMaxJacobiSweeps = 32;

double offDiagonal(const Matrix3& a) { return a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2]; }

// One rotation in the (p, q) plane that zeroes a[p][q].
void rotate(Matrix3& a, Matrix3& v, int p, int q) {
    if (a[p][q] == 0.0) return;
    const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
    const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
    const double c = 1.0 / std::sqrt(t * t + 1.0);
    const double s = t * c;
    for (int k = 0; k < 3; ++k) {
        const double akp = a[k][p];
        const double akq = a[k][q];
        a[k][p] = c * akp - s * akq;
        a[k][q] = s * akp + c * akq;
    }
    for (int k = 0; k < 3; ++k) {
        const double apk = a[p][k];
        const double aqk = a[q][k];
        a[p][k] = c * apk - s * aqk;
        a[q][k] = s * apk + c * aqk;
    }
    for (int k = 0; k < 3; ++k) {
        const double vkp = v[k][p];
        const double vkq = v[k][q];
        v[k][p] = c * vkp - s * vkq;
        v[k][q] = s * vkp + c * vkq;
    }
}

}  // namespace

SymmetricEigen symmetricEigen(const Matrix3& matrix) {
    Matrix3 a = matrix;
    Matrix3 v{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    const double scale = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]) + std::sqrt(offDiagonal(a));
    for (int sweep = 0; sweep < kMaxJacobiSweeps; ++sweep) {
        // Stop once the off-diagonal part is below rounding of the diagonal.
        if (!(offDiagonal(a) > 1e-36 * scale * scale)) break;
        rotate(a, v, 0, 1);
        rotate(a, v, 0, 2);
        rotate(a, v, 1, 2);
    }
    SymmetricEigen eigen;
    for (int i = 0; i < 3; ++i) {
        eigen.values[i] = a[i][i];
        eigen.vectors[i] = {v[0][i], v[1][i], v[2][i]};
    }
    return eigen;
}

QefSolution minimizeQef(std::span<const HermiteSample> samples) {
    glm::dvec3 mass(0.0);
    for (const HermiteSample& s : samples) mass += s.point;
    mass /= double(samples.size());
    // Normal equations about the mass point: (AᵀA) d = Aᵀ r with r_i the
    // distance of the mass point from plane i. Working relative to the mass
    // point keeps the right-hand side small and exact where it should be 0.
    Matrix3 ata{};
    glm::dvec3 atb(0.0);
    for (const HermiteSample& s : samples) {
        const glm::dvec3& n = s.normal;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) ata[r][c] += n[r] * n[c];
        }
        atb += n * glm::dot(n, s.point - mass);
    }
    const SymmetricEigen eigen = symmetricEigen(ata);
    const double largest = std::max({eigen.values[0], eigen.values[1], eigen.values[2]});
    QefSolution solution;
    glm::dvec3 step(0.0);
    for (int i = 0; i < 3; ++i) {
        if (!(eigen.values[i] > kQefRelativeEigenvalueCutoff * largest)) continue;
        step += eigen.vectors[i] * (glm::dot(eigen.vectors[i], atb) / eigen.values[i]);
        ++solution.rank;
    }
    solution.point = mass + step;
    for (const HermiteSample& s : samples) {
        const double d = glm::dot(s.normal, solution.point - s.point);
        solution.residual += d * d;
    }
    return solution;
}

}  // namespace strata::contour
