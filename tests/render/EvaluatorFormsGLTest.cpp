// The evaluator's fast forms against its general one. The first-surface form
// (a block's tree is one operand of one layer), the register form (operands
// of at most eight peeled layers in all, convex or not) and the product form
// (many one-layer operands under one AND or OR) are shortcuts of the array
// form's walk; the array form is checked against the CPU reference and a
// brute-force ray caster elsewhere (RendererOracleGLTest, DeepPixelGLTest,
// the accuracy suite). Here every fast-form frame must equal the array
// form's frame bit for bit: coverage, tagged depth, leaf and normal, on
// random products and unions seen from outside and from inside (the near
// plane cutting operands, so that they start inside).

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "SphereShells.h"

using namespace strata;
using scene::NodeKind;

namespace {

// A random convex solid (cube, sphere, cylinder or cone) near the origin.
scene::Leaf convexLeaf(std::mt19937& rng, double spread) {
    std::uniform_real_distribution<double> size(0.6, 1.8), pos(-spread, spread), angle(0.0, 360.0);
    scene::Leaf leaf;
    switch (rng() % 3) {
        case 0: leaf.primitive = scene::Cube{{size(rng), size(rng), size(rng)}, true}; break;
        case 1: {
            scene::Sphere s;
            s.r = size(rng) * 0.7;
            s.fragments.fn = 8 + static_cast<double>(rng() % 10);
            leaf.primitive = s;
            break;
        }
        default: {
            scene::Cylinder c;
            c.h = size(rng) * 1.5;
            c.r1 = size(rng) * 0.5;
            c.r2 = rng() % 3 == 0 ? 0.0 : size(rng) * 0.5;
            c.center = true;
            c.fragments.fn = 6 + static_cast<double>(rng() % 10);
            leaf.primitive = c;
        }
    }
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), {pos(rng), pos(rng), pos(rng)});
    leaf.transform = glm::rotate(m, glm::radians(angle(rng)), glm::normalize(glm::dvec3(0.3, pos(rng), 1.0)));
    return leaf;
}

// One node of `count` leaves, the last `shells` of them non-convex (two
// sphere shells in one polyhedron: two peeled layers where they overlap on
// screen), the others convex. A difference keeps a big first operand so that
// something is left; an intersection keeps its operands close.
scene::Tree flatTree(NodeKind kind, int count, std::mt19937& rng, int shells = 0) {
    scene::Tree tree;
    std::vector<int> children;
    for (int i = 0; i < count; ++i) {
        scene::Leaf leaf = convexLeaf(rng, kind == NodeKind::Intersection ? 0.3 : 1.5);
        if (i >= count - shells) {
            std::uniform_real_distribution<double> unit(-1.0, 1.0);
            const glm::dvec3 half = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 0.45;
            leaf.primitive = test::sphereShells({-half, half}, 0.55, 12);
        }
        if (kind == NodeKind::Difference && i == 0) leaf.primitive = scene::Cube{{3.0, 3.0, 3.0}, true};
        if (kind == NodeKind::Intersection) leaf.transform = glm::scale(leaf.transform, glm::dvec3(2.0));
        children.push_back(tree.addLeaf(std::move(leaf)));
    }
    tree.root = tree.addNode(kind, children);
    return tree;
}

camera::Camera cameraFor(int which, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    glm::dvec3 dir;
    do dir = {unit(rng), unit(rng), unit(rng)};
    while (glm::length(dir) < 0.3 || std::abs(glm::normalize(dir).z) > 0.95);
    dir = glm::normalize(dir);
    camera::Camera camera;
    camera.width = camera.height = 64;
    if (which == 0) {  // outside, perspective
        camera.eye = dir * 9.0;
        camera.center = glm::dvec3(0.0);
        camera.fovDegrees = 35.0;
    } else if (which == 1) {  // outside, orthographic
        camera.projection = camera::Projection::Orthographic;
        camera.eye = dir * 8.0;
        camera.center = glm::dvec3(0.0);
        camera.fovDegrees = 40.0;
    } else {  // inside the model's box: the near plane cuts operands
        camera.eye = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 0.4;
        camera.center = camera.eye - dir;
        camera.fovDegrees = 80.0;
    }
    return camera;
}

