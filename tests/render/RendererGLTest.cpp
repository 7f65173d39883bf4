// The renderer against closed-form answers: depths at pixels whose ray is
// known exactly, computed here from the geometry, not from the renderer.
//
// Most scenes are seen from straight above (eye on +Z looking down), so the
// centre pixel of an odd-sized image looks down the Z axis. OpenSCAD spheres
// have flat polar caps (no pole vertex: ring 0 sits at polar angle
// 180°·0.5/rings), so that ray meets a sphere of radius r centred at height c
// exactly at z = c ± r·cos(90°/rings).
//
//        eye (0,0,10)
//          :
//          v   (the centre pixel's view ray)
//       ___:___   <- cap of a sphere: z = c + r cos(90°/rings)
//      /   :   \  .
//      \___:___/   <- bottom cap:     z = c - r cos(90°/rings)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "strata/model/Model.h"
#include "FrameCompare.h"
#include "SphereShells.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"
#include "strata/render/ColorScheme.h"
#include "strata/render/Renderer.h"

using namespace strata;
using scene::NodeKind;

namespace {

constexpr int kSize = 101;           // odd: the centre pixel's ray is the axis
constexpr int kCentre = kSize / 2;
constexpr double kEyeHeight = 10.0;
constexpr int kFn = 16;              // sphere $fn: 8 rings
constexpr int kRings = (kFn + 1) / 2;

// Height of a sphere's top (+1) or bottom (-1) cap.
double capHeight(double centreZ, double radius, int side) {
    return centreZ + side * radius * std::cos(std::numbers::pi / (2.0 * kRings));
}

scene::Leaf cubeLeaf(glm::dvec3 min, glm::dvec3 max) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{max - min, false};
    leaf.transform = glm::translate(glm::dmat4(1.0), min);
    return leaf;
}

scene::Leaf sphereLeaf(glm::dvec3 centre, double radius) {
    scene::Leaf leaf;
    scene::Sphere s;
    s.r = radius;
    s.fragments.fn = kFn;
    leaf.primitive = s;
    leaf.transform = glm::translate(glm::dmat4(1.0), centre);
    return leaf;
}

// The slab [-2, 2]^2 x [-1, 1] and `count` spheres of `radius`, seeded by
// `seed`, centred within `spread` of the axis in x and y and between
// `low` and `high` in z: the operands of a difference, slab first.
std::vector<int> slabAndSpheres(scene::Tree& tree, unsigned seed, int count, double spread, double low, double high,
                                double radius) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> across(-spread, spread), height(low, high);
    std::vector<int> operands{tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}))};
    for (int i = 0; i < count; ++i) {
        operands.push_back(tree.addLeaf(sphereLeaf({across(rng), across(rng), height(rng)}, radius)));
    }
    return operands;
}

// One polyhedron leaf made of several sphere shells: a non-convex operand.
// Adds a closed box, 2 * half wide and deep, z from -0.5 to 0.5, to `poly`
// as one more shell.
void appendBox(scene::Polyhedron& poly, double half) {
    const mesh::Mesh box = mesh::tessellate(scene::Cube{{2 * half, 2 * half, 1.0}, true});
    const int base = static_cast<int>(poly.points.size());
    for (const glm::dvec3& p : box.positions) poly.points.push_back(p);
    for (const auto& t : box.triangles) {  // OpenSCAD's order: clockwise seen from outside
        poly.faces.push_back({base + static_cast<int>(t[2]), base + static_cast<int>(t[1]),
                              base + static_cast<int>(t[0])});
    }
}

scene::Leaf shellsLeaf(const std::vector<glm::dvec3>& centres, double radius) {
    scene::Leaf leaf;
    leaf.primitive = test::sphereShells(centres, radius, kFn);
    return leaf;
}

camera::Camera topCamera(camera::Projection projection = camera::Projection::Perspective,
                         double eyeHeight = kEyeHeight) {
    camera::Camera camera;
    camera.eye = {0.0, 0.0, eyeHeight};
    camera.center = {0.0, 0.0, eyeHeight - 10.0};
    camera.projection = projection;
    camera.width = kSize;
    camera.height = kSize;
    return camera;
}

std::size_t at(const render::Frame& f, int i, int j) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(f.width) + static_cast<std::size_t>(i);
}

using test::pixelsDiffering;

// Writes the shaded image as a PPM when STRATA_TEST_IMAGES names a folder,
// to look at what the tests render.
void maybeSave(const render::Frame& f, const std::string& name) {
    const char* dir = std::getenv("STRATA_TEST_IMAGES");
    if (dir == nullptr) return;
    std::ofstream out(std::string(dir) + "/" + name + ".ppm", std::ios::binary);
    out << "P6\n" << f.width << ' ' << f.height << "\n255\n";
    for (std::size_t p = 0; p < f.rgba.size(); p += 4) out.write(reinterpret_cast<const char*>(&f.rgba[p]), 3);
}

class RendererGLTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        context_ = std::make_unique<gpu::Context>();
        renderer_ = std::make_unique<render::Renderer>();
    }
    static void TearDownTestSuite() {
        renderer_.reset();
        context_.reset();
    }

    render::Frame draw(const scene::Tree& tree, const camera::Camera& camera, render::RenderSettings settings = {}) {
        const model::Model model = model::buildModel(tree);
        renderer_->setScene(tree, model);
        render::Frame frame = renderer_->render(camera, settings);
        const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        maybeSave(frame, name + "_" + std::to_string(saved_++));
        return frame;
    }

    // Draws `tree` with leaf marks (where the driver has them) and with one
    // mark for all: every AOV and the image must be the same to the bit.
    // Returns the one-mark frame.
    render::Frame expectMarksChangeNothing(const scene::Tree& tree, const camera::Camera& camera) {
        const render::Frame marked = draw(tree, camera);
        render::RenderSettings oneMark;
        oneMark.leafMarks = false;
        render::Frame plain = renderer_->render(camera, oneMark);
        EXPECT_EQ(pixelsDiffering(marked, plain), 0u);
        EXPECT_EQ(marked.rgba, plain.rgba);
        return plain;
    }

    // Centre pixel: depth, leaf, normal.
    static void expectCentre(const render::Frame& f, double depth, int leaf, glm::vec3 normal) {
        const std::size_t c = at(f, kCentre, kCentre);
        EXPECT_NEAR(f.depth[c], depth, 1e-5 * depth);
        EXPECT_EQ(f.leaf[c], leaf);
        EXPECT_NEAR(f.normal[c].x, normal.x, 1e-5);
        EXPECT_NEAR(f.normal[c].y, normal.y, 1e-5);
        EXPECT_NEAR(f.normal[c].z, normal.z, 1e-5);
    }

    static std::unique_ptr<gpu::Context> context_;
    static std::unique_ptr<render::Renderer> renderer_;
    int saved_ = 0;
};

std::unique_ptr<gpu::Context> RendererGLTest::context_;
std::unique_ptr<render::Renderer> RendererGLTest::renderer_;

const camera::Projection kProjections[] = {camera::Projection::Perspective, camera::Projection::Orthographic};

// The paper's cube-and-sphere pair: cube [-1,1]^3, sphere r=1 on its top face.
scene::Tree paperPair(NodeKind op) {
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}));
    const int sphere = tree.addLeaf(sphereLeaf({0, 0, 1}, 1.0));
    tree.root = tree.addNode(NodeKind::Union, {tree.addNode(op, {cube, sphere})});
    return tree;
}

}  // namespace

TEST_F(RendererGLTest, CubeMinusSphereShowsTheCavityFloor) {
    for (camera::Projection p : kProjections) {
        const render::Frame f = draw(paperPair(NodeKind::Difference), topCamera(p));
        // The ray passes the removed top face and meets the sphere's bottom cap
        // from inside the cube: the sphere's face, flipped to point up.
        expectCentre(f, kEyeHeight - capHeight(1.0, 1.0, -1), 1, {0, 0, 1});
        // Pixel (73, 27) looks at (0.91, 0.91, 1) (orthographic) or (0.82,
        // 0.82, 1) (perspective): on the cube's top face, outside the cut
        // (the sphere's section at z = 1 has radius r sin(78.75°) < 0.99).
        // The top face is a plane of view depth 9.
        const std::size_t k = at(f, 73, 27);
        EXPECT_EQ(f.leaf[k], 0);
        EXPECT_NEAR(f.depth[k], 9.0, 1e-5);
        EXPECT_NEAR(f.normal[k].z, 1.0f, 1e-6);
    }
}

TEST_F(RendererGLTest, ThePapersThreeOperationsInBothProjections) {
    for (camera::Projection p : kProjections) {
        // Union: the sphere's top cap stands highest.
        expectCentre(draw(paperPair(NodeKind::Union), topCamera(p)), kEyeHeight - capHeight(1.0, 1.0, +1), 1,
                     {0, 0, 1});
        // Intersection: inside the sphere the cube's top face at z = 1.
        expectCentre(draw(paperPair(NodeKind::Intersection), topCamera(p)), kEyeHeight - 1.0, 0, {0, 0, 1});
        // Difference: the cavity floor, the sphere's face flipped.
        expectCentre(draw(paperPair(NodeKind::Difference), topCamera(p)), kEyeHeight - capHeight(1.0, 1.0, -1), 1,
                     {0, 0, 1});
    }
}

TEST_F(RendererGLTest, IntersectionOfSpheresIsTheLens) {
    scene::Tree tree;
    const int a = tree.addLeaf(sphereLeaf({0, 0, 0.5}, 1.0));
    const int b = tree.addLeaf(sphereLeaf({0, 0, -0.5}, 1.0));
    tree.root = tree.addNode(NodeKind::Intersection, {a, b});
    for (camera::Projection p : kProjections) {
        // The lens's top is the lower sphere's top cap.
        expectCentre(draw(tree, topCamera(p)), kEyeHeight - capHeight(-0.5, 1.0, +1), 1, {0, 0, 1});
    }
}

