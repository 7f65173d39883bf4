// The export room's entry (strata/export/Export.h) as a host calls it, with
// no application code: each kind of file it writes read back and compared
// with the closed form of the model, and each refusal writing nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "../mesh/MeshTestUtil.h"
#include "strata/core/Error.h"
#include "strata/export/Export.h"
#include "strata/flat/FlatImport.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/mesh/MeshImport.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;

namespace {

scene::Tree parse(const std::string& text) {
    std::istringstream in(text);
    return scene::parseCsg(in, "model.csg", ".");
}

// A 10 mm cube less a 4 mm cube that reaches 3 mm into one of its corners.
const char* const kNotchedCube =
    "difference() {\n"
    "cube(size = [10, 10, 10], center = false);\n"
    "multmatrix([[1, 0, 0, 7], [0, 1, 0, 7], [0, 0, 1, 7], [0, 0, 0, 1]]) cube(size = [4, 4, 4], center = false);\n"
    "}\n";
constexpr double kNotchedVolume = 1000.0 - 27.0;

// A 6 by 4 rectangle less a 2 by 2 square inside it: 24 - 4 mm².
const char* const kHoledRectangle =
    "difference() {\n"
    "square(size = [6, 4], center = false);\n"
    "multmatrix([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]]) square(size = [2, 2], center = false);\n"
    "}\n";

class ExportEntry : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::path(::testing::TempDir()) /
               ("strata-export-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // Stages and commits `tree`'s export as `name`; the mesh read back.
    mesh::Mesh exported(const std::string& text, const std::string& name, const exporting::ExportSettings& settings,
                            std::size_t* triangles = nullptr) {
        const scene::Tree tree = parse(text);
        const model::Model model = model::buildModel(tree);
        exporting::StagedExport staged = exporting::stageExport(tree, model, path(name), settings);
        staged.file.commit();
        if (triangles != nullptr) *triangles = staged.triangles;
        return mesh::importMesh(path(name));
    }

    // The exact export of `text` and its sampled one at `resolution` cells
    // by the CPU reference, read back, with their triangle counts.
    struct BothMeshes {
        mesh::Mesh exact, sampled;
        std::size_t exactTriangles = 0, sampledTriangles = 0;
    };
    BothMeshes exactAndSampled(const std::string& text, int resolution) {
        BothMeshes both;
        both.exact = exported(text, "exact.off", exporting::ExportSettings{}, &both.exactTriangles);
        exporting::ExportSettings settings;
        settings.sampled = true;
        settings.reference = true;
        settings.resolution = resolution;
        both.sampled = exported(text, "sampled.off", settings, &both.sampledTriangles);
        EXPECT_TRUE(mesh::checkMesh(both.sampled).ok()) << mesh::checkMesh(both.sampled).describe();
        return both;
    }

private:
    std::filesystem::path dir_;
};

// The area of one outline with holes inside it, however the file orients
// them (a DXF's loops come back as drawn): the largest loop less the others.
double areaOfOneHoledOutline(const flat::Outlines& outlines) {
    std::vector<double> areas;
    for (const flat::Outline& o : outlines.outlines) {
        double twice = 0.0;
        for (std::size_t i = 0; i < o.points.size(); ++i) {
            const glm::dvec2& a = o.points[i];
            const glm::dvec2& b = o.points[(i + 1) % o.points.size()];
            twice += a.x * b.y - b.x * a.y;
        }
        areas.push_back(std::abs(0.5 * twice));
    }
    std::sort(areas.begin(), areas.end());
    double area = areas.empty() ? 0.0 : areas.back();
    for (std::size_t i = 0; i + 1 < areas.size(); ++i) area -= areas[i];
    return area;
}

}  // namespace

TEST_F(ExportEntry, TheExactMeshIsTheClosedSolidOfTheTree) {
    std::size_t triangles = 0;
    const mesh::Mesh mesh = exported(kNotchedCube, "notched.off", exporting::ExportSettings{}, &triangles);
    EXPECT_EQ(mesh.triangles.size(), triangles);
    EXPECT_TRUE(mesh::checkMesh(mesh).ok()) << mesh::checkMesh(mesh).describe();
    EXPECT_NEAR(mesh::test::signedVolume(mesh), kNotchedVolume, 1e-9);
}

TEST_F(ExportEntry, TheSampledMeshIsClosedAndWithinACellOfTheSolid) {
    exporting::ExportSettings settings;
    settings.sampled = true;
    settings.reference = true;  // the CPU reference: no GL context
    settings.resolution = 20;
    const mesh::Mesh mesh = exported(kNotchedCube, "notched.stl", settings);
    EXPECT_TRUE(mesh::checkMesh(mesh).ok()) << mesh::checkMesh(mesh).describe();
    // Flat faces on the grid's offset planes come back on their planes: the
    // volume is the solid's to well within a cell's layer over its surface.
    EXPECT_NEAR(mesh::test::signedVolume(mesh), kNotchedVolume, 1.0);
}