// Bit-for-bit equality of two frames' AOVs; `what` names the case.
void expectSameFrame(const render::Frame& fast, const render::Frame& general, const std::string& what) {
    ASSERT_EQ(fast.leaf.size(), general.leaf.size());
    std::size_t differ = 0;
    for (std::size_t p = 0; p < fast.leaf.size(); ++p) {
        const bool same = fast.leaf[p] == general.leaf[p] &&
                          std::memcmp(&fast.depth[p], &general.depth[p], sizeof(float)) == 0 &&
                          std::memcmp(&fast.normal[p], &general.normal[p], sizeof(glm::vec3)) == 0;
        if (!same && ++differ <= 3) {
            ADD_FAILURE() << what << ", pixel " << p % static_cast<std::size_t>(fast.width) << ","
                          << p / static_cast<std::size_t>(fast.width) << ": fast form leaf " << fast.leaf[p]
                          << " depth " << fast.depth[p] << " normal " << fast.normal[p].x << "," << fast.normal[p].y
                          << "," << fast.normal[p].z << ", array form leaf " << general.leaf[p] << " depth "
                          << general.depth[p] << " normal " << general.normal[p].x << "," << general.normal[p].y << ","
                          << general.normal[p].z << " form " << static_cast<int>(fast.blockForms[p]);
        }
    }
    EXPECT_EQ(differ, 0u) << what;
    EXPECT_EQ(fast.stats.unresolvedPixels, 0u) << what;
    EXPECT_EQ(general.stats.unresolvedPixels, 0u) << what;
}

// One view drawn twice: by the cheapest form of each block, then by the
// array form alone. Every operand is its own: grouped, an intersection of
// convex solids would be one operand and one form (ConvexGroups.h).
std::pair<render::Frame, render::Frame> fastAndGeneral(render::Renderer& renderer, const camera::Camera& camera) {
    render::RenderSettings settings;
    settings.groupOperands = false;
    settings.keepBlockForms = true;
    render::Frame fast = renderer.render(camera, settings);
    settings.generalEvaluator = true;
    return {std::move(fast), renderer.render(camera, settings)};
}

struct FormsCase {
    NodeKind kind;
    int count;
    int shells = 0;  // non-convex leaves among them (flatTree)
};

}  // namespace

class EvaluatorForms : public ::testing::TestWithParam<FormsCase> {};

