// The CPU reference on models whose faces coincide (tests/data/coincident:
// flush pockets, shared faces, identical solids) against OpenSCAD's exact
// result of the same model: the CGAL evaluation that OpenSCAD 2021.01 exported
// as NAME.off, loaded as one plain mesh, as strata-render loads a mesh file.
//
// Both are ray cast by the reference (reference::renderReference) with the
// same cameras: OpenSCAD's default view of the model, two perspective views
// from odd angles (one from below) and an orthographic one, 160x120. The
// exact mesh has no coincident faces, so its image is the right answer; the
// model's must agree with it on coverage, depth and normal (tests/accuracy/
// Compare.h: depth within 1e-4 of the model's bounding-box diagonal, normals
// within 1 degree) in at least kMinAgreement of the pixels off the EXACT
// image's edges (Compare.h takes the edges from the reference image alone,
// here the exact mesh's, so a speckled skin in the model's image cannot hide
// as edges of its own), and pass Compare.h's bounds. Leaf ids are not
// compared: the exact mesh is one leaf. A model whose exact result is empty
// (NAME.empty instead of NAME.off) must render no pixel.
//
// Each comparison prints a line with its figures; a failing one writes
// <build>/coincident-failures/<model>-<view>-{strata,reference,diff,strip}.png
// (strata: the model's reference image, reference: the exact mesh's).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "Compare.h"
#include "DiffImages.h"
#include "OrbitCamera.h"
#include "strata/camera/Camera.h"
#include "strata/model/Model.h"
#include "strata/reference/RayCaster.h"
#include "strata/scene/CsgParser.h"
#include "strata/scene/Tree.h"

using namespace strata;

namespace {

const std::string kDir = STRATA_TEST_DIR "/data/coincident";
const std::string kFailures = STRATA_BINARY_DIR "/coincident-failures";
constexpr double kMinAgreement = 0.9999;

// The models, by name: every NAME.csg beside a NAME.off or NAME.empty.
std::vector<std::string> models() {
    std::vector<std::string> names;
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(kDir, ignored)) {
        if (entry.path().extension() != ".csg") continue;
        const std::filesystem::path stem = entry.path().parent_path() / entry.path().stem();
        if (std::filesystem::exists(stem.string() + ".off") || std::filesystem::exists(stem.string() + ".empty"))
            names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

struct View {
    std::string name;
    camera::Camera camera;
};

// OpenSCAD's default view of `bounds`, and three more at the same distance:
// azimuth and elevation in degrees (azimuth from +x toward +y), off round
// numbers so no pixel's ray runs along a face of the axis-aligned models.
std::vector<View> views(const mesh::Bounds& bounds) {
    camera::Camera base;
    base.width = 160;
    base.height = 120;
    const camera::Camera standard = camera::defaultCamera(bounds, base);
    auto orbit = [&](double azimuth, double elevation, camera::Projection projection) {
        return accuracy::orbit(standard, azimuth, elevation, projection);
    };
    return {{"default", standard},
            {"p_odd", orbit(23.7, 31.3, camera::Projection::Perspective)},
            {"p_below", orbit(-127.9, -23.6, camera::Projection::Perspective)},
            {"o_odd", orbit(61.3, 48.2, camera::Projection::Orthographic)}};
}

struct Loaded {
    scene::Tree tree;
    model::Model model;
};

Loaded load(scene::Tree tree) {
    Loaded l;
    l.tree = std::move(tree);
    l.model = model::buildModel(l.tree);
    return l;
}

// The image with every hit's leaf id 0: the exact mesh is one leaf, so which
// of the model's leaves shows is not compared (nor are leaf boundaries edges).
struct OneLeaf {
    std::vector<std::int32_t> leaf;
    accuracy::AovView view;
    explicit OneLeaf(const reference::ReferenceImage& image) {
        leaf.resize(image.leaf.size());
        for (std::size_t k = 0; k < leaf.size(); ++k) leaf[k] = image.leaf[k] >= 0 ? 0 : -1;
        view = {image.width, image.height, image.depth, image.normal, leaf, {}};
    }
};

std::size_t hits(const reference::ReferenceImage& image) {
    return static_cast<std::size_t>(std::count_if(image.leaf.begin(), image.leaf.end(), [](int l) { return l >= 0; }));
}

class CoincidentExactTest : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(CoincidentExactTest, ReferenceMatchesOpenScadsExactResult) {
    const std::string name = GetParam();
    const Loaded csg = load(scene::parseCsgFile(kDir + "/" + name + ".csg"));
    ASSERT_FALSE(csg.model.bounds.empty());
    const reference::ReferenceScene model(csg.tree, csg.model);
    const bool empty = std::filesystem::exists(kDir + "/" + name + ".empty");

    if (empty) {
        for (const View& v : views(csg.model.bounds)) {
            const reference::ReferenceImage image = model.render(v.camera);
            std::printf("[ coincident ] %-26s %-8s exact result empty: %zu pixels covered\n", name.c_str(),
                        v.name.c_str(), hits(image));
            EXPECT_EQ(hits(image), 0u) << name << " (" << v.name << "): OpenSCAD's exact result is empty";
        }
        return;
    }

    const Loaded off = load(scene::meshFileTree(kDir + "/" + name + ".off"));
    ASSERT_EQ(off.model.leafMeshes.size(), 1u);
    const reference::ReferenceScene exact(off.tree, off.model);
    accuracy::CompareOptions options = accuracy::optionsForScene(csg.model.bounds.diagonal());
    options.minAgreement = kMinAgreement;

    for (const View& v : views(csg.model.bounds)) {
        SCOPED_TRACE(v.name);
        const reference::ReferenceImage mine = model.render(v.camera);
        const reference::ReferenceImage theirs = exact.render(v.camera);
        const OneLeaf a(mine), b(theirs);
        // The exact mesh's image is the reference: its edges alone count.
        const accuracy::CompareResult r = accuracy::compare(v.camera, a.view, b.view, options);
        const std::size_t wrong = r.nonEdge.total(), inside = r.nonEdgePixels;
        std::printf("[ coincident ] %-26s %-8s agreement %8.4f%% (%zu of %5zu non-edge pixels disagree; "
                    "c/d/n %zu/%zu/%zu), edge %4zu (%zu disagree), covered %zu / exact %zu\n",
                    name.c_str(), v.name.c_str(), 100.0 * r.agreement(), wrong, inside, r.nonEdge.coverage,
                    r.nonEdge.depth, r.nonEdge.normal, r.edgePixels, r.edge.total(), r.coveredGpu, r.coveredReference);
        EXPECT_GT(r.coveredReference, 0u);
        if (!r.passed()) {
            const accuracy::ComparisonImages p =
                accuracy::writeComparisonImages(kFailures + "/" + name + "-" + v.name, v.camera, a.view, b.view, r);
            ADD_FAILURE() << kDir << "/" << name << ".csg against " << name << ".off, view " << v.name << ": "
                          << wrong << " of the exact image's " << inside << " non-edge pixels disagree; "
                          << r.summary() << "\nimages (strata = the model, reference = the exact mesh): " << p.strip;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Coincident, CoincidentExactTest, ::testing::ValuesIn(models()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(CoincidentExactData, HoldsTheModelsWithTheirExactResults) {
    const std::vector<std::string> names = models();
    EXPECT_GE(names.size(), 20u);
    int empty = 0;
    for (const std::string& n : names) empty += std::filesystem::exists(kDir + "/" + n + ".empty") ? 1 : 0;
    EXPECT_EQ(empty, 1);  // identical_difference
}
