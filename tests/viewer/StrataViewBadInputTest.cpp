// strata-view on bad input: the same one-line errors as strata-render, a
// non-zero status, and no window needed (all of it is found before one opens).

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::lineCount;
using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kView = STRATA_VIEW_EXE;
const std::string kRender = STRATA_RENDER_EXE;

// No display: these must fail before a window is asked for.
const std::vector<std::pair<std::string, std::string>> kNoDisplay{{"DISPLAY", ":4999"}};

}  // namespace

TEST(StrataViewBadInput, SceneErrorsAreStrataRendersOneLiners) {
    TempDir dir;
    const std::string bad = dir.write("bad.csg", "cube(size = [1, 1, 1]);\nsphere(r = );\n");
    const std::string open = dir.write("open.csg", "polyhedron(points = [[0,0,0],[1,0,0],[0,1,0]], faces = [[0,1,2]]);\n");
    // A FIFO would block the reader, a device feed it forever: refused before opening.
    EXPECT_EQ(::mkfifo((dir / "pipe.csg").c_str(), 0600), 0);
    EXPECT_EQ(::mkfifo((dir / "pipe.scad").c_str(), 0600), 0);
    std::filesystem::create_symlink("/dev/urandom", dir / "noise.stl");
    for (const std::string& scene :
         {bad, open, dir / "missing.csg", dir / "scene.txt", dir / "pipe.csg", dir / "pipe.scad", dir / "noise.stl"}) {
        const ProcessResult view = runProcess({kView, scene}, kNoDisplay);
        const ProcessResult render = runProcess({kRender, scene});
        EXPECT_NE(view.exitCode, 0) << scene;
        EXPECT_EQ(lineCount(view.err), 1) << view.err;
        EXPECT_TRUE(view.err.starts_with(scene + ":")) << view.err;
        EXPECT_EQ(view.err, render.err);
    }
}

TEST(StrataViewBadInput, ScadWithoutOpenscadSaysSoInOneLine) {
    TempDir dir;
    const std::string scad = dir.write("a.scad", "cube(1);\n");
    const ProcessResult r = runProcess({kView, scad}, {{"DISPLAY", ":4999"}, {"PATH", dir / "nothing-here"}});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(scad + ": cannot open .scad: openscad is not installed"), std::string::npos) << r.err;
}

TEST(StrataViewBadInput, ScriptMistakesAreFoundBeforeTheWindowOpens) {
    TempDir dir;
    const std::string scene = dir.write("a.csg", "cube(size = [1, 1, 1]);\n");
    const std::string script = dir.write("s.txt", "size 64 64\nlayers -2\n");
    const ProcessResult r = runProcess({kView, scene, "--script", script}, kNoDisplay);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, script + ":2:8: layers: expected 'auto' or a whole number from 1 to 1024, got '-2'\n");
}

TEST(StrataViewBadInput, BadOptionsExitWithUsageStatus) {
    const ProcessResult r = runProcess({kView, "a.csg", "--imgsize", "12"}, kNoDisplay);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "strata-view: --imgsize: expected W,H (two whole numbers from 1 to 16384), got '12'\n");
    EXPECT_EQ(runProcess({kView}, kNoDisplay).exitCode, 2);
}