TEST_P(EvaluatorForms, EqualTheArrayForm) {
    const FormsCase c = GetParam();
    gpu::Context context;
    render::Renderer renderer;
    std::mt19937 rng(static_cast<unsigned>(1000 + c.count * 7 + static_cast<int>(c.kind) + c.shells * 101));
    std::size_t covered = 0, insideStarts = 0, multiLayer = 0;
    render::FrameStats fastBlocks;
    for (int s = 0; s < 4; ++s) {
        const scene::Tree tree = flatTree(c.kind, c.count, rng, c.shells);
        const model::Model model = model::buildModel(tree);
        renderer.setScene(tree, model);
        for (int which = 0; which < 3; ++which) {
            const camera::Camera camera = cameraFor(which, rng);
            const auto [fast, general] = fastAndGeneral(renderer, camera);
            expectSameFrame(fast, general,
                            std::string(scene::kindName(c.kind)) + " of " + std::to_string(c.count) + ", scene " + std::to_string(s) +
                                ", camera " + std::to_string(which));
            EXPECT_EQ(general.stats.firstSurfaceBlocks + general.stats.registerBlocks + general.stats.productBlocks,
                      0u);
            fastBlocks.firstSurfaceBlocks += fast.stats.firstSurfaceBlocks;
            fastBlocks.registerBlocks += fast.stats.registerBlocks;
            fastBlocks.productBlocks += fast.stats.productBlocks;
            fastBlocks.arrayBlocks += fast.stats.arrayBlocks;
            covered += fast.stats.coveredPixels;
            if (which == 2) insideStarts += fast.stats.coveredPixels;
            for (int layers : fast.stats.layersPerLeaf) multiLayer += layers > 1 ? 1 : 0;
        }
    }
    EXPECT_GT(covered, 12u * 64u * 64u / 10u) << "the scenes must show something";
    EXPECT_GT(insideStarts, 0u) << "the cameras inside must see something";
    // The fast forms must have been the ones drawn: a shells leaf has at
    // most two layers, so every block of at most eight operands fits the
    // register form's sixteen slots.
    EXPECT_EQ(fastBlocks.arrayBlocks, 0u);
    // Blocks that one operand alone meets take the first-surface form: the
    // first operand of a difference, any operand of a union.
    if (c.kind != NodeKind::Intersection) {
        EXPECT_GT(fastBlocks.firstSurfaceBlocks, 0u);
    }
    if (c.shells > 0) {
        EXPECT_GT(multiLayer, 0u) << "some shells must have needed two layers";
        EXPECT_GT(fastBlocks.registerBlocks, 0u);
    } else if (c.count > 8) {
        EXPECT_GT(fastBlocks.productBlocks, 0u);
    } else {
        EXPECT_GT(fastBlocks.registerBlocks, 0u);
    }
}

INSTANTIATE_TEST_SUITE_P(Trees, EvaluatorForms,
                         ::testing::Values(FormsCase{NodeKind::Difference, 6}, FormsCase{NodeKind::Intersection, 5},
                                           FormsCase{NodeKind::Union, 7}, FormsCase{NodeKind::Difference, 24},
                                           FormsCase{NodeKind::Intersection, 20}, FormsCase{NodeKind::Union, 30},
                                           FormsCase{NodeKind::Difference, 4, 3}, FormsCase{NodeKind::Union, 4, 4},
                                           FormsCase{NodeKind::Intersection, 3, 2}, FormsCase{NodeKind::Difference, 8, 7},
                                           FormsCase{NodeKind::Union, 8, 7}),
                         [](const ::testing::TestParamInfo<FormsCase>& info) {
                             return std::string(scene::kindName(info.param.kind)) + std::to_string(info.param.count) +
                                    (info.param.shells > 0 ? "Shells" + std::to_string(info.param.shells) : "");
                         });

// Screen hulls (RenderSettings::screenHulls): a block's tree leaves out the
// operands whose hull does not reach it, where their rectangles would have
// kept them. Slabs drilled by thin bars lying aslant: the frames with hulls
// and with rectangles alone must be the same to the bit, and the hulls
// must have left operands out (fewer blocks in the forms for many operands).
TEST(EvaluatorFormsHulls, ThinBarsAslantGiveTheFrameOfTheirRectangles) {
    gpu::Context context;
    render::Renderer renderer;
    for (const unsigned seed : {77u, 78u}) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> pos(-1.2, 1.2), angle(0.0, 360.0);
        scene::Tree tree;
        scene::Leaf slab;
        slab.primitive = scene::Cube{{3.0, 3.0, 0.6}, true};
        std::vector<int> parts{tree.addLeaf(slab)};
        for (int i = 0; i < 24; ++i) {
            scene::Leaf bar;
            bar.primitive = scene::Cube{{0.12, 0.12, 4.0}, true};
            // Lying nearly flat (turned 80 degrees about x), at any heading.
            bar.transform = glm::translate(glm::dmat4(1.0), {pos(rng), pos(rng), 0.2 * pos(rng)}) *
                            glm::rotate(glm::dmat4(1.0), glm::radians(angle(rng)), {0.0, 0.0, 1.0}) *
                            glm::rotate(glm::dmat4(1.0), glm::radians(80.0), {1.0, 0.0, 0.0});
            parts.push_back(tree.addLeaf(bar));
        }
        tree.root = tree.addNode(NodeKind::Difference, parts);
        renderer.setScene(tree, model::buildModel(tree));
        for (int which = 0; which < 3; ++which) {
            camera::Camera camera = cameraFor(which, rng);
            camera.width = camera.height = 160;  // blocks enough for the hulls to leave some out
            render::RenderSettings settings;
            settings.groupOperands = false;
            settings.keepBlockForms = true;
            const render::Frame hulls = renderer.render(camera, settings);
            settings.screenHulls = false;
            const render::Frame rects = renderer.render(camera, settings);
            const std::string what = "seed " + std::to_string(seed) + ", camera " + std::to_string(which);
            expectSameFrame(hulls, rects, what);
            EXPECT_GT(hulls.stats.coveredPixels, 160u * 160u / 10u) << what;
            // Leaving operands out moves blocks to the forms for fewer of them.
            const std::size_t many = hulls.stats.productBlocks + hulls.stats.arrayBlocks;
            const std::size_t manyRects = rects.stats.productBlocks + rects.stats.arrayBlocks;
            if (which < 2) {
                EXPECT_LT(many, manyRects) << what;
            } else {
                EXPECT_LE(many, manyRects) << what;  // from inside, a bar may reach the near plane: no hull
            }
        }
    }
}

