// Evaluated frames lit as drawn (RenderSettings::outline off; NormalPass.h):
// where no normal is read back, the normal pass lights each visible surface
// into the image and no shade pass runs. The image must be the one the
// shade pass gives from the stored normals and base colours, to the byte:
// the same surfaces, leaves and depths, in both lights and projections,
// with and without leaf marks, with cut faces, translucent colours and
// modifiers, on seeded trees and on real models. The shaded frame is itself
// checked against the CPU reference elsewhere (the accuracy suite).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "SphereShells.h"
#include "strata/camera/Camera.h"
#include "strata/camera/ViewBounds.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Framebuffer.h"
#include "strata/gpu/Texture.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using scene::NodeKind;

namespace {

constexpr int kSize = 89;

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
    s.fragments.fn = 18;
    leaf.primitive = s;
    leaf.transform = glm::translate(glm::dmat4(1.0), centre);
    return leaf;
}

// A block with seeded holes: spheres and sphere shells (non-convex) taken
// away, some coloured (their cut faces take the colour), a sphere kept by
// an intersection, a translucent coloured part, a '%' leaf and a '#' one.
scene::Tree drilledBlock(unsigned seed) {
    scene::Tree tree;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> at(-1.2, 1.2), size(0.2, 0.55), hue(0.2, 1.0);
    std::vector<int> holes;
    for (int i = 0; i < 9; ++i) {
        const glm::dvec3 c(at(rng), at(rng), at(rng));
        scene::Leaf hole = i % 3 == 2 ? scene::Leaf{} : sphereLeaf(c, size(rng));
        if (i % 3 == 2) hole.primitive = test::sphereShells({c, c + glm::dvec3(0.0, 0.0, 0.45)}, 0.3, 14);
        if (i % 2 == 0) hole.color = glm::dvec4(hue(rng), hue(rng), hue(rng), 1.0);
        if (i == 4) hole.display = scene::Display::Highlight;
        holes.push_back(tree.addLeaf(hole));
    }
    scene::Leaf block = cubeLeaf({-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0});
    block.color = glm::dvec4(0.8, 0.7, 0.3, 1.0);
    const int body = tree.addNode(NodeKind::Intersection,
                                  {tree.addLeaf(block), tree.addLeaf(sphereLeaf({0.0, 0.0, 0.0}, 1.45))});
    std::vector<int> parts{body};
    parts.insert(parts.end(), holes.begin(), holes.end());
    const int drilled = tree.addNode(NodeKind::Difference, parts);
    scene::Leaf glass = cubeLeaf({1.1, -0.5, -0.5}, {1.9, 0.5, 0.5});
    glass.color = glm::dvec4(0.2, 0.6, 0.9, 0.5);
    tree.root = tree.addNode(NodeKind::Union, {drilled, tree.addLeaf(glass)});
    tree.background.push_back(tree.addLeaf(sphereLeaf({-1.6, 1.4, 0.4}, 0.4)));
    return tree;
}

camera::Camera cameraAt(glm::dvec3 eye, camera::Projection projection) {
    camera::Camera camera;
    camera.eye = eye;
    camera.center = {0.0, 0.0, 0.0};
    camera.projection = projection;
    camera.width = kSize + 7;
    camera.height = kSize;
    return camera;
}

class LitFrameGLTest : public ::testing::Test {
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