TEST_F(RendererGLTest, OrthographicCubeCoversExactlyItsPixels) {
    // Drawn plainly (a union seen from outside: PlainPass.h) and peeled.
    scene::Tree tree;
    tree.root = tree.addNode(NodeKind::Union, {tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}))});
    for (const bool plain : {true, false}) {
        render::RenderSettings settings;
        settings.plainUnions = plain;
        const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic), settings);
        EXPECT_EQ(f.stats.plain, plain);
        // The contract's orthographic ray of pixel (i, j) starts at x*h*a, y*h:
        // it hits the top face (depth 9, normal +Z) iff both are inside [-1, 1].
        const double h = 10.0 * std::tan(22.5 / 2.0 * std::numbers::pi / 180.0);
        std::size_t expected = 0;
        for (int j = 0; j < kSize; ++j) {
            for (int i = 0; i < kSize; ++i) {
                const double x = (2.0 * (i + 0.5) / kSize - 1.0) * h;
                const double y = (1.0 - 2.0 * (j + 0.5) / kSize) * h;
                const bool hit = std::abs(x) < 1.0 && std::abs(y) < 1.0;
                expected += hit ? 1 : 0;
                const std::size_t k = at(f, i, j);
                ASSERT_EQ(f.leaf[k], hit ? 0 : -1) << i << "," << j;
                if (hit) {
                    EXPECT_NEAR(f.depth[k], 9.0, 1e-5);
                    EXPECT_NEAR(f.normal[k].z, 1.0f, 1e-6);
                } else {
                    EXPECT_TRUE(std::isinf(f.depth[k]) && f.depth[k] > 0);
                    EXPECT_EQ(f.normal[k], glm::vec3(0.0f));
                }
            }
        }
        EXPECT_EQ(f.stats.coveredPixels, expected);
        EXPECT_EQ(f.stats.layersPerLeaf, std::vector<int>{plain ? 0 : 1});
    }
}

TEST_F(RendererGLTest, ASmallerModelAfterALargeOneLeavesNoTrace) {
    // The G-buffer is cleared only where the last frame wrote: a big cube
    // filling the frame, then a small one in a corner, must give exactly the
    // small cube's pixels, the shaded image included.
    scene::Tree big;
    big.root = big.addNode(NodeKind::Union, {big.addLeaf(cubeLeaf({-3, -3, -1}, {3, 3, 1}))});
    scene::Tree small;
    small.root = small.addNode(NodeKind::Union, {small.addLeaf(cubeLeaf({1.0, 1.0, -1}, {1.6, 1.6, 1}))});
    const camera::Camera camera = topCamera(camera::Projection::Orthographic);
    const render::Frame first = draw(big, camera);
    ASSERT_EQ(first.stats.coveredPixels, static_cast<std::size_t>(kSize) * kSize);
    const render::Frame f = draw(small, camera);
    // A fresh renderer, whose images were never written, for comparison.
    render::Renderer fresh;
    fresh.setScene(small, model::buildModel(small));
    const render::Frame want = fresh.render(camera, {});
    ASSERT_GT(want.stats.coveredPixels, 0u);
    ASSERT_LT(want.stats.coveredPixels, static_cast<std::size_t>(kSize) * kSize / 10);
    EXPECT_EQ(f.stats.coveredPixels, want.stats.coveredPixels);
    EXPECT_EQ(f.leaf, want.leaf);
    EXPECT_EQ(f.rgba, want.rgba);
    for (std::size_t k = 0; k < f.leaf.size(); ++k) {
        if (f.leaf[k] >= 0) continue;
        ASSERT_TRUE(std::isinf(f.depth[k])) << k;
        ASSERT_EQ(f.normal[k], glm::vec3(0.0f)) << k;
    }
}

TEST_F(RendererGLTest, PerspectiveCubeSideFaceDepthIsItsPlane) {
    // Seen from the side (eye on -Y), the face y = -1 is a plane of constant
    // view depth: every pixel on it reads |eye.y| - 1, with normal -Y.
    scene::Tree tree;
    tree.root = tree.addNode(NodeKind::Union, {tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}))});
    camera::Camera camera;
    camera.eye = {0.0, -8.0, 0.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.width = 64;
    camera.height = 48;
    const render::Frame f = draw(tree, camera);
    int onFace = 0;
    for (std::size_t k = 0; k < f.leaf.size(); ++k) {
        if (f.leaf[k] < 0) continue;
        ++onFace;
        EXPECT_NEAR(f.depth[k], 7.0, 1e-5);
        EXPECT_NEAR(f.normal[k].y, -1.0f, 1e-6);
    }
    EXPECT_GT(onFace, 100);
}

TEST_F(RendererGLTest, UnionOfSpheresAndCubeTakesTheHighest) {
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}));
    const int low = tree.addLeaf(sphereLeaf({0, 0, 0.5}, 0.9));
    const int high = tree.addLeaf(sphereLeaf({0, 0, 1.2}, 0.5));
    tree.root = tree.addNode(NodeKind::Union, {cube, low, high});
    for (camera::Projection p : kProjections) {
        expectCentre(draw(tree, topCamera(p)), kEyeHeight - capHeight(1.2, 0.5, +1), 2, {0, 0, 1});
    }
}

// The original paper's failure case: a slab minus three spheres on the view
// ray, the spheres being ONE non-convex operand. One dual-peel layer sees
// only that operand's first entry and last exit, so it believes the ray stays
// inside the subtrahend all through the slab: the centre pixel shows nothing.
//
//      z= 1.39  ( o )   sphere 1 pokes out of the slab's top
//      z= 1   ==|===|==  slab top (cut away)
//      z= 0.61  (_o_)   <- the true visible surface: sphere 1's bottom
//      z= 0     ( o )   sphere 2, inside the slab
//      z=-1   ==(=o=)==  slab bottom, sphere 3 pokes out below
TEST_F(RendererGLTest, StackedSubtractionNeedsAllLayersOfANonConvexOperand) {
    scene::Tree tree;
    const int slab = tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}));
    const int spheres = tree.addLeaf(shellsLeaf({{0, 0, 1}, {0, 0, 0}, {0, 0, -1}}, 0.4));
    tree.root = tree.addNode(NodeKind::Difference, {slab, spheres});
    const double truth = kEyeHeight - capHeight(1.0, 0.4, -1);
    for (camera::Projection p : kProjections) {
        render::RenderSettings one;
        one.layers = 1;
        const render::Frame wrong = draw(tree, topCamera(p), one);
        const std::size_t c = at(wrong, kCentre, kCentre);
        EXPECT_TRUE(std::isinf(wrong.depth[c])) << "one layer should miss the cavity floor, got " << wrong.depth[c];
        EXPECT_EQ(wrong.leaf[c], -1);

        render::RenderSettings lists;  // however few triangles the shells have
        lists.fragmentListTriangles = 0;
        const render::Frame right = draw(tree, topCamera(p), lists);  // auto
        expectCentre(right, truth, 1, {0, 0, 1});
        EXPECT_EQ(right.stats.layersPerLeaf[1], 3);  // 6 surfaces, 2 per layer
        EXPECT_EQ(right.stats.layersPerLeaf[0], 1);  // the slab is convex
        // One pass each: the shells' 6 surfaces fit a fragment list.
        EXPECT_EQ(right.stats.peelPasses, 1 + 1);
        EXPECT_EQ(right.stats.listPeeledOperands, 1);

        render::RenderSettings passes;
        passes.fragmentListTriangles = -1;
        const render::Frame peeled = draw(tree, topCamera(p), passes);
        expectCentre(peeled, truth, 1, {0, 0, 1});
        EXPECT_EQ(peeled.stats.layersPerLeaf[1], 3);
        // The first pass counted 6 surfaces: no fourth pass to find nothing.
        EXPECT_EQ(peeled.stats.peelPasses, 1 + 3);
        EXPECT_EQ(peeled.stats.listPeeledOperands, 0);

        render::RenderSettings three;
        three.layers = 3;
        expectCentre(draw(tree, topCamera(p), three), truth, 1, {0, 0, 1});
    }
}

TEST_F(RendererGLTest, AutoPeelingStopsWhereCountedSurfacesCoincide) {
    // One polyhedron of two boxes, the narrow one inside the wide one with
    // its top and bottom in the wide one's planes. Over the narrow box the
    // first pass counts four surfaces at two depths; the first layer peels
    // both pairs at once. The second pass is drawn (the counts promise more),
    // finds nothing and is not kept. Orthographic, so that both boxes' tops
    // interpolate to the very same depth (in perspective the two triangles
    // may differ by an ulp, and the second layer is real).
    scene::Polyhedron poly;
    for (const double half : {1.5, 0.5}) appendBox(poly, half);
    // Intersected with a larger cube, so that its inner surfaces could matter
    // and all of them are peeled.
    scene::Tree tree;
    scene::Leaf boxes;
    boxes.primitive = poly;
    tree.root = tree.addNode(NodeKind::Intersection, {tree.addLeaf(boxes), tree.addLeaf(cubeLeaf({-2, -2, -2}, {2, 2, 2}))});
    render::RenderSettings passes;
    passes.fragmentListTriangles = -1;
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic), passes);
    expectCentre(f, kEyeHeight - 0.5, 0, {0, 0, 1});
    EXPECT_EQ(f.stats.layersPerLeaf[0], 1);
    EXPECT_EQ(f.stats.peelPasses, 1 + 2);  // the cube, then the boxes' two
    // A fragment list holds all four; they make one layer all the same.
    render::RenderSettings lists;
    lists.fragmentListTriangles = 0;
    const render::Frame listed = draw(tree, topCamera(camera::Projection::Orthographic), lists);
    expectCentre(listed, kEyeHeight - 0.5, 0, {0, 0, 1});
    EXPECT_EQ(listed.stats.layersPerLeaf[0], 1);
    EXPECT_EQ(listed.stats.peelPasses, 1 + 1);
    EXPECT_EQ(listed.stats.listPeeledOperands, 1);
}

// Without a wait after each pass (RenderSettings::passTimes false) the
// frame is the same to the bit, in one tile and in several.
TEST_F(RendererGLTest, AFrameWithoutWaitsBetweenPassesIsTheSame) {
    scene::Tree tree;
    tree.root = tree.addNode(NodeKind::Difference, slabAndSpheres(tree, 3, 12, 1.5, -1.2, 1.2, 0.3));
    for (const std::size_t budget : {std::size_t(0), std::size_t(30 * 30 * 8 * 3)}) {
        render::RenderSettings timed;
        if (budget > 0) timed.memoryBudget = budget;
        render::RenderSettings untimed = timed;
        untimed.passTimes = false;
        const render::Frame a = draw(tree, topCamera(), timed);
        const render::Frame b = draw(tree, topCamera(), untimed);
        EXPECT_EQ(a.stats.tiles, b.stats.tiles);
        if (budget > 0) EXPECT_GT(a.stats.tiles, 1);
        EXPECT_EQ(pixelsDiffering(a, b), 0u);
        EXPECT_EQ(a.rgba, b.rgba);
    }
}

