// strata-bench on a user's own scene file (--files): the file is timed like
// the built-in scenes, its row named after it with K its number of leaves,
// and a file it cannot load stops the run before any frame, with the file
// named and no JSON left behind.

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