    // The scene set last, without the outline in `look`'s light: the frame
    // lit as drawn (no normals read back), and a window's (renderInto),
    // show the image the shade pass gives, to the byte.
    static void expectLitEqualsShaded(const camera::Camera& camera, render::RenderSettings look,
                                      const std::string& what) {
        look.outline = false;
        render::RenderSettings shadedLook = look;
        shadedLook.readNormal = true;
        const render::Frame shaded = renderer_->render(camera, shadedLook);
        look.readNormal = false;
        const render::Frame lit = renderer_->render(camera, look);
        EXPECT_FALSE(shaded.stats.litAsDrawn) << what;
        EXPECT_TRUE(lit.stats.litAsDrawn) << what;
        EXPECT_FALSE(lit.stats.plain) << what;
        EXPECT_GT(lit.stats.coveredPixels, std::size_t(kSize * kSize) / 20) << what;
        EXPECT_EQ(lit.leaf, shaded.leaf) << what;
        ASSERT_EQ(lit.rgba.size(), shaded.rgba.size()) << what;
        std::size_t differ = 0;
        for (std::size_t i = 0; i < lit.rgba.size(); ++i) differ += lit.rgba[i] != shaded.rgba[i];
        EXPECT_EQ(differ, 0u) << what;

        gpu::Texture color = gpu::Texture::create2D("host", GL_RGBA8, camera.width, camera.height);
        gpu::Framebuffer host("host");
        host.attachTexture(GL_COLOR_ATTACHMENT0, color);
        host.setDrawBuffers({GL_COLOR_ATTACHMENT0});
        host.checkComplete();
        EXPECT_TRUE(renderer_->renderInto(host.id(), 0, 0, camera, look).litAsDrawn) << what;
        std::vector<std::uint8_t> pixels(shaded.rgba.size());
        color.download(GL_RGBA, GL_UNSIGNED_BYTE, std::as_writable_bytes(std::span(pixels)));
        const std::size_t row = static_cast<std::size_t>(camera.width) * 4;  // GL's rows count from the bottom
        differ = 0;
        for (int y = 0; y < camera.height; ++y) {
            differ += std::memcmp(&pixels[static_cast<std::size_t>(camera.height - 1 - y) * row],
                                  &shaded.rgba[static_cast<std::size_t>(y) * row], row) != 0;
        }
        EXPECT_EQ(differ, 0u) << what << ": rows of the window's image";
    }

    static std::unique_ptr<gpu::Context> context_;
    static std::unique_ptr<render::Renderer> renderer_;
};

std::unique_ptr<gpu::Context> LitFrameGLTest::context_;
std::unique_ptr<render::Renderer> LitFrameGLTest::renderer_;

const camera::Projection kProjections[] = {camera::Projection::Perspective, camera::Projection::Orthographic};
const render::Lighting kLights[] = {render::Lighting::Strata, render::Lighting::OpenScad};

}  // namespace

TEST_F(LitFrameGLTest, DrilledBlocksInEitherLightEqualTheShadedImage) {
    for (unsigned seed : {3u, 4u}) {
        setScene(drilledBlock(seed));
        for (const render::Lighting lighting : kLights) {
            for (const camera::Projection projection : kProjections) {
                for (const bool marks : {true, false}) {
                    render::RenderSettings look;
                    look.lighting = lighting;
                    look.leafMarks = marks;
                    expectLitEqualsShaded(cameraAt({3.0, -4.5, 3.5}, projection), look,
                                          "seed " + std::to_string(seed) + ", " + std::string(render::lightingName(lighting)) +
                                              ", projection " + std::to_string(static_cast<int>(projection)) +
                                              (marks ? ", leaf marks" : ""));
                }
            }
        }
    }
}

TEST_F(LitFrameGLTest, RealModelsEqualTheShadedImage) {
    // OpenSCAD's examples with differences, intersections, text,
    // a '#' leaf (Basics_logo's) and multi-layer operands, from
    // OpenSCAD's default view of each.
    for (const char* name : {"Old_example004", "Basics_text_on_cube", "Basics_logo", "Old_example008"}) {
        const scene::Tree tree = scene::parseCsgFile(std::string(STRATA_TEST_DIR) + "/bench/models/" + name + ".csg");
        model::Model model = model::buildModel(tree);
        const mesh::Bounds bounds = camera::viewBounds(tree, model);
        renderer_->setScene(tree, std::move(model));
        camera::Camera base;
        base.width = 2 * kSize;
        base.height = kSize + 31;
        const camera::Camera camera = camera::defaultCamera(bounds, base);
        for (const render::Lighting lighting : kLights) {
            render::RenderSettings look;
            look.lighting = lighting;
            expectLitEqualsShaded(camera, look, std::string(name) + ", " + std::string(render::lightingName(lighting)));
        }
    }
}