// What a frame leaves unset, the device fills in: on llvmpipe the budget
// and llvmpipe's coverage tiles; on a GPU no coverage tiles. What the
// caller sets stays.
TEST_F(RendererGLTest, TheDeviceFillsInTheBudgetAndTheTiles) {
    const render::RenderSettings filled = renderer_->deviceSettings({});
    ASSERT_TRUE(filled.memoryBudget.has_value());
    ASSERT_TRUE(filled.coverageTilingFrom.has_value());
    const std::string name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (name.find("llvmpipe") != std::string::npos) {
        EXPECT_EQ(*filled.memoryBudget, render::RenderSettings::kMemoryBudget);
        EXPECT_EQ(*filled.coverageTilingFrom, render::RenderSettings::kSoftwareCoverageTilingFrom);
    } else {
        EXPECT_GE(*filled.memoryBudget, render::RenderSettings::kMemoryBudget);
        EXPECT_LE(*filled.memoryBudget, std::size_t(4) << 30);
        EXPECT_EQ(*filled.coverageTilingFrom, *filled.memoryBudget);
    }
    render::RenderSettings own;
    own.memoryBudget = 12345;
    own.coverageTilingFrom = 678;
    const render::RenderSettings kept = renderer_->deviceSettings(own);
    EXPECT_EQ(kept.memoryBudget, own.memoryBudget);
    EXPECT_EQ(kept.coverageTilingFrom, own.coverageTilingFrom);
}

TEST_F(RendererGLTest, OperandsOnlyUnionsLeadToArePeeledOnce) {
    // A union of the three shells (six surfaces on the axis) and a cube
    // beside them. Seen from outside, the union's first surface on any ray is
    // the first surface of one of its operands, so one layer of the shells is
    // all it can show: the frame must equal the one that peels all three
    // (the debug views' setting, which peels every layer).
    scene::Tree tree;
    const int shells = tree.addLeaf(shellsLeaf({{0, 0, 1}, {0, 0, 0}, {0, 0, -1}}, 0.4));
    const int cube = tree.addLeaf(cubeLeaf({1, 1, -1}, {1.8, 1.8, 0.5}));
    tree.root = tree.addNode(NodeKind::Union, {tree.addNode(NodeKind::Union, {shells}), cube});
    // Both as operands of their own and as one union group (ConvexGroups.h).
    render::RenderSettings everyLayer, apart;
    everyLayer.keepPeelLayers = true;
    apart.groupOperands = false;
    apart.plainUnions = false;  // the peel of such a union is what is tested
    for (camera::Projection p : kProjections) {
        const render::Frame once = draw(tree, topCamera(p), apart);
        EXPECT_EQ(once.stats.layersPerLeaf[0], 1);
        EXPECT_EQ(once.stats.peelPasses, 2);  // one batch draw each
        expectCentre(once, kEyeHeight - capHeight(1.0, 0.4, +1), 0, {0, 0, 1});
        const render::Frame all = renderer_->render(topCamera(p), everyLayer);
        EXPECT_EQ(all.stats.layersPerLeaf[0], 3);
        EXPECT_EQ(pixelsDiffering(once, all), 0u);
        EXPECT_EQ(once.rgba, all.rgba);
        render::RenderSettings unite;
        unite.unionGroupFrom = 2;
        unite.plainUnions = false;
        const render::Frame united = renderer_->render(topCamera(p), unite);
        EXPECT_EQ(united.stats.operands, 1);
        EXPECT_EQ(united.stats.layersPerLeaf[0], 1);
        EXPECT_EQ(pixelsDiffering(united, all), 0u);
        EXPECT_EQ(united.rgba, all.rgba);
    }
    // From inside the model's box the near plane may cut operands, and the
    // union can start inside one: then every layer counts again. Here, just
    // outside the middle shell and looking down, the rays meet the middle and
    // the lower shells: four surfaces, two layers.
    camera::Camera inside = topCamera();
    inside.eye = {0.3, 0.3, 0.2};
    inside.center = {0.3, 0.3, -5.0};
    EXPECT_EQ(draw(tree, inside).stats.layersPerLeaf[0], 2);
}

TEST_F(RendererGLTest, AFlatShellKeepsEveryLayerOfItsOperand) {
    // One polyhedron: a box, and above it a flat sheet (two faces at one
    // depth, a shell of no volume). A ray enters and leaves the sheet at one
    // depth, so the sheet shows nowhere and the box's top does. Only a union
    // leads to the leaf, but its first layer alone would keep the sheet's
    // entry and lose its exit: the leaf must be peeled in full.
    scene::Polyhedron poly;
    appendBox(poly, 1.0);
    const int base = static_cast<int>(poly.points.size());
    for (const glm::dvec3& p : {glm::dvec3{-2, -2, 1.5}, {2, -2, 1.5}, {2, 2, 1.5}, {-2, 2, 1.5}}) poly.points.push_back(p);
    for (const std::vector<int>& face : {std::vector<int>{0, 3, 2}, {0, 2, 1}, {1, 2, 3}, {1, 3, 0}}) {
        poly.faces.push_back({base + face[0], base + face[1], base + face[2]});
    }
    scene::Tree tree;
    scene::Leaf both;
    both.primitive = poly;
    tree.root = tree.addNode(NodeKind::Union, {tree.addLeaf(both)});
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));  // both faces at one depth
    expectCentre(f, kEyeHeight - 0.5, 0, {0, 0, 1});
    EXPECT_EQ(f.stats.layersPerLeaf[0], 2);
}

TEST_F(RendererGLTest, PeeledLayersHoldTheSurfacesInOrder) {
    // The three shells on the view axis: six surfaces, peeled in pairs from
    // the outside in (Bavoil & Myers): layer 0 = (top of shell 1, bottom of
    // shell 3), layer 1 = (bottom of shell 1, top of shell 3), layer 2 =
    // (top of shell 2, bottom of shell 2).
    scene::Tree tree;
    const int slab = tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}));
    const int spheres = tree.addLeaf(shellsLeaf({{0, 0, 1}, {0, 0, 0}, {0, 0, -1}}, 0.4));
    tree.root = tree.addNode(NodeKind::Difference, {slab, spheres});
    render::RenderSettings settings;
    settings.keepPeelLayers = true;
    const render::Frame f = draw(tree, topCamera(), settings);
    const double expected[3][2] = {{capHeight(1.0, 0.4, +1), capHeight(-1.0, 0.4, -1)},
                                   {capHeight(1.0, 0.4, -1), capHeight(-1.0, 0.4, +1)},
                                   {capHeight(0.0, 0.4, +1), capHeight(0.0, 0.4, -1)}};
    int found = 0;
    const std::size_t c = at(f, kCentre, kCentre);
    for (const render::PeelLayerImage& layer : f.peelLayers) {
        ASSERT_EQ(layer.nearDepth.size(), f.depth.size());
        if (layer.leaf == 0) {  // the slab: one layer, its top and bottom faces
            EXPECT_EQ(layer.layer, 0);
            EXPECT_NEAR(layer.nearDepth[c], kEyeHeight - 1.0, 1e-5);
            EXPECT_NEAR(layer.farDepth[c], kEyeHeight + 1.0, 1e-5);
            continue;
        }
        ASSERT_EQ(layer.leaf, 1);
        ASSERT_LT(layer.layer, 3);
        ++found;
        EXPECT_NEAR(layer.nearDepth[c], kEyeHeight - expected[layer.layer][0], 1e-5) << layer.layer;
        EXPECT_NEAR(layer.farDepth[c], kEyeHeight - expected[layer.layer][1], 1e-5) << layer.layer;
        // Off the shells' outline the operand has nothing on any layer.
        EXPECT_TRUE(std::isinf(layer.nearDepth[at(f, 5, 5)]));
    }
    EXPECT_EQ(found, 3);
}

TEST_F(RendererGLTest, RenderIntoAHostFramebuffer) {
    const scene::Tree tree = paperPair(NodeKind::Difference);
    const render::Frame frame = draw(tree, topCamera());
    gpu::Texture target = gpu::Texture::create2D("host", GL_RGBA8, kSize + 20, kSize + 20);
    gpu::Framebuffer host("host");
    host.attachTexture(GL_COLOR_ATTACHMENT0, target);
    host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    host.checkComplete();
    const float clear[4] = {0, 0, 0, 0};
    host.clearColor(0, clear);
    const render::FrameStats stats = renderer_->renderInto(host.id(), 5, 7, topCamera(), {});
    EXPECT_EQ(stats.tiles, 1);
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>((kSize + 20) * (kSize + 20) * 4));
    target.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(pixels)));
    // Host pixel (5 + i, 7 + row-from-bottom) holds image pixel (i, kSize-1-row).
    std::size_t differ = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int i = 0; i < kSize; ++i) {
            const std::size_t h = (static_cast<std::size_t>(7 + row) * (kSize + 20) + 5 + i) * 4;
            const std::size_t m = at(frame, i, kSize - 1 - row) * 4;
            for (int ch = 0; ch < 4; ++ch) differ += pixels[h + ch] != frame.rgba[m + ch] ? 1 : 0;
        }
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(pixels[0], 0);  // outside the copied rectangle: untouched
}

TEST_F(RendererGLTest, RenderIntoLeavesNoTraceOfTheFrameBefore) {
    // renderInto() clears neither the depth nor the leaf image (nothing
    // reads them back, and the passes read them only where the evaluator
    // wrote this frame), and the normals only around the operands. A frame drawn after another scene and view, with
    // and without leaf marks, must still equal render()'s image of it.
    // The frame before: a plate just under the eye, nearer than anything
    // of the scene, on every pixel.
    scene::Tree plate;
    plate.root = plate.addLeaf(cubeLeaf({-50, -50, kEyeHeight - 1.5}, {50, 50, kEyeHeight - 1.0}));
    gpu::Texture target = gpu::Texture::create2D("host", GL_RGBA8, kSize, kSize);
    gpu::Framebuffer host("host");
    host.attachTexture(GL_COLOR_ATTACHMENT0, target);
    host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    host.checkComplete();
    // The third case adds a '%' cube beside the result: the translucent
    // pass reads the depth image at every pixel it covers, most of them
    // pixels the result misses.
    scene::Tree highlighted = paperPair(NodeKind::Difference);
    scene::Leaf ghost = cubeLeaf({1.5, 1.5, -1}, {2.5, 2.5, 0});
    ghost.display = scene::Display::Background;
    highlighted.background = {highlighted.addLeaf(ghost)};
    // The fourth: two cubes in opposite corners, each with its own screen
    // rectangle, around both of which the normals must be cleared.
    scene::Tree corners;
    corners.root = corners.addNode(NodeKind::Union, {corners.addLeaf(cubeLeaf({-2.5, -2.5, -1}, {-0.5, -0.5, 0})),
                                                     corners.addLeaf(cubeLeaf({0.5, 0.5, -1}, {2.5, 2.5, 0}))});
    for (int c = 0; c < 4; ++c) {
        const bool marks = c != 1;
        const scene::Tree tree = c == 2 ? highlighted : c == 3 ? corners : paperPair(NodeKind::Difference);
        render::RenderSettings settings;
        settings.leafMarks = marks;
        const render::Frame expected = draw(tree, topCamera(), settings);
        const render::Frame before = draw(plate, topCamera(), settings);
        ASSERT_EQ(before.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize));
        renderer_->setScene(tree, model::buildModel(tree));
        renderer_->renderInto(host.id(), 0, 0, topCamera(), settings);
        std::vector<std::uint8_t> pixels(static_cast<std::size_t>(kSize * kSize * 4));
        target.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(pixels)));
        std::size_t differ = 0;
        for (int row = 0; row < kSize; ++row) {
            for (int i = 0; i < kSize; ++i) {
                const std::size_t h = (static_cast<std::size_t>(row) * kSize + static_cast<std::size_t>(i)) * 4;
                const std::size_t m = at(expected, i, kSize - 1 - row) * 4;
                for (int ch = 0; ch < 4; ++ch) differ += pixels[h + ch] != expected.rgba[m + ch] ? 1 : 0;
            }
        }
        EXPECT_EQ(differ, 0u) << "case " << c;
        EXPECT_GT(expected.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 10);
    }
}

