// The plain path (RenderSettings::plainUnions; engine/render/PlainPass.h)
// against the full pipeline: a union of leaves seen from outside, drawn as
// depth-tested geometry, must give the frame that peeling every operand and
// evaluating the tree gives, to the bit (surfaces, normals, leaves and the
// shaded image), ties of faces that several leaves share included. The full
// pipeline is itself checked against the CPU reference and closed forms
// elsewhere (RendererGLTest, the accuracy suite).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "FrameCompare.h"
#include "SphereShells.h"
#include "strata/camera/Camera.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using scene::NodeKind;
using test::pixelsDiffering;

namespace {

constexpr int kSize = 97;

scene::Leaf cubeLeaf(glm::dvec3 min, glm::dvec3 max) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{max - min, false};
    leaf.transform = glm::translate(glm::dmat4(1.0), min);
    return leaf;
}

scene::Leaf sphereLeaf(glm::dvec3 centre, double radius, int fn = 16) {
    scene::Leaf leaf;
    scene::Sphere s;
    s.r = radius;
    s.fragments.fn = fn;
    leaf.primitive = s;
    leaf.transform = glm::translate(glm::dmat4(1.0), centre);
    return leaf;
}

scene::Leaf cylinderLeaf(glm::dvec3 base, double radius, double height) {
    scene::Leaf leaf;
    scene::Cylinder c;
    c.r1 = c.r2 = radius;
    c.h = height;
    c.fragments.fn = 20;
    leaf.primitive = c;
    leaf.transform = glm::translate(glm::dmat4(1.0), base);
    return leaf;
}

camera::Camera cameraAt(glm::dvec3 eye, camera::Projection projection = camera::Projection::Perspective) {
    camera::Camera camera;
    camera.eye = eye;
    camera.center = {0.0, 0.0, 0.0};
    camera.projection = projection;
    camera.width = kSize;
    camera.height = kSize + 6;
    return camera;
}

const camera::Projection kProjections[] = {camera::Projection::Perspective, camera::Projection::Orthographic};

class PlainFrameGLTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        context_ = std::make_unique<gpu::Context>();
        renderer_ = std::make_unique<render::Renderer>();
    }
    static void TearDownTestSuite() {
        renderer_.reset();
        context_.reset();
    }

    static void setScene(const scene::Tree& tree) { renderer_->setScene(tree, model::buildModel(tree)); }

    // The scene set last, drawn plainly and through every pass (each operand
    // its own): the frames agree to the bit (surfaces, normals, leaves and
    // colours) on every pixel but where the full pipeline's coincidence rule
    // drops a chord of one leaf thinner than the tolerance, which the plain
    // path draws, as exact geometry has it (PlainPass.h): a ray grazing the
    // leaf's silhouette. Such a pixel shows the leaf's front face in the
    // plain frame, nothing or a surface behind it in the full one, and lies
    // on the leaf's outline in the plain frame. `look`: the light and
    // outline of both; without the outline the plain frame is lit as drawn,
    // and its colours too are the full pipeline's, to the byte, wherever its
    // surfaces are. Returns the plain frame.
    //
    // `beside`: the scene's root is a union of plain leaves and of a rest
    // with CSG in it, so the plain frame draws those leaves plainly and
    // evaluates the rest after them, and both peel.
    static render::Frame expectPlainEqualsFull(const camera::Camera& camera, const std::string& what,
                                               const render::RenderSettings& look = {}, bool beside = false) {
        render::RenderSettings full = look;
        full.plainUnions = false;
        full.groupOperands = false;
        render::Frame plain = renderer_->render(camera, look);
        const render::Frame apart = renderer_->render(camera, full);
        EXPECT_EQ(plain.stats.plain, !beside) << what;
        EXPECT_EQ(plain.stats.plainBesideLeaves > 0, beside) << what;
        EXPECT_FALSE(apart.stats.plain) << what;
        EXPECT_EQ(apart.stats.plainBesideLeaves, 0u) << what;
        EXPECT_GT(apart.stats.peelPasses, 0) << what;
        if (beside) {
            EXPECT_LT(plain.stats.peelPasses, apart.stats.peelPasses) << what;
        } else {
            EXPECT_EQ(plain.stats.peelPasses, 0) << what;
        }
        const int w = plain.width, h = plain.height;
        auto outline = [&](int x, int y) {
            const std::size_t k = static_cast<std::size_t>(y * w + x);
            for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int u = x + dx, v = y + dy;
                if (u < 0 || v < 0 || u >= w || v >= h) return true;
                if (plain.leaf[static_cast<std::size_t>(v * w + u)] != plain.leaf[k]) return true;
            }
            return false;
        };
        std::size_t grazing = 0, covered = 0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t k = static_cast<std::size_t>(y * w + x);
                covered += plain.leaf[k] >= 0;
                const bool same = plain.leaf[k] == apart.leaf[k] &&
                                  std::memcmp(&plain.depth[k], &apart.depth[k], sizeof(float)) == 0 &&
                                  std::memcmp(&plain.normal[k], &apart.normal[k], sizeof(glm::vec3)) == 0;
                if (same) {
                    if (!look.outline) {
                        EXPECT_EQ(std::memcmp(&plain.rgba[4 * k], &apart.rgba[4 * k], 4), 0)
                            << what << ": the colour of pixel " << x << ", " << y;
                    }
                    continue;
                }
                ++grazing;
                EXPECT_GE(plain.leaf[k], 0) << what << ": pixel " << x << ", " << y;
                EXPECT_TRUE(outline(x, y)) << what << ": pixel " << x << ", " << y << " inside leaf " << plain.leaf[k];
                EXPECT_TRUE(apart.leaf[k] < 0 || apart.depth[k] > plain.depth[k] || apart.leaf[k] == plain.leaf[k])
                    << what << ": pixel " << x << ", " << y;
            }
        }
        // A few pixels of the outlines at most, and the images alike elsewhere.
        EXPECT_LE(grazing * 200, covered) << what;
        return plain;
    }

    // One of OpenSCAD's examples in tests/bench/models as the scene, and
    // its default view at 160 x 120.
    static camera::Camera setModel(const char* name) {
        const scene::Tree tree = scene::parseCsgFile(std::string(STRATA_TEST_DIR) + "/bench/models/" + name + ".csg");
        model::Model model = model::buildModel(tree);
        mesh::Bounds bounds;
        for (const mesh::Mesh& mesh : model.leafMeshes)
            for (const glm::dvec3& p : mesh.positions) bounds.extend(p);
        renderer_->setScene(tree, std::move(model));
        camera::Camera base = cameraAt({0, 0, 0});
        base.width = 160;
        base.height = 120;
        return camera::defaultCamera(bounds, base);
    }

    static std::unique_ptr<gpu::Context> context_;
    static std::unique_ptr<render::Renderer> renderer_;
};

std::unique_ptr<gpu::Context> PlainFrameGLTest::context_;
std::unique_ptr<render::Renderer> PlainFrameGLTest::renderer_;

// A union of `count` coloured spheres, blocks, cylinders and sets of sphere
// shells (non-convex leaves; without `shells`, more spheres), overlapping,
// seeded.
scene::Tree randomUnion(unsigned seed, int count, bool shells = true) {
    scene::Tree tree;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> at(-1.6, 1.6), size(0.15, 0.6), hue(0.2, 1.0);
    std::vector<int> parts;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 c(at(rng), at(rng), 0.5 * at(rng));
        const double r = size(rng);
        scene::Leaf leaf;
        switch (i % 4) {
            case 0: leaf = sphereLeaf(c, r); break;
            case 1: leaf = cubeLeaf(c - glm::dvec3(r), c + glm::dvec3(r, 0.7 * r, 1.3 * r)); break;
            case 2: leaf = cylinderLeaf(c, r, 2 * r); break;
            default:
                if (!shells) {
                    leaf = sphereLeaf(c, 0.8 * r, 24);
                    break;
                }
                leaf.primitive = test::sphereShells({c + glm::dvec3(0, 0, 0.5), c, c - glm::dvec3(0, 0, 0.5)}, r * 0.6, 16);
        }
        if (i % 3 != 0) leaf.color = glm::dvec4(hue(rng), hue(rng), hue(rng), 1.0);
        parts.push_back(tree.addLeaf(leaf));
    }
    tree.root = tree.addNode(NodeKind::Union, parts);
    return tree;
}

}  // namespace

