// The QEF solve and its 3×3 eigen solver.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "Qef.h"

using namespace strata::contour;

TEST(ContourQef, EigenDecompositionReconstructsTheMatrix) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        std::array<std::array<double, 3>, 3> m{};
        for (int r = 0; r < 3; ++r) {
            for (int c = r; c < 3; ++c) m[r][c] = m[c][r] = value(random);
        }
        const SymmetricEigen e = symmetricEigen(m);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(glm::length(e.vectors[i]), 1.0, 1e-12);
            for (int r = 0; r < 3; ++r) {
                double mv = 0.0;
                for (int c = 0; c < 3; ++c) mv += m[r][c] * e.vectors[i][c];
                EXPECT_NEAR(mv, e.values[i] * e.vectors[i][r], 1e-12);
            }
        }
    }
}

TEST(ContourQef, ThreePlanesMeetAtTheirCorner) {
    const glm::dvec3 corner(0.3125, 0.71875, 0.4375);
    const std::vector<HermiteSample> samples{
        {{corner.x, 0.0, 1.0}, {1.0, 0.0, 0.0}},
        {{corner.x, 1.0, 0.0}, {1.0, 0.0, 0.0}},
        {{0.0, corner.y, 0.0}, {0.0, 1.0, 0.0}},
        {{0.0, 0.0, corner.z}, {0.0, 0.0, -1.0}},
    };
    const glm::dvec3 x = minimizeQef(samples).point;
    EXPECT_EQ(x, corner);
}

TEST(ContourQef, AFlatPatchKeepsItsMassPoint) {
    const std::vector<HermiteSample> samples{
        {{0.0, 0.0, 0.5}, {0.0, 0.0, 1.0}},
        {{1.0, 0.0, 0.5}, {0.0, 0.0, 1.0}},
        {{1.0, 1.0, 0.5}, {0.0, 0.0, 1.0}},
        {{0.0, 0.75, 0.5}, {0.0, 0.0, 1.0}},
    };
    const glm::dvec3 x = minimizeQef(samples).point;
    EXPECT_DOUBLE_EQ(x.x, 0.5);
    EXPECT_DOUBLE_EQ(x.y, 0.4375);
    EXPECT_DOUBLE_EQ(x.z, 0.5);
}

// Two planes: the point on their edge line nearest the mass point.
TEST(ContourQef, AnEdgeProjectsTheMassPointOntoIt) {
    const std::vector<HermiteSample> samples{
        {{0.25, 0.0, 0.0}, {1.0, 0.0, 0.0}},
        {{0.25, 0.0, 1.0}, {1.0, 0.0, 0.0}},
        {{0.0, 0.5, 0.0}, {0.0, 1.0, 0.0}},
        {{0.0, 0.5, 1.0}, {0.0, 1.0, 0.0}},
    };
    const glm::dvec3 x = minimizeQef(samples).point;
    EXPECT_DOUBLE_EQ(x.x, 0.25);
    EXPECT_DOUBLE_EQ(x.y, 0.5);
    EXPECT_DOUBLE_EQ(x.z, 0.5);
}