TEST_F(RendererGLTest, IdenticalLeavesShareOneOperandAndChangeNoSurface) {
    // A chain in the manner of strata-bench's deep scene: the slab and seeded
    // spheres joined by unions and differences, and every third step an
    // intersection with one big sphere, each time a leaf of its own.
    scene::Tree tree;
    const std::vector<int> leaves = slabAndSpheres(tree, 7, 18, 1.8, -1.2, 1.2, 0.5);
    std::vector<int> copies;  // leaf indices
    int node = leaves[0];
    for (std::size_t i = 1; i < leaves.size(); ++i) {
        node = tree.addNode(i % 2 == 1 ? NodeKind::Union : NodeKind::Difference, {node, leaves[i]});
        if (i % 3 == 0) {
            const int big = tree.addLeaf(sphereLeaf({0, 0, 0}, 2.4));
            copies.push_back(tree.nodes[static_cast<std::size_t>(big)].leaf);
            node = tree.addNode(NodeKind::Intersection, {node, big});
        }
    }
    tree.root = node;
    const model::Model model = model::buildModel(tree);
    // The same solids, but each copy's triangles in an order of its own, so
    // that no two leaves are identical bit for bit: the path without sharing.
    model::Model apart = model;
    for (int c : copies) {
        auto& triangles = apart.leafMeshes[static_cast<std::size_t>(c)].triangles;
        std::rotate(triangles.begin(), triangles.begin() + 1 + c, triangles.end());
    }
    for (camera::Projection projection : kProjections) {
        renderer_->setScene(tree, apart);
        const render::Frame separate = renderer_->render(topCamera(projection), {});
        renderer_->setScene(tree, model);
        const render::Frame shared = renderer_->render(topCamera(projection), {});
        EXPECT_EQ(separate.stats.operands, static_cast<int>(leaves.size() + copies.size()));
        EXPECT_EQ(shared.stats.operands, static_cast<int>(leaves.size() + 1));
        EXPECT_EQ(shared.stats.layersPerLeaf[static_cast<std::size_t>(copies[0])], 1);
        const auto saysRepeat = [](const render::Frame& f) {
            return std::any_of(f.stats.notes.begin(), f.stats.notes.end(),
                               [](const std::string& n) { return n.find("repeat") != std::string::npos; });
        };
        EXPECT_TRUE(saysRepeat(shared));
        EXPECT_FALSE(saysRepeat(separate));
        for (std::size_t i = 1; i < copies.size(); ++i) {
            EXPECT_EQ(shared.stats.layersPerLeaf[static_cast<std::size_t>(copies[i])], 0);
        }
        ASSERT_GT(shared.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 4);
        EXPECT_EQ(shared.stats.coveredPixels, separate.stats.coveredPixels);
        // Same surfaces and image; the leaf image names the first copy for every copy.
        std::size_t differ = 0, copiesShown = 0;
        for (std::size_t k = 0; k < shared.leaf.size(); ++k) {
            int leaf = separate.leaf[k] >= 0 ? separate.leaf[k] : -1;
            if (std::find(copies.begin(), copies.end(), leaf) != copies.end()) {
                leaf = copies[0];
                ++copiesShown;
            }
            differ += shared.leaf[k] != leaf || std::memcmp(&shared.depth[k], &separate.depth[k], sizeof(float)) != 0 ||
                      std::memcmp(&shared.normal[k], &separate.normal[k], sizeof(glm::vec3)) != 0;
        }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(copiesShown, 100u) << "the big sphere must show";
        EXPECT_EQ(shared.rgba, separate.rgba);
        // The array form alone, where one slot carries the copies' literals.
        render::RenderSettings general;
        general.generalEvaluator = true;
        const render::Frame sharedGeneral = renderer_->render(topCamera(projection), general);
        EXPECT_EQ(sharedGeneral.stats.arrayBlocks, shared.stats.arrayBlocks + shared.stats.registerBlocks +
                                                        shared.stats.productBlocks + shared.stats.firstSurfaceBlocks);
        EXPECT_EQ(pixelsDiffering(sharedGeneral, shared), 0u);
        EXPECT_EQ(sharedGeneral.rgba, shared.rgba);
    }
}

TEST_F(RendererGLTest, ConvexSubtrahendsNeedOneLayerEach) {
    // The same stack as three separate (convex) leaves: one layer suffices.
    scene::Tree tree;
    const int slab = tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}));
    std::vector<int> parts;
    for (double z : {1.0, 0.0, -1.0}) parts.push_back(tree.addLeaf(sphereLeaf({0, 0, z}, 0.4)));
    const int stack = tree.addNode(NodeKind::Union, parts);
    tree.root = tree.addNode(NodeKind::Difference, {slab, stack});
    render::RenderSettings one;
    one.layers = 1;
    expectCentre(draw(tree, topCamera(), one), kEyeHeight - capHeight(1.0, 0.4, -1), 1, {0, 0, 1});
}

TEST_F(RendererGLTest, EyeInsideASubtractedOperand) {
    // The eye at z = 3 sits inside the subtracted sphere (centre z = 2, r = 1.6),
    // which also swallows the cube's top face: the first surface is the
    // sphere's bottom cap, where the ray leaves the subtrahend inside the cube.
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}));
    const int sphere = tree.addLeaf(sphereLeaf({0, 0, 2}, 1.6));
    tree.root = tree.addNode(NodeKind::Difference, {cube, sphere});
    for (camera::Projection p : kProjections) {
        const render::Frame f = draw(tree, topCamera(p, 3.0));
        expectCentre(f, 3.0 - capHeight(2.0, 1.6, -1), 1, {0, 0, 1});
    }
}

TEST_F(RendererGLTest, NearPlaneThroughTheModel) {
    // The eye at the origin, inside the cube [-2,2]^3 minus a sphere below it:
    // the ray starts inside the result and leaves it where it enters the
    // sphere's top cap; the result's outward normal there points down (-Z),
    // into the cavity: the sphere's face, flipped.
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-2, -2, -2}, {2, 2, 2}));
    const int sphere = tree.addLeaf(sphereLeaf({0, 0, -1}, 0.5));
    tree.root = tree.addNode(NodeKind::Difference, {cube, sphere});
    for (camera::Projection p : kProjections) {
        camera::Camera camera = topCamera(p, 0.0);
        // A side pixel whose ray passes the sphere (r = 0.5 at depth 1) and
        // leaves the cube through its bottom (depth 2):
        //   perspective, fov 90°: slope 0.79 at column 10, passing the
        //     sphere's centre at 1 * sin(atan 0.79) = 0.62 > 0.5, meeting the
        //     bottom at |x| = 1.58 < 2;
        //   orthographic, fov 22.5°: column 20 starts at x = -1.18.
        camera.fovDegrees = p == camera::Projection::Perspective ? 90.0 : 22.5;
        const int column = p == camera::Projection::Perspective ? 10 : 20;
        const render::Frame f = draw(tree, camera);
        expectCentre(f, 0.0 - capHeight(-1.0, 0.5, +1), 1, {0, 0, -1});
        // The side ray leaves through the cube's bottom face (its own face, not
        // flipped): depth 2, normal -Z.
        const std::size_t k = at(f, column, kCentre);
        EXPECT_EQ(f.leaf[k], 0);
        EXPECT_NEAR(f.depth[k], 2.0, 1e-5);
        EXPECT_NEAR(f.normal[k].z, -1.0f, 1e-6);
    }
}

// A tiled frame against the same view in one tile. A tile's viewport is
// shifted, so interpolated depths may differ in the last bits.
void expectSameAsUntiled(const render::Frame& tiled, const render::Frame& whole) {
    ASSERT_EQ(tiled.leaf.size(), whole.leaf.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < whole.leaf.size(); ++k) {
        const bool same = tiled.leaf[k] == whole.leaf[k] &&
                          (std::isinf(whole.depth[k]) ? tiled.depth[k] == whole.depth[k]
                                                      : std::abs(tiled.depth[k] - whole.depth[k]) <= 1e-6 * whole.depth[k]) &&
                          glm::length(tiled.normal[k] - whole.normal[k]) < 1e-6f;
        if (!same && differ++ < 5) {
            ADD_FAILURE() << "pixel " << k % kSize << "," << k / kSize << ": tiled leaf " << tiled.leaf[k] << " depth "
                          << tiled.depth[k] << ", whole leaf " << whole.leaf[k] << " depth " << whole.depth[k];
        }
    }
    EXPECT_EQ(differ, 0u);
}

// A group's scratch images are textures of their own: the layer texture
// holds the layers alone (one a group, one scratch), not room for them too.
TEST_F(RendererGLTest, AGroupsScratchImagesTakeNoLayers) {
    scene::Tree tree;
    std::vector<int> lens{tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}))};
    for (int i = 0; i < 3; ++i) lens.push_back(tree.addLeaf(sphereLeaf({0.2 * i, 0.1, 0.0}, 2.2)));
    tree.root = tree.addNode(NodeKind::Intersection, lens);
    render::Renderer fresh;  // the shared renderer keeps the largest layer texture of the tests before
    fresh.setScene(tree, model::buildModel(tree));
    render::RenderSettings grouped;
    grouped.convexGroupFrom = 2;  // a group of four
    const render::Frame f = fresh.render(topCamera(), grouped);
    ASSERT_EQ(f.stats.operands, 1);
    // Two RG32F layers; the group's images are two RGBA32F ones, a depth and
    // stencil texture and the members' ids: 16 + 44 bytes a pixel.
    const std::size_t pixels = static_cast<std::size_t>(kSize) * kSize;
    EXPECT_GT(f.stats.textureBytes, 16 * pixels);
    EXPECT_LE(f.stats.textureBytes, (16 + 44) * pixels);
}