TEST_F(PlainFrameGLTest, RandomUnionsEqualTheFullPipeline) {
    const glm::dvec3 eyes[] = {{0.3, -0.4, 9.0}, {7.0, -5.0, 4.0}, {-3.0, 6.5, -4.0}};
    for (unsigned seed : {11u, 12u, 13u}) {
        setScene(randomUnion(seed, 40));
        for (const glm::dvec3& eye : eyes) {
            for (camera::Projection projection : kProjections) {
                const render::Frame plain = expectPlainEqualsFull(
                    cameraAt(eye, projection), "seed " + std::to_string(seed) + ", projection " +
                                                   std::to_string(static_cast<int>(projection)));
                EXPECT_GT(plain.stats.coveredPixels, std::size_t(kSize * kSize) / 10);
                EXPECT_EQ(plain.stats.peelPasses, 0);
            }
        }
    }
}

TEST_F(PlainFrameGLTest, WithoutTheOutlineLitAsDrawnInEitherLight) {
    setScene(randomUnion(14, 40));
    for (const render::Lighting lighting : {render::Lighting::Strata, render::Lighting::OpenScad}) {
        render::RenderSettings look;
        look.lighting = lighting;
        look.outline = false;
        for (const glm::dvec3& eye : {glm::dvec3(0.3, -0.4, 9.0), glm::dvec3(-3.0, 6.5, -4.0)}) {
            for (camera::Projection projection : kProjections) {
                const render::Frame plain = expectPlainEqualsFull(
                    cameraAt(eye, projection), std::string(render::lightingName(lighting)) + ", projection " +
                                                   std::to_string(static_cast<int>(projection)), look);
                EXPECT_GT(plain.stats.coveredPixels, std::size_t(kSize * kSize) / 10);
            }
        }
    }
}

TEST_F(PlainFrameGLTest, AFaceSharedByLeavesShowsTheLowestLeaf) {
    // Blocks standing in a larger block with their tops in its top's plane,
    // turned by odd angles so that rounding puts the tops a hair apart, this
    // way or that: every pixel of the common top names the first block, as
    // the evaluator's rule does, and the frame is the full pipeline's. The
    // tie pass runs on the leaves whose boxes meet.
    const glm::dmat4 turn = glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(23.0), glm::dvec3(1, 0, 0)),
                                        glm::radians(11.0), glm::dvec3(0, 1, 0));
    scene::Tree tree;
    std::vector<int> blocks;
    for (int k = 0; k < 10; ++k) {
        const double grow = 0.03 * k;
        scene::Leaf leaf = k == 0 ? cubeLeaf({-2, -2, -2}, {2, 2, 1})
                                  : cubeLeaf({-1.5 - grow, -0.5 - grow, -3}, {0.5 + grow, 1.5, 1});
        leaf.transform = turn * leaf.transform;
        leaf.color = glm::dvec4(0.2 + 0.07 * k, 0.5, 0.9 - 0.05 * k, 1.0);
        blocks.push_back(tree.addLeaf(leaf));
    }
    // One more block apart from the rest: no box meets its box.
    scene::Leaf apart = cubeLeaf({2.5, 2.5, -1}, {3.0, 3.0, 0});
    apart.transform = turn * apart.transform;
    blocks.push_back(tree.addLeaf(apart));
    tree.root = tree.addNode(NodeKind::Union, blocks);
    setScene(tree);
    const glm::vec3 up = glm::vec3(turn * glm::dvec4(0, 0, 1, 0));
    for (camera::Projection projection : kProjections) {
        const render::Frame plain = expectPlainEqualsFull(cameraAt(glm::dvec3(up) * 9.0 + glm::dvec3(0.2, 0.1, 0), projection),
                                                          "projection " + std::to_string(static_cast<int>(projection)));
        EXPECT_EQ(plain.stats.tiedLeaves, 10u);
        std::size_t top = 0, lowest = 0;
        for (std::size_t k = 0; k < plain.leaf.size(); ++k) {
            if (plain.leaf[k] < 0 || plain.leaf[k] == blocks.back() || glm::dot(plain.normal[k], up) < 0.999f) continue;
            ++top;
            lowest += plain.leaf[k] == blocks[0];
        }
        EXPECT_GT(top, std::size_t(kSize * kSize) / 10);
        EXPECT_EQ(lowest, top);
    }
}

