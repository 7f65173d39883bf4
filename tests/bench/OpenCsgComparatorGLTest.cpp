// strata-bench's OpenCSG comparator draws what strata draws: cheese (a cube
// minus 8 spheres), 2 intersected spheres and two trees of several products
// at 128 x 96, every OpenCSG
// setting's coverage against strata's Renderer::render() away from
// silhouettes. It caught a vertex buffer left bound across OpenCSG's own
// drawing (OpenCsgComparator.cpp). The comparator's own context is GLX with
// an X display (CI: xvfb-run), else EGL; one test asks for EGL always.
// Skipped where strata-bench was built without OpenCSG.
#include <gtest/gtest.h>

#include "OpenCsgRun.h"
#include "Scenes.h"
#include "strata/camera/ViewBounds.h"
#include "strata/core/Error.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace strata;

namespace {

int addCube(scene::Tree& tree, glm::dvec3 center, double size) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{glm::dvec3(size), true};
    leaf.transform = glm::translate(glm::dmat4(1.0), center);
    return tree.addLeaf(std::move(leaf));
}

int addSphere(scene::Tree& tree, glm::dvec3 center, double r) {
    scene::Leaf leaf;
    scene::Sphere sphere;
    sphere.r = r;
    sphere.fragments.fn = 32;
    leaf.primitive = sphere;
    leaf.transform = glm::translate(glm::dmat4(1.0), center);
    return tree.addLeaf(std::move(leaf));
}

// cheese (what the brief asks) and intersection (where a wrong comparator
// shows most), every setting against strata.
void expectCoversWhatStrataCovers(bench::OpenCsgComparator& comparator, gpu::Context& context) {
    for (const auto& [name, k] : {std::pair<const char*, int>{"cheese", 8}, {"intersection", 2}}) {
        SCOPED_TRACE(name);
        camera::Camera base;
        base.width = 128;
        base.height = 96;
        const bench::BenchScene scene = bench::makeScene(name, k, 1, base);
        const model::Model model = model::buildModel(scene.tree);
        const camera::Camera camera = camera::defaultCamera(camera::viewBounds(scene.tree, model), base);
        render::Renderer renderer;
        renderer.setScene(scene.tree, model);
        const render::Frame frame = renderer.render(camera, {});
        std::vector<std::uint8_t> strataCoverage(frame.leaf.size());
        for (std::size_t i = 0; i < frame.leaf.size(); ++i) strataCoverage[i] = frame.leaf[i] >= 0;

        bench::OpenCsgCaps caps;
        const bench::OpenCsgResult result = bench::runOpenCsg(comparator, context, scene.tree, model, camera,
                                                              strataCoverage, {.frames = 1, .warmup = 0}, name, k, caps);
        ASSERT_TRUE(result.unavailable.empty()) << result.unavailable;
        ASSERT_EQ(result.settings.size(), bench::openCsgSettings().size());
        ASSERT_GE(result.best, 0);
        for (const bench::OpenCsgSettingResult& s : result.settings) {
            ASSERT_TRUE(s.skipped.empty()) << s.name << ": " << s.skipped;
            EXPECT_GT(s.agreement.coveredA, 1000u) << "strata drew (almost) nothing";
            EXPECT_GT(s.agreement.coveredB, 1000u) << s.name << " drew (almost) nothing";
            EXPECT_GE(s.agreement.interiorFraction(), 0.99) << s.name;
            // Stricter: among the covered pixels only (a wrong blob of 1 % of the
            // result passes the line above at this size; it fails this one).
            EXPECT_GE(s.agreement.coveredFraction(), 0.99) << s.name;
        }
    }
}

}  // namespace

TEST(OpenCsgComparator, CoversWhatStrataCovers) {
    gpu::Context context;
    std::unique_ptr<bench::OpenCsgComparator> comparator;
    try {
        comparator = bench::openOpenCsgComparator();
    } catch (const Error& e) {  // not built (no libopencsg-dev), or no context at all
        context.makeCurrent();
        GTEST_SKIP() << "OpenCSG comparator unavailable: " << e.what();
    }
    context.makeCurrent();
    expectCoversWhatStrataCovers(*comparator, context);
}

// The EGL compatibility context, which the comparator falls back to without
// an X display, asked for here also where there is one (CI's Xvfb): GLEW,
// built for GLX, has to load GL's entry points there too, and OpenCSG has to
// draw the same.
TEST(OpenCsgComparator, EglContextCoversWhatStrataCovers) {
    if (std::string(bench::openCsgVersion()) == "no OpenCSG") GTEST_SKIP() << "built without OpenCSG";
    gpu::Context context;
    std::unique_ptr<bench::OpenCsgComparator> comparator = bench::openOpenCsgComparator(bench::CompatContext::Egl);
    context.makeCurrent();
    EXPECT_EQ(comparator->context().rfind("EGL ", 0), 0u) << comparator->context();
    expectCoversWhatStrataCovers(*comparator, context);
}