TEST_F(RendererGLTest, OnlyIntersectionsOfManyConvexOperandsAreGroupedByDefault) {
    // Spheres around the origin, intersected: up to eight stay operands of
    // their own (the evaluator holds them in registers, cheaper than a
    // group's passes), nine and more are one group; the images agree with
    // the ungrouped frame either way.
    for (const int count : {8, 9}) {
        scene::Tree tree;
        std::vector<int> spheres;
        for (int i = 0; i < count; ++i) {
            const double angle = 0.7 * i;
            spheres.push_back(tree.addLeaf(sphereLeaf({0.4 * std::cos(angle), 0.4 * std::sin(angle), 0.1 * i}, 1.8)));
        }
        tree.root = tree.addNode(NodeKind::Intersection, spheres);
        render::RenderSettings separate, grouped;
        separate.groupOperands = false;
        grouped.convexGroupFrom = 2;
        const camera::Camera camera = topCamera();
        const render::Frame byDefault = draw(tree, camera);
        EXPECT_EQ(byDefault.stats.operands, count < 9 ? count : 1) << count << " spheres";
        EXPECT_EQ(renderer_->render(camera, grouped).stats.operands, 1) << count << " spheres";
        const render::Frame apart = renderer_->render(camera, separate);
        EXPECT_EQ(apart.stats.operands, count);
        ASSERT_GT(byDefault.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 10);
        EXPECT_EQ(pixelsDiffering(byDefault, apart), 0u) << count << " spheres";
        // The setting read again at the next frame of the same scene.
        EXPECT_EQ(renderer_->render(camera, {}).stats.operands, count < 9 ? count : 1) << count << " spheres";
    }
}

TEST_F(RendererGLTest, ConvexIntersectionsAsOneOperandChangeNoSurface) {
    // A lens of a slab and six offset spheres, minus a lens of a sphere and a
    // cube: each an intersection of convex leaves, so each one operand when
    // grouped. Every leaf has its own colour. Grouped and separate, the
    // frames must agree to the bit: the same surfaces, normals and leaves
    // (the subtracted group shows its members' back faces, flipped), seen
    // from above, from inside the model (the near plane cuts every member:
    // rays that start inside all of them), and in tiles.
    scene::Tree tree;
    std::mt19937 rng(61123);
    std::uniform_real_distribution<double> offset(-0.5, 0.5), hue(0.2, 1.0);
    auto coloured = [&](scene::Leaf leaf) {
        leaf.color = glm::dvec4(hue(rng), hue(rng), hue(rng), 1.0);
        return tree.addLeaf(leaf);
    };
    std::vector<int> lens{coloured(cubeLeaf({-2, -2, -1}, {2, 2, 1}))};
    for (int i = 0; i < 6; ++i) lens.push_back(coloured(sphereLeaf({offset(rng), offset(rng), offset(rng)}, 2.2)));
    const int cut = tree.addNode(NodeKind::Intersection, {coloured(sphereLeaf({0.3, 0, 1.1}, 0.9)),
                                                          coloured(cubeLeaf({-0.5, -0.7, -0.5}, {1.2, 0.7, 2}))});
    tree.root = tree.addNode(NodeKind::Difference, {tree.addNode(NodeKind::Intersection, lens), cut});
    render::RenderSettings grouped, separate, tiled;
    grouped.convexGroupFrom = tiled.convexGroupFrom = 2;  // the cut's two members too
    separate.groupOperands = false;
    tiled.memoryBudget = 30 * 30 * 8 * 3;
    for (camera::Projection projection : kProjections) {
        for (double height : {kEyeHeight, 0.0}) {
            camera::Camera camera = topCamera(projection, height);
            if (height == 0.0) camera.fovDegrees = projection == camera::Projection::Perspective ? 90.0 : 60.0;
            const render::Frame one = draw(tree, camera, grouped);
            const render::Frame apart = renderer_->render(camera, separate);
            EXPECT_EQ(one.stats.operands, 2);
            EXPECT_EQ(apart.stats.operands, 9);
            for (std::size_t leaf = 0; leaf < 9; ++leaf) EXPECT_EQ(one.stats.layersPerLeaf[leaf], 1) << leaf;
            const bool above = height == kEyeHeight;
            ASSERT_GT(one.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / (above ? 4 : 20));
            EXPECT_EQ(pixelsDiffering(one, apart), 0u);
            EXPECT_EQ(one.rgba, apart.rgba);
            // Several members show, the subtracted ones flipped.
            std::vector<int> shown(9, 0);
            for (int leaf : one.leaf) {
                if (leaf >= 0) ++shown[static_cast<std::size_t>(leaf)];
            }
            EXPECT_GE(std::count_if(shown.begin(), shown.end(), [](int n) { return n > 20; }), above ? 4 : 2)
                << "projection " << static_cast<int>(projection) << ", eye at " << height;
            // Tiles name the same leaves. (Their shifted viewports round
            // depths near the eye differently from the whole frame's.)
            render::RenderSettings tiledApart = tiled;
            tiledApart.groupOperands = false;
            const render::Frame tiles = renderer_->render(camera, tiled);
            const render::Frame tilesApart = renderer_->render(camera, tiledApart);
            EXPECT_GT(tiles.stats.tiles, 1);
            ASSERT_EQ(tiles.leaf.size(), tilesApart.leaf.size());
            std::size_t otherLeaf = 0;
            for (std::size_t k = 0; k < tiles.leaf.size(); ++k) {
                otherLeaf += tiles.leaf[k] != tilesApart.leaf[k];
                if (tiles.leaf[k] >= 0) {
                    EXPECT_NEAR(tiles.depth[k], tilesApart.depth[k], 1e-5 * tilesApart.depth[k]);
                }
            }
            EXPECT_EQ(otherLeaf, 0u);
            if (above) expectSameAsUntiled(tiles, one);
            // Debug views show every operand's own layers.
            render::RenderSettings layers;
            layers.keepPeelLayers = true;
            EXPECT_EQ(renderer_->render(camera, layers).stats.operands, 9);
        }
    }
}

TEST_F(RendererGLTest, LeafMarksGiveTheFrameOfOneMark) {
    // A slab minus 300 small spheres and a pair of shells: more operands
    // than the stencil's 63 mark slots, so slots repeat (among operands whose
    // rectangles do not meet) and the normal pass must still tell the leaves
    // apart. With leaf marks
    // (where the driver has them) and with one mark for all, every AOV and
    // the image must be the same to the bit.
    scene::Tree tree;
    std::vector<int> children = slabAndSpheres(tree, 7, 300, 1.8, 0.7, 1.1, 0.15);
    children.push_back(tree.addLeaf(shellsLeaf({{0.5, 0.5, 1}, {0.5, 0.5, 0.3}}, 0.3)));
    tree.root = tree.addNode(NodeKind::Difference, children);
    for (camera::Projection p : kProjections) {
        const render::Frame plain = expectMarksChangeNothing(tree, topCamera(p));
        const auto fromHighLeaves = std::count_if(plain.leaf.begin(), plain.leaf.end(), [](int l) { return l >= 255; });
        EXPECT_GT(fromHighLeaves, 50) << "leaves past the 255th must show";
        EXPECT_GT(plain.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 4);
    }
}

TEST_F(RendererGLTest, CrowdedMarkSlotsGiveTheFrameOfOneMark) {
    // A slab minus 90 spheres crowded into one spot: every rectangle meets
    // every other, so the 63 mark slots cannot keep them apart and some
    // spheres share one where they overlap. The normal pass must then check
    // those leaves' depths, and the frame must equal one mark's.
    scene::Tree tree;
    const std::vector<int> holes = slabAndSpheres(tree, 5, 90, 0.4, 0.6, 1.1, 0.45);
    tree.root = tree.addNode(NodeKind::Difference, holes);
    for (camera::Projection p : kProjections) {
        const render::Frame plain = expectMarksChangeNothing(tree, topCamera(p));
        const auto fromSpheres = std::count_if(plain.leaf.begin(), plain.leaf.end(), [](int l) { return l > 63; });
        EXPECT_GT(fromSpheres, 20) << "spheres past the 63rd must show";
    }
}

TEST_F(RendererGLTest, UniqueLeafMarksGiveTheFrameOfOneMark) {
    // Few enough leaves that every leaf, facing and flip has a mark of its
    // own: the normal pass then trusts the stencil test alone for convex
    // leaves. A slab minus spheres (their back faces, flipped), a block
    // sharing the slab's top face (a tie), a sphere cut by an intersection
    // (its own faces) and a pair of shells (non-convex: checked as before),
    // seen from above and from inside the slab (its back faces first).
    scene::Tree tree;
    std::vector<int> holes = slabAndSpheres(tree, 11, 40, 1.6, 0.6, 1.0, 0.3);
    holes.push_back(tree.addLeaf(cubeLeaf({1, 1, 0}, {3, 3, 1})));
    holes.push_back(tree.addLeaf(shellsLeaf({{-0.5, 0.5, 1}, {-0.5, 0.5, 0.3}}, 0.3)));
    const int slab = tree.addNode(NodeKind::Difference, holes);
    const int lens = tree.addNode(NodeKind::Intersection, {tree.addLeaf(sphereLeaf({0, -2.2, 1.2}, 0.8)),
                                                          tree.addLeaf(cubeLeaf({-1, -3, 1.0}, {1, -1.5, 2}))});
    tree.root = tree.addNode(NodeKind::Union, {slab, lens});
    ASSERT_LE(tree.leaves.size(), 63u);
    for (const double eyeHeight : {kEyeHeight, 0.5}) {
        for (camera::Projection p : kProjections) {
            const render::Frame plain = expectMarksChangeNothing(tree, topCamera(p, eyeHeight));
            EXPECT_GT(plain.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 4);
            const auto holeWalls =
                std::count_if(plain.leaf.begin(), plain.leaf.end(), [](int l) { return l > 0 && l <= 40; });
            if (eyeHeight > 1.0) {
                EXPECT_GT(holeWalls, 100) << "the holes' walls (flipped) must show";
            }
        }
    }
}

TEST_F(RendererGLTest, TilesGiveTheSameImageWithinABudget) {
    const scene::Tree tree = paperPair(NodeKind::Difference);
    const render::Frame whole = draw(tree, topCamera());
    EXPECT_EQ(whole.stats.tiles, 1);
    render::RenderSettings small;
    small.memoryBudget = 30 * 30 * 8 * 3;  // three RG32F layers of a 30x30 tile
    const render::Frame tiled = draw(tree, topCamera(), small);
    EXPECT_GT(tiled.stats.tiles, 4);
    EXPECT_FALSE(tiled.stats.notes.empty());
    EXPECT_LE(tiled.stats.textureBytes, small.memoryBudget);
    expectCentre(tiled, kEyeHeight - capHeight(1.0, 1.0, -1), 1, {0, 0, 1});
    expectSameAsUntiled(tiled, whole);
}