TEST_F(PlainFrameGLTest, TiesAreSoughtTriangleByTriangle) {
    // A grid of small blocks standing in a large one, every top in one
    // plane, turned so that rounding puts the tops a hair apart: the tie
    // pass draws only the triangles that come near another leaf's (not the
    // blocks' bottoms, nor the outer walls), and the frame is still the
    // full pipeline's, the common top showing the large block.
    const glm::dmat4 turn = glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(17.0), glm::dvec3(1, 0, 0)),
                                        glm::radians(-29.0), glm::dvec3(0, 1, 0));
    scene::Tree tree;
    std::vector<int> parts;
    scene::Leaf base = cubeLeaf({-2.5, -2.5, -1}, {2.5, 2.5, 1});
    base.transform = turn * base.transform;
    parts.push_back(tree.addLeaf(base));
    constexpr int kSide = 5;
    for (int i = 0; i < kSide; ++i) {
        for (int j = 0; j < kSide; ++j) {
            const glm::dvec3 low(-2.0 + 0.8 * i, -2.0 + 0.8 * j, -1.5 - 0.1 * ((i + j) % 3));
            scene::Leaf block = cubeLeaf(low, low + glm::dvec3(0.7, 0.7, 1.0 - low.z));
            block.transform = turn * block.transform;
            block.color = glm::dvec4(0.3 + 0.1 * i, 0.4 + 0.1 * j, 0.5, 1.0);
            parts.push_back(tree.addLeaf(block));
        }
    }
    tree.root = tree.addNode(NodeKind::Union, parts);
    const glm::dvec3 up = glm::dvec3(turn * glm::dvec4(0, 0, 1, 0));
    for (camera::Projection projection : kProjections) {
        // The scene's first frame draws the tying leaves whole; the next sorts out their triangles.
        const camera::Camera camera = cameraAt(up * 9.0 + glm::dvec3(0.3, -0.2, 0), projection);
        setScene(tree);
        const render::Frame whole = expectPlainEqualsFull(camera, "a grid of blocks, first frame");
        EXPECT_EQ(whole.stats.tiedTriangles, 0u);
        const render::Frame plain = expectPlainEqualsFull(camera, "a grid of blocks");
        const std::size_t triangles = parts.size() * 12;
        EXPECT_EQ(plain.stats.tiedLeaves, parts.size());
        EXPECT_GT(plain.stats.tiedTriangles, kSide * kSide * 2u);
        EXPECT_LT(plain.stats.tiedTriangles, triangles);
        std::size_t top = 0, base = 0;
        for (std::size_t k = 0; k < plain.leaf.size(); ++k) {
            if (plain.leaf[k] < 0 || glm::dot(glm::dvec3(plain.normal[k]), up) < 0.999) continue;
            ++top;
            base += plain.leaf[k] == parts[0];
        }
        EXPECT_GT(top, std::size_t(kSize * kSize) / 4);
        EXPECT_EQ(base, top);
    }
}

