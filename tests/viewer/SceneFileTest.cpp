// A .scad's CSG export kept with the loaded scene (apps/strata-view/SceneFile.h)
// and saved where the user says: the text OpenSCAD wrote, complete or not at
// all, never over the .scad, and one line when it cannot be saved.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "RunProcess.h"
#include "strata/scene/ScadExport.h"
#include "SceneFile.h"
#include "TempDir.h"

using strata::Error;
using strata::testing::runProcess;
using strata::testing::TempDir;
using strata::view::LoadedScene;

namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The message saveCsgExport throws; empty when it saved.
std::string saveError(const LoadedScene& scene, const std::string& scenePath, const std::string& target) {
    try {
        strata::view::saveCsgExport(scene, scenePath, target);
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

const std::string kScad = "cube(5);\n";
const std::string kExport = "group() {\n\tcube(size = [5, 5, 5], center = false);\n}\n";

}  // namespace

TEST(SaveCsgExport, WritesTheExportAsKeptAndNothingElse) {
    TempDir dir;
    const std::string scad = dir.write("a.scad", kScad);
    LoadedScene scene;
    scene.csgExport = kExport;
    EXPECT_EQ(saveError(scene, scad, dir / "a.csg"), "");
    EXPECT_EQ(readText(dir / "a.csg"), kExport);
    EXPECT_EQ(readText(scad), kScad);
    // No temporary left beside it; saving again replaces the file.
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.csg", "a.scad"}));
    scene.csgExport = "cube(size = [1, 1, 1], center = false);\n";
    EXPECT_EQ(saveError(scene, scad, dir / "a.csg"), "");
    EXPECT_EQ(readText(dir / "a.csg"), scene.csgExport);
}

TEST(SaveCsgExport, DefaultsBesideTheScadWithItsStem) {
    EXPECT_EQ(strata::view::defaultCsgExportPath("/models/gear.scad"), "/models/gear.csg");
    EXPECT_EQ(strata::view::defaultCsgExportPath("gear.v2.scad"), "gear.v2.csg");
}

TEST(SaveCsgExport, ASceneWithoutAnExportIsOneLineAndNoFile) {
    TempDir dir;
    const std::string csg = dir.write("a.csg", kExport);
    const LoadedScene scene;  // a .csg: no export
    const std::string error = saveError(scene, csg, dir / "out.csg");
    EXPECT_EQ(error, "cannot save a CSG export: " + csg + " is not a .scad, its positions are its own lines");
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.csg"}));
}

TEST(SaveCsgExport, NeverWritesOverTheScad) {
    TempDir dir;
    const std::string scad = dir.write("a.scad", kScad);
    LoadedScene scene;
    scene.csgExport = kExport;
    EXPECT_EQ(saveError(scene, scad, scad),
              "cannot save the CSG export to '" + scad + "': expected a .csg file name");
    // A .csg name that leads to the .scad.
    std::filesystem::create_symlink(scad, dir / "link.csg");
    EXPECT_EQ(saveError(scene, scad, dir / "link.csg"),
              "cannot save the CSG export to '" + (dir / "link.csg") + "': that is the .scad itself");
    EXPECT_EQ(readText(scad), kScad);
    EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.csg"));
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.scad", "link.csg"}));
}

TEST(SaveCsgExport, AMissingFolderIsOneLineAndNoFile) {
    TempDir dir;
    const std::string scad = dir.write("a.scad", kScad);
    LoadedScene scene;
    scene.csgExport = kExport;
    const std::string target = dir / "missing/a.csg";
    const std::string error = saveError(scene, scad, target);
    EXPECT_TRUE(error.starts_with(target + ": cannot write")) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.scad"}));
}

TEST(SaveCsgExport, ALoadedScadKeepsOpenscadsExportAndACsgKeepsNone) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    const std::string scad = dir.write("a.scad", "\n\ndifference() { cube(10, center = true); sphere(6.5); }\n");
    const LoadedScene scene = strata::view::loadSceneFile(scad);
    ASSERT_EQ(runProcess({"/bin/sh", "-c", "openscad -o '" + (dir / "by-openscad.csg") + "' '" + scad + "'"}).exitCode, 0);
    EXPECT_EQ(scene.csgExport, readText(dir / "by-openscad.csg"));
    EXPECT_FALSE(scene.csgExport.empty());
    EXPECT_TRUE(strata::view::loadSceneFile(dir / "by-openscad.csg").csgExport.empty());
}

TEST(SceneDependencies, AMakeRuleGivesItsFilesWithEscapedSpaces) {
    EXPECT_EQ(strata::scene::makeRuleFiles("out.csg: \\\n\t/a/p.stl \\\n\t/a/my\\ lib.scad \\\n\tmain.scad\n"),
              (std::vector<std::string>{"/a/p.stl", "/a/my lib.scad", "main.scad"}));
    EXPECT_EQ(strata::scene::makeRuleFiles("x.csg: a.scad b.scad"), (std::vector<std::string>{"a.scad", "b.scad"}));
    EXPECT_TRUE(strata::scene::makeRuleFiles("").empty());
    EXPECT_TRUE(strata::scene::makeRuleFiles("no colon at all").empty());
}

TEST(SceneDependencies, AScadNamesEveryFileItUsesIncludesAndImports) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    const std::string lib = dir.write("my lib.scad", "module part() { cube(2); }\n");
    const std::string size = dir.write("size.scad", "h = 3;\n");
    // A closed tetrahedron.
    std::string stl = "solid p\n";
    const char* faces[4][3] = {{"0 0 0", "0 1 0", "1 0 0"}, {"0 0 0", "1 0 0", "0 0 1"},
                               {"0 0 0", "0 0 1", "0 1 0"}, {"1 0 0", "0 1 0", "0 0 1"}};
    for (const auto& face : faces) {
        stl += "facet normal 0 0 0\nouter loop\n";
        for (const char* corner : face) stl += std::string("vertex ") + corner + "\n";
        stl += "endloop\nendfacet\n";
    }
    const std::string mesh = dir.write("p.stl", stl + "endsolid p\n");
    const std::string scad =
        dir.write("a.scad", "use <my lib.scad>\ninclude <size.scad>\npart();\n%import(\"p.stl\");\ncube(h);\n");
    const LoadedScene scene = strata::view::loadSceneFile(scad);
    auto has = [&](const std::string& file) {
        return std::find(scene.dependencies.begin(), scene.dependencies.end(), file) != scene.dependencies.end();
    };
    EXPECT_TRUE(has(lib)) << ::testing::PrintToString(scene.dependencies);
    EXPECT_TRUE(has(size)) << ::testing::PrintToString(scene.dependencies);
    EXPECT_TRUE(has(mesh)) << ::testing::PrintToString(scene.dependencies);
    EXPECT_TRUE(strata::view::loadSceneFile(dir / "p.stl").dependencies.empty());
}