// Tiles of one size for the whole frame, however unevenly the operands crowd
// it, so that the next frame peels into the same texture: a sparse quarter
// and a crowded one's sixteenths would each want their own shape.
TEST_F(RendererGLTest, TiledFramesReuseOneLayerTexture) {
    scene::Tree tree;
    std::vector<int> children{tree.addLeaf(cubeLeaf({-2, -2, -2}, {2, 2, 2}))};
    for (int i = 0; i < 12; ++i) children.push_back(tree.addLeaf(sphereLeaf({1.3 + 0.05 * i, 1.3, 2.0 - 0.3 * i}, 0.3)));
    children.push_back(tree.addLeaf(sphereLeaf({-1.2, -1.2, 2.0}, 0.4)));
    tree.root = tree.addNode(NodeKind::Difference, children);
    const render::Frame whole = draw(tree, topCamera());
    EXPECT_EQ(whole.stats.tiles, 1);
    render::RenderSettings small;
    small.memoryBudget = 32 * 32 * 8 * 8;  // eight layers of 32x32: the crowded corner needs 14
    const render::Frame first = draw(tree, topCamera(), small);
    const render::Frame second = renderer_->render(topCamera(), small);
    EXPECT_GT(first.stats.tiles, 4);
    EXPECT_GT(first.stats.textureAllocations, 0);
    EXPECT_EQ(second.stats.textureAllocations, 0);
    EXPECT_LE(second.stats.textureBytes, small.memoryBudget);
    expectSameAsUntiled(second, whole);
}

TEST_F(RendererGLTest, AFrameReadsBackOnlyTheOutputsAskedFor) {
    const scene::Tree tree = paperPair(NodeKind::Difference);
    const render::Frame all = draw(tree, topCamera());
    render::RenderSettings imageOnly;
    imageOnly.readDepth = false;
    imageOnly.readNormal = false;
    const render::Frame image = renderer_->render(topCamera(), imageOnly);
    EXPECT_TRUE(image.depth.empty());
    EXPECT_TRUE(image.normal.empty());
    EXPECT_EQ(image.rgba, all.rgba);
    EXPECT_EQ(image.leaf, all.leaf);
    EXPECT_EQ(image.stats.coveredPixels, all.stats.coveredPixels);
    ASSERT_EQ(all.depth.size(), all.leaf.size());
    ASSERT_EQ(all.normal.size(), all.leaf.size());
    // The full read-back, rows top first: the centre pixel's normal faces the eye above.
    expectCentre(all, kEyeHeight - capHeight(1.0, 1.0, -1), 1, {0, 0, 1});
    render::RenderSettings depthOnly;
    depthOnly.readNormal = false;
    const render::Frame depth = renderer_->render(topCamera(), depthOnly);
    EXPECT_EQ(depth.depth, all.depth);
    EXPECT_TRUE(depth.normal.empty());
}

// Small operands spread over the frame: past coverageTilingFrom, quarters
// that each peel only the spheres that meet them, in a fraction of the
// memory, with the same surfaces as one tile.
TEST_F(RendererGLTest, SmallScatteredOperandsArePeeledInTilesOfTheirOwn) {
    scene::Tree tree;
    tree.root = tree.addNode(NodeKind::Difference, slabAndSpheres(tree, 3, 48, 1.7, 0.7, 1.1, 0.15));
    camera::Camera camera = topCamera();
    camera.width = camera.height = 512;
    // 49 layers and a scratch one of 512 x 512 x 8 bytes: 100 MiB in one tile.
    render::RenderSettings roomy;
    roomy.coverageTilingFrom = std::size_t(16) << 20;
    render::Renderer fresh;  // the shared renderer keeps the largest layer texture of the tests before
    fresh.setScene(tree, model::buildModel(tree));
    const render::Frame tiled = fresh.render(camera, roomy);  // first: the texture is made for the tiles
    render::RenderSettings whole;
    whole.coverageTilingFrom = std::numeric_limits<std::size_t>::max();
    const render::Frame one = fresh.render(camera, whole);
    EXPECT_EQ(one.stats.tiles, 1);
    EXPECT_GE(tiled.stats.tiles, 4);
    EXPECT_LT(tiled.stats.textureBytes * 4, one.stats.textureBytes) << "each tile holds the layers of few spheres";
    EXPECT_LE(tiled.stats.peelPasses, 2 * one.stats.peelPasses);
    ASSERT_EQ(tiled.stats.notes.size(), 1u);
    EXPECT_NE(tiled.stats.notes[0].find("only the operands that meet it"), std::string::npos) << tiled.stats.notes[0];
    EXPECT_EQ(tiled.stats.notes[0].find("budget"), std::string::npos) << tiled.stats.notes[0];
    expectSameAsUntiled(tiled, one);
}

// Operands that span the frame would be drawn once per tile: they stay in
// one, however low the threshold.
TEST_F(RendererGLTest, OperandsThatSpanTheFrameStayInOneTile) {
    scene::Tree tree;
    const int slab = tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}));
    const int big = tree.addLeaf(sphereLeaf({0.1, -0.1, 1.0}, 1.9));
    const int bigger = tree.addLeaf(sphereLeaf({-0.1, 0.1, 1.4}, 2.2));
    tree.root = tree.addNode(NodeKind::Difference, {slab, big, bigger});
    camera::Camera camera = topCamera();
    camera.width = camera.height = 512;
    render::RenderSettings eager;
    eager.coverageTilingFrom = 0;
    EXPECT_EQ(draw(tree, camera, eager).stats.tiles, 1);
}

TEST_F(RendererGLTest, AutoPeelingDeeperThanGuessedSplitsTheTile) {
    // The guess is 2 layers for a non-convex operand (and a scratch layer);
    // four shells stacked on the view axis need 4. A budget of exactly the
    // guess for the whole frame forces a split once peeling pass by pass
    // goes deeper. (Fragment lists make room for 4 layers from the start.)
    scene::Tree tree;
    const int slab = tree.addLeaf(cubeLeaf({-2, -2, -1}, {2, 2, 1}));
    const int spheres = tree.addLeaf(shellsLeaf({{0, 0, 1}, {0, 0, 0}, {0, 0, -1}, {0, 0, -2}}, 0.4));
    tree.root = tree.addNode(NodeKind::Difference, {slab, spheres});
    render::RenderSettings tight;
    tight.fragmentListTriangles = -1;
    tight.memoryBudget = static_cast<std::size_t>(kSize) * kSize * 8 * (1 + 2 + 1);
    const render::Frame f = draw(tree, topCamera(), tight);
    EXPECT_GT(f.stats.tiles, 1);
    EXPECT_LE(f.stats.textureBytes, tight.memoryBudget);
    ASSERT_FALSE(f.stats.notes.empty());
    EXPECT_NE(f.stats.notes.back().find("split"), std::string::npos) << f.stats.notes.back();
    expectCentre(f, kEyeHeight - capHeight(1.0, 0.4, -1), 1, {0, 0, 1});
    EXPECT_EQ(f.stats.layersPerLeaf[1], 4);
}

TEST_F(RendererGLTest, ABudgetTooSmallForOnePixelIsAnError) {
    render::RenderSettings none;
    none.memoryBudget = 16;
    EXPECT_THROW(draw(paperPair(NodeKind::Difference), topCamera(), none), Error);
}

TEST_F(RendererGLTest, ManyOperandsUseALargerEvaluator) {
    // 40 thin slabs stacked along the view axis, unioned in shuffled order:
    // the top of the highest one is visible. 40 operands > 32 per-pixel slots.
    scene::Tree tree;
    std::vector<int> leaves;
    for (int i = 0; i < 40; ++i) {
        const int k = (i * 17) % 40;
        const double z = -2.0 + 0.1 * k;
        leaves.push_back(tree.addLeaf(cubeLeaf({-0.5, -0.5, z}, {0.5, 0.5, z + 0.05})));
    }
    tree.root = tree.addNode(NodeKind::Union, leaves);
    // Fewer than RenderSettings::unionGroupFrom: no union group.
    const render::Frame f = draw(tree, topCamera());
    // Highest slab: k = 39, top at -2 + 3.9 + 0.05; leaf index i with 17 i = 39 mod 40 -> i = 7.
    expectCentre(f, kEyeHeight - (-2.0 + 3.9 + 0.05), 7, {0, 0, 1});
    EXPECT_EQ(f.stats.operands, 40);
}

TEST_F(RendererGLTest, ColoursFollowTheSchemeAndTheLeaves) {
    scene::Tree tree = paperPair(NodeKind::Difference);
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));
    const render::ColorScheme& cornfield = render::colorScheme("Cornfield");
    // Background: the scheme's colour, opaque.
    const std::size_t bg = at(f, 0, 0) * 4;
    EXPECT_EQ(f.rgba[bg + 0], 255);
    EXPECT_EQ(f.rgba[bg + 1], 255);
    EXPECT_EQ(f.rgba[bg + 2], 229);
    EXPECT_EQ(f.rgba[bg + 3], 255);
    // Lit surfaces keep the hue of their base colour: cut face (green) at the
    // centre, face colour (yellow) on the cube's rim.
    auto ratio = [&](std::size_t k) { return double(f.rgba[k * 4]) / double(f.rgba[k * 4 + 1]); };
    EXPECT_NEAR(ratio(at(f, kCentre, kCentre)), cornfield.faceBack.r / cornfield.faceBack.g, 0.03);
    const double h = 10.0 * std::tan(22.5 / 2.0 * std::numbers::pi / 180.0);
    const int rim = static_cast<int>(std::floor((1.0 - 0.98 / h) * kSize / 2.0));  // |x| ~ 0.98
    const std::size_t onRim = at(f, rim + 1, rim + 1);
    ASSERT_EQ(f.leaf[onRim], 0);
    EXPECT_NEAR(ratio(onRim), cornfield.faceFront.r / cornfield.faceFront.g, 0.03);

    // A leaf colour wins over the scheme, cut face included.
    tree.leaves[1].color = glm::dvec4(0.0, 0.0, 1.0, 1.0);
    const render::Frame blue = draw(tree, topCamera(camera::Projection::Orthographic));
    const std::size_t c = at(blue, kCentre, kCentre) * 4;
    EXPECT_EQ(blue.rgba[c + 0], 0);
    EXPECT_EQ(blue.rgba[c + 1], 0);
    EXPECT_GT(blue.rgba[c + 2], 100);

    // Another scheme changes the background.
    render::RenderSettings starnight;
    starnight.colorScheme = "Starnight";
    const render::Frame night = draw(tree, topCamera(), starnight);
    EXPECT_EQ(night.rgba[bg + 0], 0);
    EXPECT_EQ(night.rgba[bg + 3], 255);
}