// randomUnion's leaves and, beside them under the root's union, CSG:
// a block less a ball, whose top a plain block shares and whose cut a
// plain block touches, and a lens (two balls intersected) that a plain
// ball crosses. No sets of shells: where two shells of one leaf cross, the
// full pipeline's one layer of a union's operand can hold one shell's exit
// a hair before the other's entry, and show it flipped, where the plain
// path shows the entry.
scene::Tree unionBesideCsg(unsigned seed, int count) {
    scene::Tree tree = randomUnion(seed, count, false);
    std::vector<int> parts = tree.nodes[static_cast<std::size_t>(tree.root)].children;
    const int block = tree.addLeaf(cubeLeaf({-1.0, -1.0, -0.6}, {0.6, 0.6, 0.4}));
    const int ball = tree.addLeaf(sphereLeaf({0.6, 0.6, 0.4}, 0.7, 24));
    parts.push_back(tree.addNode(NodeKind::Difference, {block, ball}));
    scene::Leaf lensA = sphereLeaf({1.2, -1.0, 0.0}, 0.6), lensB = sphereLeaf({1.6, -1.0, 0.0}, 0.6);
    lensB.color = glm::dvec4(0.9, 0.3, 0.2, 1.0);
    parts.push_back(tree.addNode(NodeKind::Intersection, {tree.addLeaf(lensA), tree.addLeaf(lensB)}));
    // Sharing the block's top, touching its cut from outside, crossing the lens.
    for (scene::Leaf leaf : {cubeLeaf({-1.4, -1.4, -0.2}, {-0.4, -0.4, 0.4}), cubeLeaf({0.6, -0.3, -0.6}, {0.9, 0.3, 0.4}),
                             sphereLeaf({1.4, -1.2, 0.3}, 0.3)}) {
        leaf.color = glm::dvec4(0.4, 0.8, 0.4, 1.0);
        parts.push_back(tree.addLeaf(leaf));
    }
    tree.root = tree.addNode(NodeKind::Union, parts);
    return tree;
}

TEST_F(PlainFrameGLTest, PlainLeavesBesideCsgEqualTheFullPipeline) {
    // The plain leaves drawn first, the CSG evaluated after them: the frame
    // is the full pipeline's, in both looks, from views where the CSG is in
    // front of plain leaves and behind them, and where faces of both tie.
    const glm::dvec3 eyes[] = {{0.3, -0.4, 9.0}, {7.0, -5.0, 4.0}, {-3.0, 6.5, -4.0}};
    for (unsigned seed : {21u, 22u}) {
        setScene(unionBesideCsg(seed, 24));
        for (const glm::dvec3& eye : eyes) {
            for (camera::Projection projection : kProjections) {
                for (const bool outline : {true, false}) {
                    render::RenderSettings look;
                    look.outline = outline;
                    look.plainBesideFrom = 0.0;  // whatever share of the frame they reach alone
                    const std::string what = "seed " + std::to_string(seed) + ", projection " +
                                             std::to_string(static_cast<int>(projection)) +
                                             (outline ? ", outline" : ", lit as drawn");
                    const render::Frame plain = expectPlainEqualsFull(cameraAt(eye, projection), what, look, true);
                    EXPECT_EQ(plain.stats.plainBesideLeaves, 27u) << what;
                    // Both parts show: some pixels a plain leaf's, some the CSG's.
                    std::size_t csg = 0, covered = 0;
                    for (std::int32_t leaf : plain.leaf) {
                        covered += leaf >= 0;
                        csg += leaf >= 24 && leaf < 28;
                    }
                    EXPECT_GT(csg, covered / 50) << what;
                    EXPECT_LT(csg, covered) << what;
                }
            }
        }
    }
}

TEST_F(PlainFrameGLTest, RealModelsWithPlainLeavesBesideCsgEqualTheFullPipeline) {
    // OpenSCAD's examples whose root unions plain parts with CSG: columns
    // and a roof beside a cut ring, a module's parts beside its differences.
    for (const char* name : {"Old_example005", "Basics_CSG-modules", "Advanced_GEB"}) {
        const camera::Camera camera = setModel(name);
        for (int frame = 0; frame < 2; ++frame) {
            const render::Frame plain =
                expectPlainEqualsFull(camera, name, render::RenderSettings{}, true);
            EXPECT_GT(plain.stats.coveredPixels, std::size_t(160 * 120) / 20) << name;
        }
    }
}