// Coincident faces: the forms must settle ties alike. A cube minus copies of
// itself leaves nothing; a union of cubes that share faces shows them once.
TEST(EvaluatorFormsTies, CoincidentFacesCancelAlike) {
    gpu::Context context;
    render::Renderer renderer;
    for (NodeKind kind : {NodeKind::Difference, NodeKind::Union, NodeKind::Intersection}) {
        scene::Tree tree;
        std::vector<int> children;
        for (int i = 0; i < 12; ++i) {
            scene::Leaf leaf;
            leaf.primitive = scene::Cube{{2.0, 2.0, 2.0}, true};
            // Unions: a row of cubes sharing faces; the others: one cube, repeated.
            if (kind == NodeKind::Union) leaf.transform = glm::translate(glm::dmat4(1.0), {2.0 * (i % 4) - 3.0, 0, 0});
            // A colour each, so that the repeated cubes stay operands of their
            // own (identical leaves would share one: IdenticalLeaves.h).
            leaf.color = glm::dvec4(i / 16.0, 0.5, 0.5, 1.0);
            children.push_back(tree.addLeaf(std::move(leaf)));
        }
        tree.root = tree.addNode(kind, children);
        const model::Model model = model::buildModel(tree);
        renderer.setScene(tree, model);
        camera::Camera camera;
        camera.width = camera.height = 64;
        camera.eye = {7.0, -9.0, 6.0};
        camera.center = {0.0, 0.0, 0.0};
        const auto [fast, general] = fastAndGeneral(renderer, camera);
        EXPECT_GT(fast.stats.productBlocks, 0u);
        if (kind == NodeKind::Difference) {
            EXPECT_EQ(fast.stats.coveredPixels, 0u) << "a cube minus itself is empty";
        } else {
            EXPECT_GT(fast.stats.coveredPixels, 500u);
        }
        // Coverage, depth and normal must match exactly; the leaf named at a
        // tie may differ (each form names the first operand it meets). So
        // for the intersection and the union as one group (ConvexGroups.h),
        // and the intersection's group names the lowest leaf: cube 0; and
        // for the union drawn plainly (PlainPass.h).
        render::RenderSettings unite;
        unite.unionGroupFrom = 2;
        unite.plainUnions = false;
        const render::Frame grouped = renderer.render(camera, unite);
        EXPECT_EQ(grouped.stats.operands, kind == NodeKind::Difference ? 12 : 1);
        const render::Frame plain = renderer.render(camera, {});
        EXPECT_EQ(plain.stats.plain, kind == NodeKind::Union);
        for (const render::Frame* other : {&general, &grouped, &plain}) {
            for (std::size_t p = 0; p < fast.leaf.size(); ++p) {
                ASSERT_EQ(fast.leaf[p] >= 0, other->leaf[p] >= 0) << scene::kindName(kind) << " pixel " << p;
                ASSERT_EQ(std::memcmp(&fast.depth[p], &other->depth[p], sizeof(float)), 0) << scene::kindName(kind);
                ASSERT_EQ(std::memcmp(&fast.normal[p], &other->normal[p], sizeof(glm::vec3)), 0)
                    << scene::kindName(kind);
            }
        }
        if (kind == NodeKind::Intersection) {
            for (int leaf : grouped.leaf) ASSERT_TRUE(leaf == -1 || leaf == 0) << leaf;
        }
    }
}