TEST_F(RendererGLTest, ShadingAFramesOwnResultGivesItsImage) {
    // render() gets each pixel's base colour from the normal pass, shade()
    // (strata-render --reference) packs it on the CPU: fed render()'s own
    // AOVs, shade() must give render()'s image to the bit.
    scene::Tree tree = paperPair(NodeKind::Difference);
    tree.leaves[0].color = glm::dvec4(0.2, 0.6, 0.9, 1.0);  // the cube its own; the cut sphere the scheme's
    const camera::Camera camera = topCamera();
    const render::Frame f = draw(tree, camera);
    std::vector<std::uint8_t> cut(f.leaf.size());
    for (std::size_t k = 0; k < cut.size(); ++k) cut[k] = f.leaf[k] == 1 ? 1 : 0;  // the sphere acts subtracted
    ASSERT_GT(std::count(cut.begin(), cut.end(), 1), 100);
    ASSERT_GT(std::count(f.leaf.begin(), f.leaf.end(), 0), 100);
    const render::Frame shaded = renderer_->shade(camera, {}, {f.depth, f.normal, f.leaf, cut});
    EXPECT_EQ(shaded.rgba, f.rgba);
}

TEST_F(RendererGLTest, BackgroundLeavesAreDrawnButNotInTheCsg) {
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}));
    scene::Leaf ghost = cubeLeaf({-1.2, -1.2, -3}, {1.2, 1.2, -2});
    ghost.display = scene::Display::Background;
    const int g = tree.addLeaf(ghost);
    tree.root = tree.addNode(NodeKind::Union, {cube});
    tree.background = {g};
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));
    // Outside the cube but over the ghost: no CSG surface, but not plain background.
    const double h = 10.0 * std::tan(22.5 / 2.0 * std::numbers::pi / 180.0);
    const int i = static_cast<int>(std::floor((1.0 - 1.1 / h) * kSize / 2.0));  // x ~ -1.1
    const std::size_t k = at(f, i, kCentre);
    EXPECT_EQ(f.leaf[k], -1);
    EXPECT_TRUE(std::isinf(f.depth[k]));
    EXPECT_NE(f.rgba[k * 4 + 2], 229);  // blended grey over the background
    EXPECT_EQ(f.rgba[k * 4 + 3], 255);
    EXPECT_EQ(f.stats.operands, 1);
}

// Translucent color()s, as OpenSCAD 2021.01's preview draws them
// (docs/algorithm.md, "Translucent colours"): a surface of alpha a is lit as
// any other (F) and blended over what OpenSCAD shows behind it (U):
// a F + (1 - a) U. For a leaf alone in its product, U is its own back face
// over the background, a B + (1 - a) background; else the background.
// Seen from straight above, orthographic: the ray is -Z, right +X, up +Y, so
// strata's light (light.glsl) gives a face of normal +Z, and a back face
// seen from inside it, ambient 0.35 + 0.65 Lambert towards
// normalize(+Z + 0.25 (up - right)).
namespace {

double topLight() {
    const glm::dvec3 toLight = glm::normalize(glm::dvec3(-0.25, 0.25, 1.0));
    return 0.35 + 0.65 * toLight.z;
}

// The centre pixel's colour, 0..255.
glm::dvec3 centreColour(const render::Frame& f) {
    const std::size_t c = at(f, kCentre, kCentre) * 4;
    return {f.rgba[c + 0], f.rgba[c + 1], f.rgba[c + 2]};
}

void expectColour(const glm::dvec3& got, const glm::dvec3& want) {
    // The lit colour is rounded to 8 bits before the blend.
    EXPECT_NEAR(got.r, want.r, 2.0);
    EXPECT_NEAR(got.g, want.g, 2.0);
    EXPECT_NEAR(got.b, want.b, 2.0);
}

const glm::dvec3 kCornfield{255.0, 255.0, 229.0};

}  // namespace

TEST_F(RendererGLTest, ATranslucentLeafAloneShowsItsBackFacesOverTheBackground) {
    const double a = 0.3, lit = topLight();
    scene::Tree tree;
    scene::Leaf red = cubeLeaf({-1, -1, -1}, {1, 1, 1});
    red.color = glm::dvec4(1.0, 0.0, 0.0, a);
    const int cube = tree.addLeaf(red);
    tree.root = tree.addNode(NodeKind::Union, {cube});
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));
    // Back face (the bottom, lit as seen from inside) over the background,
    // then the top face over that.
    const glm::dvec3 top(255.0 * lit, 0.0, 0.0);
    const glm::dvec3 under = a * top + (1.0 - a) * kCornfield;
    expectColour(centreColour(f), a * top + (1.0 - a) * under);
    EXPECT_EQ(f.rgba[at(f, kCentre, kCentre) * 4 + 3], 255);  // the image stays opaque
    EXPECT_EQ(f.leaf[at(f, kCentre, kCentre)], 0);            // and the AOVs see the surface

    // An opaque colour is drawn as before: lit, nothing behind it.
    tree.leaves[0].color = glm::dvec4(1.0, 0.0, 0.0, 1.0);
    expectColour(centreColour(draw(tree, topCamera(camera::Projection::Orthographic))), top);

    // What lies behind a translucent surface stays hidden, as in OpenSCAD
    // where the translucent object is drawn first: a blue slab under the cube.
    tree.leaves[0].color = glm::dvec4(1.0, 0.0, 0.0, a);
    scene::Leaf blue = cubeLeaf({-3, -3, -3}, {3, 3, -2});
    blue.color = glm::dvec4(0.0, 0.0, 1.0, 1.0);
    const int slab = tree.addLeaf(blue);
    tree.nodes[static_cast<std::size_t>(tree.root)].children.push_back(slab);
    const render::Frame behind = draw(tree, topCamera(camera::Projection::Orthographic));
    expectColour(centreColour(behind), centreColour(f));
    const std::size_t beside = at(behind, kCentre, 5) * 4;  // y ~ 1.8: the slab alone
    EXPECT_EQ(behind.rgba[beside + 0], 0);
    EXPECT_NEAR(behind.rgba[beside + 2], 255.0 * lit, 2.0);
}

TEST_F(RendererGLTest, ATranslucentLeafWithOthersShowsTheBackgroundOnce) {
    // In a difference or an intersection the leaf is no product of its own:
    // OpenSCAD draws only the visible surface, over the background.
    const double a = 0.3, lit = topLight();
    const glm::dvec3 want = a * glm::dvec3(255.0 * lit, 0.0, 0.0) + (1.0 - a) * kCornfield;
    for (const NodeKind op : {NodeKind::Difference, NodeKind::Intersection}) {
        scene::Tree tree;
        scene::Leaf red = cubeLeaf({-1, -1, -1}, {1, 1, 1});
        red.color = glm::dvec4(1.0, 0.0, 0.0, a);
        const int cube = tree.addLeaf(red);
        // A corner cut off, or a sphere that holds the cube's top centre.
        const int other = tree.addLeaf(op == NodeKind::Difference ? cubeLeaf({0.8, 0.8, 0.8}, {1.5, 1.5, 1.5})
                                                                  : sphereLeaf({0, 0, 0}, 1.6));
        tree.root = tree.addNode(NodeKind::Union, {tree.addNode(op, {cube, other})});
        const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));
        ASSERT_EQ(f.leaf[at(f, kCentre, kCentre)], 0);
        expectColour(centreColour(f), want);
    }
}

TEST_F(RendererGLTest, ATranslucentSubtrahendsCutFacesShowTheBackgroundOnce) {
    const double a = 0.4, lit = topLight();
    scene::Tree tree = paperPair(NodeKind::Difference);
    tree.leaves[1].color = glm::dvec4(0.0, 0.0, 1.0, a);
    const render::Frame f = draw(tree, topCamera(camera::Projection::Orthographic));
    ASSERT_EQ(f.leaf[at(f, kCentre, kCentre)], 1);  // the sphere's inside, its normal flipped up
    expectColour(centreColour(f), a * glm::dvec3(0.0, 0.0, 255.0 * lit) + (1.0 - a) * kCornfield);
}

TEST_F(RendererGLTest, ShadingAFramesOwnResultKeepsItsTranslucentColours) {
    // strata-render --reference shades the reference's AOVs through shade():
    // translucent leaves, alone and subtracted, must come out as render() draws them.
    scene::Tree tree = paperPair(NodeKind::Difference);
    tree.leaves[1].color = glm::dvec4(0.0, 0.0, 1.0, 0.4);
    scene::Leaf alone = sphereLeaf({1.6, 1.6, 0}, 0.5);
    alone.color = glm::dvec4(0.0, 1.0, 0.0, 0.6);
    const int beside = tree.addLeaf(alone);
    tree.nodes[static_cast<std::size_t>(tree.root)].children.push_back(beside);
    const camera::Camera camera = topCamera();
    const render::Frame f = draw(tree, camera);
    std::vector<std::uint8_t> cut(f.leaf.size());
    for (std::size_t k = 0; k < cut.size(); ++k) cut[k] = f.leaf[k] == 1 ? 1 : 0;
    ASSERT_GT(std::count(f.leaf.begin(), f.leaf.end(), 2), 20);
    const render::Frame shaded = renderer_->shade(camera, {}, {f.depth, f.normal, f.leaf, cut});
    EXPECT_EQ(shaded.rgba, f.rgba);
}

TEST_F(RendererGLTest, EmptyResultAndBadSettings) {
    scene::Tree tree;
    const int cube = tree.addLeaf(cubeLeaf({-1, -1, -1}, {1, 1, 1}));
    tree.root = tree.addNode(NodeKind::Intersection, {cube, tree.addNode(NodeKind::Union, {})});
    const render::Frame f = draw(tree, topCamera());
    EXPECT_EQ(f.stats.coveredPixels, 0u);
    EXPECT_EQ(f.stats.operands, 0);

    render::RenderSettings bad;
    bad.colorScheme = "NoSuchScheme";
    EXPECT_THROW(renderer_->render(topCamera(), bad), Error);
    bad = {};
    bad.layers = -1;
    EXPECT_THROW(renderer_->render(topCamera(), bad), Error);
    camera::Camera zero = topCamera();
    zero.width = 0;
    EXPECT_THROW(renderer_->render(zero, {}), Error);
}