TEST_F(PlainFrameGLTest, RealUnionModelsEqualTheFullPipeline) {
    // OpenSCAD's examples that are unions: cones crossing and sharing their
    // base plane, blocks standing on one another, a turned extrusion, each
    // from OpenSCAD's default view.
    for (const char* name : {"Old_example019", "Old_example022", "Old_example018", "Basics_rotate_extrude"}) {
        const camera::Camera camera = setModel(name);
        // The first frame with the tying leaves whole, the second with their triangles sorted out.
        for (int frame = 0; frame < 2; ++frame) {
            const render::Frame plain = expectPlainEqualsFull(camera, name);
            EXPECT_GT(plain.stats.coveredPixels, std::size_t(160 * 120) / 20) << name;
            EXPECT_GT(plain.stats.tiedLeaves, 0u) << name;
        }
    }
}

TEST_F(PlainFrameGLTest, LeavesApartNeedNoTiePass) {
    // A row of spheres and blocks, none touching: no pixel can tie, so the
    // plain frame is one pass over the leaves.
    scene::Tree tree;
    std::vector<int> parts;
    for (int i = 0; i < 6; ++i) {
        const double x = -2.5 + i;
        parts.push_back(tree.addLeaf(i % 2 ? sphereLeaf({x, 0, 0}, 0.4) : cubeLeaf({x - 0.3, -0.3, -0.3}, {x + 0.3, 0.3, 0.3})));
    }
    tree.root = tree.addNode(NodeKind::Union, parts);
    setScene(tree);
    const render::Frame plain = expectPlainEqualsFull(cameraAt({0.5, -3.0, 8.0}), "a row apart");
    EXPECT_EQ(plain.stats.tiedLeaves, 0u);
    EXPECT_EQ(plain.stats.operands, 6);
}

namespace {

// A union with a leaf repeated exactly (parts[3] repeats parts[1]), a
// translucent color() among the united leaves, a '#' leaf, and a '%'
// background leaf.
// With `translucent`, one leaf's colour is (AlphaPass.h); without,
// only the '%' and '#' leaves are drawn over the image (TranslucentPass.h).
scene::Tree modifiersScene(std::vector<int>& parts, bool translucent = true) {
    scene::Tree tree;
    scene::Leaf ball = sphereLeaf({0.4, 0, 0.2}, 0.9, 24);
    ball.color = glm::dvec4(0.9, 0.3, 0.2, 1.0);
    scene::Leaf glass = cubeLeaf({-1.8, -0.6, -0.6}, {-0.6, 0.6, 0.9});
    glass.color = glm::dvec4(0.2, 0.6, 0.9, translucent ? 0.5 : 1.0);
    scene::Leaf marked = cylinderLeaf({1.2, 0.8, -0.5}, 0.4, 1.6);
    marked.display = scene::Display::Highlight;
    parts = {tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 0.5})), tree.addLeaf(ball), tree.addLeaf(glass),
             tree.addLeaf(ball), tree.addLeaf(marked)};
    tree.root = tree.addNode(NodeKind::Union, parts);
    tree.background.push_back(tree.addLeaf(sphereLeaf({-0.5, 1.5, 0.5}, 0.5)));
    return tree;
}

}  // namespace

TEST_F(PlainFrameGLTest, IdenticalLeavesAndModifiersDrawAsThroughEveryPass) {
    // The repeated leaf is drawn once, named by the lower; the shaded
    // images agree too.
    std::vector<int> parts;
    setScene(modifiersScene(parts));
    for (camera::Projection projection : kProjections) {
        const render::Frame plain =
            expectPlainEqualsFull(cameraAt({2.0, -6.0, 5.0}, projection), "modifiers");
        EXPECT_EQ(plain.stats.operands, 4);  // the repeated ball is drawn once
        for (int leaf : plain.leaf) EXPECT_NE(leaf, parts[3]);
    }
}