// A block with a notch and a bore through it, as a CAD part is: flat faces
// and a faceted cylinder. Sampled, its flat faces and the bore's facets
// are rebuilt on their planes, and the mesh has at most three times the
// exact mesh's triangles (a plain contour at 256 cells has about 200 000).
TEST_F(ExportEntry, TheSampledMeshOfACadPartIsAboutAsSmallAsTheExactOne) {
    const char* const part =
        "difference() {\n"
        "cube(size = [20, 14, 10], center = false);\n"
        "multmatrix([[1, 0, 0, 15], [0, 1, 0, -1], [0, 0, 1, 6], [0, 0, 0, 1]]) cube(size = [6, 16, 5], center = false);\n"
        "multmatrix([[1, 0, 0, 7], [0, 1, 0, 7], [0, 0, 1, -1], [0, 0, 0, 1]]) "
        "cylinder($fn = 24, h = 12, r1 = 4, r2 = 4, center = false);\n"
        "}\n";
    const BothMeshes both = exactAndSampled(part, 256);
    EXPECT_LE(both.sampledTriangles, 3 * both.exactTriangles);
    // Every vertex on the leaves' planes: the exact volume, to well within
    // one cell's.
    const double cell = 20.0 / 256.0;
    const double volume = mesh::test::signedVolume(both.exact);
    EXPECT_NEAR(mesh::test::signedVolume(both.sampled), volume, cell * cell * cell);
    std::printf("CAD part: %zu sampled triangles, %zu exact; volume %.6f against %.6f\n", both.sampledTriangles,
                both.exactTriangles, mesh::test::signedVolume(both.sampled), volume);
}

// Three blocks of a union that touch, turned: their shared faces are a
// rounding apart once transformed. The reference sampler takes them as one
// place, as the GPU does, so no gap thinner than a cell is found between
// them and the export is the one block they make.
TEST_F(ExportEntry, TouchingOperandsOfAUnionLeaveNoGapInTheSampledMesh) {
    const char* const blocks =
        "multmatrix([[0.838671, -0.544639, 0, 0], [0.544639, 0.838671, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "multmatrix([[1, 0, 0, 0], [0, 0.956305, -0.292372, 0], [0, 0.292372, 0.956305, 0], [0, 0, 0, 1]])\n"
        "union() {\n"
        "cube(size = [10, 7, 5], center = false);\n"
        "multmatrix([[1, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(size = [6.3, 7, 5], center = false);\n"
        "multmatrix([[1, 0, 0, 0], [0, 1, 0, 7], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(size = [16.3, 3.1, 5], center = false);\n"
        "}\n";
    const BothMeshes both = exactAndSampled(blocks, 64);
    // One block: its 12 triangles (the exact result keeps 16, its faces a
    // rounding out of one plane after the six-digit turn).
    EXPECT_LE(both.sampledTriangles, both.exactTriangles);
    const double volume = mesh::test::signedVolume(both.exact);
    EXPECT_NEAR(mesh::test::signedVolume(both.sampled), volume, 1e-6 * volume);
}

TEST_F(ExportEntry, ADrawingOfAFlatModelReadsBackToItsArea) {
    for (const char* name : {"holed.svg", "holed.dxf"}) {
        const scene::Tree tree = parse(kHoledRectangle);
        const model::Model model = model::buildModel(tree);
        exporting::stageExport(tree, model, path(name), exporting::ExportSettings{}).file.commit();
        scene::FlatImport import;
        import.path = path(name);
        const flat::Outlines read = flat::importFlat(import);
        EXPECT_EQ(read.outlines.size(), 2u) << name;
        EXPECT_NEAR(areaOfOneHoledOutline(read), 24.0 - 4.0, 1e-6) << name;
    }
}

TEST_F(ExportEntry, AFormatOfTheOtherDimensionIsRefusedAndNothingIsWritten) {
    const std::pair<const char*, const char*> cases[] = {
        {kNotchedCube, "notched.svg"},
        {kHoledRectangle, "holed.stl"},
    };
    for (const auto& [text, name] : cases) {
        const scene::Tree tree = parse(text);
        const model::Model model = model::buildModel(tree);
        try {
            exporting::stageExport(tree, model, path(name), exporting::ExportSettings{});
            ADD_FAILURE() << name << " was staged";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind("model.csg: a ", 0), 0u) << e.what();
        }
        EXPECT_FALSE(std::filesystem::exists(path(name))) << name;
    }
}
