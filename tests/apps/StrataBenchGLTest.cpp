// strata-bench on a user's own scene file (--files): the file is timed like
// the built-in scenes, its row named after it with K its number of leaves,
// and a file it cannot load stops the run before any frame, with the file
// named and no JSON left behind; OpenCSG gets every tree as a sum of
// products, or the note that OpenSCAD would give up on it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kExe = STRATA_BENCH_EXE;

std::string examplePath(const std::string& name) {
    return (std::filesystem::path(STRATA_TEST_DIR).parent_path() / "examples" / name).string();
}

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

TEST(StrataBenchGL, TimesASceneFileAlone) {
    TempDir dir;
    const std::string json = dir / "bench.json";
    // The logo: a cube and a sphere minus three cylinders (4 leaves).
    const ProcessResult r = runProcess({kExe, "--files", examplePath("openscad_logo.csg"), "--size", "64x48",
                                        "--frames", "1", "--warmup", "0", "--no-opencsg", "--json", json});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("openscad_logo.csg"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("cheese"), std::string::npos) << "no built-in scene without --scenes:\n" << r.out;
    const std::string data = readFile(json);
    EXPECT_NE(data.find(R"("scene": "openscad_logo.csg")"), std::string::npos) << data;
    EXPECT_NE(data.find(R"("k": 4)"), std::string::npos) << data;
    EXPECT_EQ(data.find(R"("covered_pixels": 0,)"), std::string::npos) << "the logo must cover pixels:\n" << data;
    EXPECT_EQ(data.find(R"("error")"), std::string::npos) << data;
}

TEST(StrataBenchGL, AFileItCannotLoadStopsTheRunFirst) {
    TempDir dir;
    const std::string bad = dir.write("broken.csg", "difference() {\n  cube(size = [1, 1, 1]);\n  sphere(r = );\n}\n");
    const std::string json = dir / "bench.json";
    const ProcessResult r = runProcess({kExe, "--files", bad, "--scenes", "cheese", "--k", "1", "--size", "32x32",
                                        "--frames", "1", "--no-opencsg", "--json", json});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("broken.csg:3:"), std::string::npos) << r.err;  // file and line
    EXPECT_EQ(r.out.find("cheese"), std::string::npos) << "no frame before the error:\n" << r.out;
    EXPECT_FALSE(std::filesystem::exists(json));
}

// OpenCSG on trees that are no single product: OpenSCAD's CSG example is a
// union of a union, an intersection and a difference of a cube and a sphere,
// by hand 4 products (cube; sphere; cube * sphere; cube - sphere) of 6
// primitives after 5 visited operations. The blowup scene at K = 12 goes past
// the 200,000-element limit: reported, with no OpenCSG figure, not drawn.
TEST(StrataBenchGL, OpenCsgTimesSumsOfProductsAndReportsTheLimit) {
    TempDir dir;
    const std::string json = dir / "bench.json";
    const ProcessResult r =
        runProcess({kExe, "--files", examplePath("openscad_CSG.csg"), "--scenes", "blowup", "--k", "12", "--size",
                    "64x48", "--frames", "1", "--warmup", "0", "--json", json});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string data = readFile(json);
    if (data.find(R"("opencsg_unavailable")") != std::string::npos) GTEST_SKIP() << "no OpenCSG comparator:\n" << r.out;
    const std::size_t file = data.find(R"("scene": "openscad_CSG.csg")");
    const std::size_t blowup = data.find(R"("scene": "blowup")");
    ASSERT_NE(file, std::string::npos) << data;
    ASSERT_NE(blowup, std::string::npos) << data;
    // Rows are written in run order: the scenes first, then the files.
    ASSERT_LT(blowup, file);
    const std::string blowupRow = data.substr(blowup, file - blowup);
    const std::string fileRow = data.substr(file);
    EXPECT_NE(fileRow.find(R"("products": 4,)"), std::string::npos) << fileRow;
    EXPECT_NE(fileRow.find(R"("primitives": 6,)"), std::string::npos) << fileRow;
    EXPECT_NE(fileRow.find(R"("normalize_elements": 5,)"), std::string::npos) << fileRow;
    EXPECT_NE(fileRow.find(R"("best":)"), std::string::npos) << "an OpenCSG figure for the file:\n" << fileRow;
    EXPECT_NE(blowupRow.find(R"("normalize_gave_up": true)"), std::string::npos) << blowupRow;
    EXPECT_NE(blowupRow.find(R"("normalize_elements": 200001,)"), std::string::npos) << blowupRow;
    EXPECT_EQ(blowupRow.find(R"("best":)"), std::string::npos) << "no OpenCSG figure past the limit:\n" << blowupRow;
    EXPECT_NE(r.out.find("gave up"), std::string::npos) << r.out;
}