TEST_F(PlainFrameGLTest, FramesThatNeedThePeelRunEveryPass) {
    // Not a union seen from outside, or a frame that asks for the layers:
    // the full pipeline.
    scene::Tree tree = randomUnion(5, 12);
    setScene(tree);
    camera::Camera inside = cameraAt({0.0, 0.0, 0.0});
    inside.center = {1.0, 0.0, 0.0};
    EXPECT_FALSE(renderer_->render(inside, {}).stats.plain);
    render::RenderSettings layers;
    layers.keepPeelLayers = true;
    EXPECT_FALSE(renderer_->render(cameraAt({0.0, -3.0, 8.0}), layers).stats.plain);
    render::RenderSettings forms;
    forms.keepBlockForms = true;
    EXPECT_FALSE(renderer_->render(cameraAt({0.0, -3.0, 8.0}), forms).stats.plain);

    scene::Tree cut;
    cut.root = cut.addNode(NodeKind::Difference, {cut.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1})),
                                                  cut.addLeaf(sphereLeaf({0, 0, 1}, 0.8))});
    setScene(cut);
    EXPECT_FALSE(renderer_->render(cameraAt({0.0, -3.0, 8.0}), {}).stats.plain);
}

TEST_F(PlainFrameGLTest, RenderIntoAHostGivesThePlainImage) {
    // A window's frames (renderInto) take the plain path too, writing only
    // what the image needs, and show what render() reads back, to the byte,
    // in every look; a renderer whose first frame is a window's, too. With
    // '%' and '#' leaves and no translucent colour, the window's frame keeps
    // no result images, and the leaves drawn over it read its own depth.
    std::vector<int> parts;
    for (const int kind : {0, 1, 2}) {
        renderer_ = std::make_unique<render::Renderer>();
        setScene(kind == 0 ? randomUnion(21, 16) : modifiersScene(parts, kind == 1));
        for (const bool outline : {true, false}) {
            for (const render::Lighting lighting : {render::Lighting::Strata, render::Lighting::OpenScad}) {
                for (camera::Projection projection : kProjections) {
                    render::RenderSettings look;
                    look.outline = outline;
                    look.lighting = lighting;
                    const camera::Camera camera = cameraAt({4.0, -6.0, 5.0}, projection);
                    const std::string what = std::string(kind == 1   ? "modifiers, "
                                                         : kind == 2 ? "'%' and '#' only, "
                                                                     : "") +
                                             std::string(render::lightingName(lighting)) +
                                             (outline ? ", outline" : "") + ", projection " +
                                             std::to_string(static_cast<int>(projection));
                    gpu::Texture color = gpu::Texture::create2D("host", GL_RGBA8, camera.width, camera.height);
                    gpu::Framebuffer host("host");
                    host.attachTexture(GL_COLOR_ATTACHMENT0, color);
                    host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
                    host.checkComplete();
                    const render::FrameStats stats = renderer_->renderInto(host.id(), 0, 0, camera, look);
                    EXPECT_TRUE(stats.plain) << what;
                    EXPECT_GT(stats.tiedLeaves, 0u) << what;
                    const render::Frame read = renderer_->render(camera, look);
                    ASSERT_TRUE(read.stats.plain) << what;
                    std::vector<std::uint8_t> pixels(read.rgba.size());
                    color.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(pixels)));
                    // GL's rows count from the bottom.
                    const std::size_t row = static_cast<std::size_t>(camera.width) * 4;
                    std::size_t differ = 0;
                    for (int y = 0; y < camera.height; ++y) {
                        for (std::size_t x = 0; x < row; ++x) {
                            differ += pixels[static_cast<std::size_t>(camera.height - 1 - y) * row + x] !=
                                      read.rgba[static_cast<std::size_t>(y) * row + x];
                        }
                    }
                    EXPECT_EQ(differ, 0u) << what;
                }
            }
        }
    }
}