// A flat solid: its top and bottom faces lie at one depth on every ray down,
// an entry and an exit of one operand at one depth. The back face wins (it
// comes last in the array form's tagged order), so the flat solid encloses
// nothing and shows nowhere, in every form.
TEST(EvaluatorFormsTies, AFlatSolidShowsNowhere) {
    gpu::Context context;
    render::Renderer renderer;
    scene::Tree tree;
    scene::Leaf cube;
    cube.primitive = scene::Cube{{2.0, 2.0, 2.0}, true};
    const int block = tree.addLeaf(std::move(cube));
    scene::Polyhedron flat;
    flat.points = {{-2, -2, 1.5}, {2, -2, 1.5}, {2, 2, 1.5}, {-2, 2, 1.5}};
    flat.faces = {{0, 3, 2}, {0, 2, 1}, {1, 2, 3}, {1, 3, 0}};  // top, bottom: clockwise from outside
    scene::Leaf sheet;
    sheet.primitive = flat;
    const int sheetLeaf = tree.addLeaf(std::move(sheet));
    tree.root = tree.addNode(NodeKind::Union, {block, sheetLeaf});
    renderer.setScene(tree, model::buildModel(tree));
    camera::Camera camera;  // straight down, orthographic: both faces at exactly one depth
    camera.width = camera.height = 64;
    camera.projection = camera::Projection::Orthographic;
    camera.eye = {0.0, 0.0, 10.0};
    camera.center = {0.0, 0.0, 0.0};
    const auto [fast, general] = fastAndGeneral(renderer, camera);
    EXPECT_GT(fast.stats.registerBlocks, 0u);
    expectSameFrame(fast, general, "a cube and a flat solid");
    std::size_t cubePixels = 0;
    for (int leaf : fast.leaf) {
        EXPECT_NE(leaf, sheetLeaf);
        cubePixels += leaf == block ? 1 : 0;
    }
    EXPECT_GT(cubePixels, 500u);

    // The sheet alone: a tree of one operand of one layer, the first-surface
    // form's case, which must see the entry and the exit together too.
    scene::Tree alone;
    scene::Leaf onlySheet;
    onlySheet.primitive = flat;
    alone.root = alone.addLeaf(std::move(onlySheet));
    renderer.setScene(alone, model::buildModel(alone));
    const auto [fastAlone, generalAlone] = fastAndGeneral(renderer, camera);
    EXPECT_GT(fastAlone.stats.firstSurfaceBlocks, 0u);
    EXPECT_EQ(fastAlone.stats.layersPerLeaf.at(0), 1);
    EXPECT_EQ(fastAlone.stats.coveredPixels, 0u) << "a flat solid alone shows nowhere";
    expectSameFrame(fastAlone, generalAlone, "a flat solid alone");
}