TEST_F(RendererGLTest, GroupedMembersSharingAFaceShowTheLowestLeafThere) {
    // Blocks with their tops in one plane, intersected, the whole turned by
    // odd angles: rounding puts the tops a hair apart on each pixel, this
    // way or that. Grouped (one operand) or not, every pixel of the common
    // top shows the lowest leaf, as the evaluator's rule for coincident
    // surfaces has it (GroupPeel.h, "ties"): in a group of two, and in one of
    // more than GroupPeel::kMostTieMembers, which looks for ties because its
    // members share a plane.
    const glm::dmat4 turn = glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(23.0), glm::dvec3(1, 0, 0)),
                                        glm::radians(11.0), glm::dvec3(0, 1, 0));
    auto turned = [&](scene::Leaf leaf) {
        leaf.transform = turn * leaf.transform;
        return leaf;
    };
    for (const int count : {2, 10}) {
        scene::Tree tree;
        std::vector<int> blocks{tree.addLeaf(turned(cubeLeaf({-2, -2, -2}, {2, 2, 1})))};
        for (int k = 1; k < count; ++k) {
            const double grow = 0.02 * k;
            blocks.push_back(tree.addLeaf(turned(cubeLeaf({-1 - grow, -1.5 - grow, -3}, {1.5 + grow, 1 + grow, 1}))));
        }
        tree.root = tree.addNode(NodeKind::Intersection, blocks);
        render::RenderSettings separate, grouped;
        separate.groupOperands = false;
        grouped.convexGroupFrom = 2;
        const camera::Camera camera = topCamera();
        const render::Frame one = draw(tree, camera, grouped);
        const render::Frame apart = renderer_->render(camera, separate);
        EXPECT_EQ(one.stats.operands, 1);
        EXPECT_EQ(one.stats.peelPasses, 4) << count << " members";  // entries, exits and their ties
        std::size_t top = 0, lowest = 0, lowestApart = 0;
        const glm::vec3 up = glm::vec3(turn * glm::dvec4(0, 0, 1, 0));
        for (std::size_t k = 0; k < one.leaf.size(); ++k) {
            if (one.leaf[k] < 0 || glm::dot(one.normal[k], up) < 0.999f) continue;
            ++top;
            lowest += one.leaf[k] == blocks[0];
            lowestApart += apart.leaf[k] == blocks[0];
        }
        EXPECT_GT(top, static_cast<std::size_t>(kSize * kSize) / 10) << count << " members";
        EXPECT_EQ(lowest, top) << count << " members";
        EXPECT_EQ(lowestApart, top) << count << " members";
    }
}

TEST_F(RendererGLTest, UnitedMembersSharingAFaceShowTheLowestLeafThere) {
    // The union of a block and smaller blocks standing in it with their
    // tops in its top's plane, turned by odd angles: rounding puts the tops
    // a hair apart, this way or that. As one union group or as operands of
    // their own, every pixel of the common top shows the lowest leaf, and
    // the frames agree to the bit; in a group of two, and in one of more
    // than GroupPeel::kMostTieMembers, which looks for ties because its
    // members share a plane.
    const glm::dmat4 turn = glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(23.0), glm::dvec3(1, 0, 0)),
                                        glm::radians(11.0), glm::dvec3(0, 1, 0));
    auto turned = [&](scene::Leaf leaf, int k) {
        leaf.transform = turn * leaf.transform;
        leaf.color = glm::dvec4(0.2 + 0.07 * k, 0.5, 0.9 - 0.05 * k, 1.0);
        return leaf;
    };
    for (const int count : {2, 10}) {
        scene::Tree tree;
        std::vector<int> blocks{tree.addLeaf(turned(cubeLeaf({-2, -2, -2}, {2, 2, 1}), 0))};
        for (int k = 1; k < count; ++k) {
            const double grow = 0.03 * k;
            blocks.push_back(
                tree.addLeaf(turned(cubeLeaf({-1.5 - grow, -0.5 - grow, -3}, {0.5 + grow, 1.5, 1}), k)));
        }
        tree.root = tree.addNode(NodeKind::Union, blocks);
        render::RenderSettings separate, unite;
        separate.groupOperands = false;
        unite.unionGroupFrom = 2;
        separate.plainUnions = unite.plainUnions = false;  // the groups' peel is what is tested
        const camera::Camera camera = topCamera();
        const render::Frame one = draw(tree, camera, unite);
        const render::Frame apart = renderer_->render(camera, separate);
        EXPECT_EQ(one.stats.operands, 1);
        EXPECT_EQ(apart.stats.operands, count);
        EXPECT_EQ(one.stats.peelPasses, 4) << count << " members";  // entries, exits and their ties
        // The top is the first block's, with every other block's in it.
        std::size_t top = 0, lowest = 0;
        const glm::vec3 up = glm::vec3(turn * glm::dvec4(0, 0, 1, 0));
        for (std::size_t k = 0; k < one.leaf.size(); ++k) {
            if (one.leaf[k] < 0 || glm::dot(one.normal[k], up) < 0.999f) continue;
            ++top;
            lowest += one.leaf[k] == blocks[0];
        }
        EXPECT_GT(top, static_cast<std::size_t>(kSize * kSize) / 10) << count << " members";
        EXPECT_EQ(lowest, top) << count << " members";
        EXPECT_EQ(pixelsDiffering(one, apart), 0u) << count << " members";
        EXPECT_EQ(one.rgba, apart.rgba) << count << " members";
    }
}

TEST_F(RendererGLTest, UnitedOperandsChangeNoSurface) {
    // A union of 60 coloured spheres, blocks and sets of shells (non-convex),
    // overlapping, and beside them a block minus a ball whose top lies in the
    // plane of a united block's top (a cluster of a group's surface and
    // another operand's). Outside the model the united leaves are one
    // operand (one layer), else their own; either way the frames agree with
    // the ungrouped ones to the bit: surfaces, normals, leaves and colours,
    // whole and in tiles. From inside the model's box nothing is united.
    scene::Tree tree;
    std::mt19937 rng(7719);
    std::uniform_real_distribution<double> at(-1.6, 1.6), size(0.15, 0.5), hue(0.2, 1.0);
    auto coloured = [&](scene::Leaf leaf) {
        leaf.color = glm::dvec4(hue(rng), hue(rng), hue(rng), 1.0);
        return tree.addLeaf(leaf);
    };
    std::vector<int> parts;
    for (int i = 0; i < 60; ++i) {
        const glm::dvec3 c(at(rng), at(rng), 0.5 * at(rng));
        const double r = size(rng);
        if (i % 5 == 4) {
            parts.push_back(coloured(shellsLeaf({c + glm::dvec3(0, 0, 0.6), c, c - glm::dvec3(0, 0, 0.6)}, r * 0.6)));
        } else if (i % 2 == 0) {
            parts.push_back(coloured(sphereLeaf(c, r)));
        } else {
            parts.push_back(coloured(cubeLeaf(c - glm::dvec3(r), c + glm::dvec3(r, r, 0.8 - c.z))));
        }
    }
    const int block = coloured(cubeLeaf({1.0, -2.4, -1.0}, {2.2, -1.2, 0.8}));
    parts.push_back(tree.addNode(NodeKind::Difference, {block, coloured(sphereLeaf({1.6, -1.8, 0.8}, 0.4))}));
    parts.push_back(coloured(cubeLeaf({0.4, -2.0, -0.5}, {1.4, -1.0, 0.8})));  // its top in the block's plane
    tree.root = tree.addNode(NodeKind::Union, parts);
    render::RenderSettings unite, separate, tiled, tiledApart;
    unite.unionGroupFrom = tiled.unionGroupFrom = 2;  // 61 united leaves: fewer than the default asks
    separate.groupOperands = false;
    tiled.memoryBudget = tiledApart.memoryBudget = 40 * 40 * 8 * 6;
    tiledApart.groupOperands = false;
    // The peel's union groups here: not the plain leaves beside the CSG
    // drawn plainly first (PlainFrameGLTest).
    for (render::RenderSettings* settings : {&unite, &separate, &tiled, &tiledApart}) settings->plainUnions = false;
    for (camera::Projection projection : kProjections) {
        for (double height : {kEyeHeight, 0.0}) {
            camera::Camera camera = topCamera(projection, height);
            if (height == 0.0) camera.fovDegrees = projection == camera::Projection::Perspective ? 90.0 : 60.0;
            const render::Frame one = draw(tree, camera, unite);
            const render::Frame apart = renderer_->render(camera, separate);
            const bool outside = height == kEyeHeight;
            EXPECT_EQ(one.stats.operands, outside ? 3 : apart.stats.operands);
            ASSERT_GT(one.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / (outside ? 4 : 20));
            EXPECT_EQ(pixelsDiffering(one, apart), 0u) << "projection " << static_cast<int>(projection)
                                                       << ", eye at " << height;
            EXPECT_EQ(one.rgba, apart.rgba);
            if (!outside) continue;
            const render::Frame tiles = renderer_->render(camera, tiled);
            const render::Frame tilesApart = renderer_->render(camera, tiledApart);
            EXPECT_GT(tiles.stats.tiles, 1);
            EXPECT_EQ(pixelsDiffering(tiles, tilesApart), 0u);
        }
    }
}

TEST_F(RendererGLTest, ASceneWhoseMeshesAreLetGoRendersTheSame) {
    // setScene with the model handed over lets each mesh go as it reaches
    // the GPU; the frame must be the one of a kept model, to the bit, and
    // the model is left empty. A union of spheres and blocks minus a block.
    scene::Tree tree;
    std::vector<int> parts;
    for (int i = 0; i < 40; ++i) {
        const double x = -1.8 + 0.09 * i;
        parts.push_back(tree.addLeaf(i % 2 ? sphereLeaf({x, 0.3 * std::sin(i), 0}, 0.35)
                                           : cubeLeaf({x - 0.2, -0.9, -0.4}, {x + 0.2, 0.9, 0.3})));
    }
    tree.root = tree.addNode(NodeKind::Difference,
                             {tree.addNode(NodeKind::Union, parts), tree.addLeaf(cubeLeaf({-1, -1, 0.1}, {1, 0, 1}))});
    const camera::Camera camera = topCamera();
    const render::Frame kept = draw(tree, camera);
    model::Model model = model::buildModel(tree);
    renderer_->setScene(tree, std::move(model));
    EXPECT_TRUE(model.leafMeshes.empty());  // NOLINT(bugprone-use-after-move): the contract says so
    const render::Frame released = renderer_->render(camera, {});
    ASSERT_GT(kept.stats.coveredPixels, static_cast<std::size_t>(kSize * kSize) / 10);
    EXPECT_EQ(pixelsDiffering(kept, released), 0u);
    EXPECT_EQ(kept.rgba, released.rgba);
}