// Trees that are no single product: OpenSCAD's normalization makes several,
// and the comparator draws them all into one depth buffer. A comparator that
// drew one product, or lost the depth between products, leaves out a cube
// or a cut, which the covered-pixel agreement catches.
TEST(OpenCsgComparator, SumOfProductsCoversWhatStrataCovers) {
    gpu::Context context;
    std::unique_ptr<bench::OpenCsgComparator> comparator;
    try {
        comparator = bench::openOpenCsgComparator();
    } catch (const Error& e) {
        context.makeCurrent();
        GTEST_SKIP() << "OpenCSG comparator unavailable: " << e.what();
    }
    context.makeCurrent();

    struct Case {
        const char* name;
        scene::Tree tree;
        std::size_t products;
    };
    std::vector<Case> cases;
    {
        // (A + B) - C - (D + E): two cubes apart, a sphere cutting each and
        // one cutting both: products A - C - D - E and B - C - D - E.
        scene::Tree t;
        const int a = addCube(t, {-4, 0, 0}, 5), b = addCube(t, {4, 0, 0}, 5);
        const int c = addSphere(t, {-4, 0, 2.5}, 2), d = addSphere(t, {0, 0, 0}, 3), e = addSphere(t, {4, -2.5, 0}, 2);
        t.root = t.addNode(scene::NodeKind::Difference,
                           {t.addNode(scene::NodeKind::Union, {a, b}), c, t.addNode(scene::NodeKind::Union, {d, e})});
        cases.push_back({"union minus spheres", std::move(t), 2});
    }
    {
        // (A + B) * (C + D): four lenses, one product each, overlapping on screen.
        scene::Tree t;
        const int a = addSphere(t, {-2, 0, 0}, 3), b = addSphere(t, {2, 0, 0}, 3);
        const int c = addCube(t, {0, -2, 0}, 4), d = addCube(t, {0, 2, 1}, 4);
        t.root = t.addNode(scene::NodeKind::Intersection,
                           {t.addNode(scene::NodeKind::Union, {a, b}), t.addNode(scene::NodeKind::Union, {c, d})});
        cases.push_back({"union times union", std::move(t), 4});
    }
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        camera::Camera base;
        base.width = 128;
        base.height = 96;
        const model::Model model = model::buildModel(c.tree);
        const camera::Camera camera = camera::defaultCamera(camera::viewBounds(c.tree, model), base);
        render::Renderer renderer;
        renderer.setScene(c.tree, model);
        const render::Frame frame = renderer.render(camera, {});
        std::vector<std::uint8_t> strataCoverage(frame.leaf.size());
        for (std::size_t i = 0; i < frame.leaf.size(); ++i) strataCoverage[i] = frame.leaf[i] >= 0;

        bench::OpenCsgCaps caps;
        const bench::OpenCsgResult result = bench::runOpenCsg(*comparator, context, c.tree, model, camera,
                                                              strataCoverage, {.frames = 1, .warmup = 0}, c.name, 1, caps);
        ASSERT_TRUE(result.unavailable.empty()) << result.unavailable;
        EXPECT_EQ(result.products, c.products);
        for (const bench::OpenCsgSettingResult& s : result.settings) {
            ASSERT_TRUE(s.skipped.empty()) << s.name << ": " << s.skipped;
            EXPECT_GT(s.agreement.coveredA, 1000u) << "strata drew (almost) nothing";
            EXPECT_GE(s.agreement.interiorFraction(), 0.99) << s.name;
            EXPECT_GE(s.agreement.coveredFraction(), 0.99) << s.name;
        }
    }
}

// Past the element limit the comparator draws nothing and says why, as
// OpenSCAD gives up; it neither crashes nor hangs.
TEST(OpenCsgComparator, GivesUpPastTheElementLimit) {
    gpu::Context context;
    std::unique_ptr<bench::OpenCsgComparator> comparator;
    try {
        comparator = bench::openOpenCsgComparator();
    } catch (const Error& e) {
        context.makeCurrent();
        GTEST_SKIP() << "OpenCSG comparator unavailable: " << e.what();
    }
    context.makeCurrent();
    camera::Camera base;
    base.width = 64;
    base.height = 48;
    const bench::BenchScene scene = bench::makeScene("blowup", 18, 1, base);
    const model::Model model = model::buildModel(scene.tree);
    const camera::Camera camera = camera::defaultCamera(camera::viewBounds(scene.tree, model), base);
    const std::vector<std::uint8_t> none(std::size_t(base.width) * std::size_t(base.height), 0);
    bench::OpenCsgCaps caps;
    const bench::OpenCsgResult result =
        bench::runOpenCsg(*comparator, context, scene.tree, model, camera, none, {}, "blowup", 18, caps);
    EXPECT_TRUE(result.gaveUp);
    EXPECT_EQ(result.elements, bench::kOpenScadNormalizeLimit + 1);
    EXPECT_NE(result.unavailable.find("gave up"), std::string::npos) << result.unavailable;
    EXPECT_TRUE(result.settings.empty());
}