// The form map (RenderSettings::keepBlockForms): a cube minus a row of holes
// and a cluster of ten small ones. Where the cube alone meets a block it is
// the first-surface form; a hole's wall is drawn by the register form, or by
// the product form inside the cluster (more than eight operands). The map
// must agree with the block counts, and the array form alone must draw the
// same blocks.
TEST(EvaluatorFormsMap, EachPixelKnowsItsBlocksForm) {
    gpu::Context context;
    render::Renderer renderer;
    scene::Tree tree;
    std::vector<int> children;
    scene::Leaf cube;
    cube.primitive = scene::Cube{{4.0, 4.0, 2.0}, true};
    children.push_back(tree.addLeaf(std::move(cube)));
    auto addSphere = [&](glm::dvec3 centre, double r) {
        scene::Leaf leaf;
        scene::Sphere s;
        s.r = r;
        s.fragments.fn = 12;
        leaf.primitive = s;
        leaf.transform = glm::translate(glm::dmat4(1.0), centre);
        children.push_back(tree.addLeaf(std::move(leaf)));
    };
    for (double x : {-1.2, 0.0}) addSphere({x, -1.0, 1.0}, 0.4);
    for (int i = 0; i < 10; ++i) addSphere({0.9 + 0.08 * (i % 5), 0.9 + 0.1 * (i / 5), 1.0}, 0.25);
    tree.root = tree.addNode(NodeKind::Difference, children);
    renderer.setScene(tree, model::buildModel(tree));
    camera::Camera camera;
    camera.width = camera.height = 96;
    camera.projection = camera::Projection::Orthographic;
    camera.eye = {0.0, 0.0, 10.0};
    camera.center = {0.0, 0.0, 0.0};
    camera.fovDegrees = 30.0;
    render::RenderSettings settings;
    settings.keepBlockForms = true;
    const render::Frame fast = renderer.render(camera, settings);
    settings.generalEvaluator = true;
    const render::Frame general = renderer.render(camera, settings);
    const std::size_t n = static_cast<std::size_t>(camera.width * camera.height);
    ASSERT_EQ(fast.blockForms.size(), n);
    ASSERT_EQ(general.blockForms.size(), n);

    std::size_t cubeAlone = 0, walls = 0;
    for (std::size_t p = 0; p < n; ++p) {
        const render::BlockForm f = fast.blockForms[p];
        EXPECT_EQ(f == render::BlockForm::None, general.blockForms[p] == render::BlockForm::None) << p;
        if (general.blockForms[p] != render::BlockForm::None) {
            EXPECT_EQ(general.blockForms[p], render::BlockForm::Array);
        }
        if (fast.leaf[p] >= 0) {
            EXPECT_NE(f, render::BlockForm::None) << "a surface outside any drawn block";
        }
        if (f == render::BlockForm::FirstSurface && fast.leaf[p] >= 0) {
            EXPECT_EQ(fast.leaf[p], 0) << "only the cube is alone in a block";
            ++cubeAlone;
        }
        if (fast.leaf[p] > 0) {
            EXPECT_TRUE(f == render::BlockForm::Register || f == render::BlockForm::Product) << p;
            ++walls;
        }
    }
    EXPECT_GT(cubeAlone, n / 4);
    EXPECT_GT(walls, 50u);

    // One pixel per block (its lower-left one, GL rows counting up) gives the counts.
    std::size_t counts[5] = {};
    for (int by = 0; by * 16 < camera.height; ++by) {
        for (int bx = 0; bx * 16 < camera.width; ++bx) {
            const std::size_t row = static_cast<std::size_t>(camera.height - 1 - by * 16);
            ++counts[static_cast<int>(fast.blockForms[row * static_cast<std::size_t>(camera.width) +
                                                      static_cast<std::size_t>(bx * 16)])];
        }
    }
    EXPECT_EQ(counts[static_cast<int>(render::BlockForm::FirstSurface)], fast.stats.firstSurfaceBlocks);
    EXPECT_EQ(counts[static_cast<int>(render::BlockForm::Register)], fast.stats.registerBlocks);
    EXPECT_EQ(counts[static_cast<int>(render::BlockForm::Product)], fast.stats.productBlocks);
    EXPECT_EQ(counts[static_cast<int>(render::BlockForm::Array)], fast.stats.arrayBlocks);
    EXPECT_GT(fast.stats.productBlocks, 0u) << "the cluster's blocks hold more than eight operands";
    EXPECT_GT(fast.stats.registerBlocks, 0u);
}
