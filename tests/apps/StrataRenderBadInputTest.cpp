// strata-render on bad input: one line on stderr saying what and where,
// a non-zero exit status, and no output file (CONTRACT.md, "Exit status").

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>

#include <string>
#include <vector>

#include "../scene/NestedText.h"
#include "RunProcess.h"
#include "TempDir.h"

using strata::testing::lineCount;
using strata::testing::ProcessResult;
using strata::testing::runProcess;
using strata::testing::TempDir;

namespace {

const std::string kExe = STRATA_RENDER_EXE;
const std::string kCube = "cube(size = [2, 2, 2], center = true);\n";

// Runs strata-render with outputs in `dir`, then checks the failure's shape:
// exit status, one line on stderr that starts with `prefix`, nothing on
// stdout, and no output file in `dir`.
void expectFailure(const TempDir& dir, std::vector<std::string> args, const std::string& prefix,
                   const std::vector<std::pair<std::string, std::string>>& env = {}) {
    const std::vector<std::string> before = dir.files();
    std::vector<std::string> argv{kExe};
    argv.insert(argv.end(), args.begin(), args.end());
    for (const char* out : {"-o", "--depth", "--normal"}) {
        bool given = false;
        for (const std::string& a : args) given = given || a == out || a.rfind(std::string(out) + "=", 0) == 0;
        if (!given) {
            argv.push_back(out);
            argv.push_back(dir / (std::string(out) == "-o" ? "out.png" : std::string(out).substr(2) + ".exr"));
        }
    }
    const ProcessResult r = runProcess(argv, env);
    std::string cmd;
    for (const std::string& a : args) cmd += " " + a;
    EXPECT_NE(r.exitCode, 0) << cmd;
    EXPECT_LT(r.exitCode, 128) << "crashed:" << cmd << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << cmd << "\nstderr: " << r.err << "expected to start with: " << prefix;
    EXPECT_EQ(r.out, "") << cmd;
    EXPECT_EQ(dir.files(), before) << "an output file was written:" << cmd;
}

}  // namespace

TEST(StrataRender, NoArgumentsIsAUsageError) {
    TempDir dir;
    const ProcessResult r = runProcess({kExe});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("strata-render: ", 0), 0u) << r.err;
}

TEST(StrataRender, HelpListsTheContractsOptions) {
    const ProcessResult r = runProcess({kExe, "--help"});
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"-o", "--depth", "--normal", "--imgsize", "--camera", "--projection", "--fov",
                               "--layers", "--stats", "--colorscheme", "-D", "--viewall", "--autocenter", "--preview",
                               "--quiet", "--light", "--no-outline"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
}

TEST(StrataRender, UnknownOptionIsAUsageError) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "--bogus"}, "strata-render: ");
    expectFailure(dir, {scene, "extra.csg"}, "strata-render: ");
}

TEST(StrataRender, BadImageSizeIsOneLine) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    for (const char* size : {"0,10", "10,0", "-5,5", "abc", "10", "10,10,10", "1.5,2", "10,", ",10", "99999,10"})
        expectFailure(dir, {scene, "--imgsize", size}, "strata-render: --imgsize: ");
    // The --opt=value form reads the same.
    expectFailure(dir, {scene, "--imgsize=0,10"}, "strata-render: --imgsize: ");
}

TEST(StrataRender, BadCameraIsOneLine) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "--camera=1,2,3,4,5,6,7,8"}, "strata-render: --camera: expected 6 numbers");
    expectFailure(dir, {scene, "--camera", "1,2,3,4,5"}, "strata-render: --camera: expected 6 numbers");
    expectFailure(dir, {scene, "--camera", "1,2,x,4,5,6"}, "strata-render: --camera: 'x' is not a finite number");
    expectFailure(dir, {scene, "--camera", "1,2,inf,4,5,6"}, "strata-render: --camera: ");
    expectFailure(dir, {scene, "--camera", "1,1,1,1,1,1"}, "strata-render: --camera: eye and center must differ");
}

TEST(StrataRender, BadProjectionFovAndLayersAreOneLine) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "--projection", "x"}, "strata-render: --projection: ");
    expectFailure(dir, {scene, "--fov", "0"}, "strata-render: --fov: ");
    expectFailure(dir, {scene, "--fov=180"}, "strata-render: --fov: ");
    expectFailure(dir, {scene, "--fov", "wide"}, "strata-render: --fov: ");
    expectFailure(dir, {scene, "--fov", "1e-300"}, "strata-render: --fov: expected degrees from 0.01 to 179");
    expectFailure(dir, {scene, "--layers", "0"}, "strata-render: --layers: ");
    expectFailure(dir, {scene, "--layers=-2"}, "strata-render: --layers: ");
    expectFailure(dir, {scene, "--layers", "some"}, "strata-render: --layers: ");
    expectFailure(dir, {scene, "--colorscheme", "Rainbow"},
                  "strata-render: --colorscheme: unknown colour scheme 'Rainbow' (valid: Cornfield");
    // Several scenes need %s in every output name, and names of their own.
    expectFailure(dir, {scene, dir.write("other.csg", kCube), "-o", dir / "out.png"},
                  "strata-render: -o: with several scenes the name needs %s, the scene's name (got '");
    expectFailure(dir, {scene, scene, "-o", dir / "%s.png", "--depth", dir / "%s.exr", "--normal", dir / "%s-n.exr"},
                  "strata-render: '" + scene + "' and '" + scene + "' have one name, 'cube'");
    expectFailure(dir, {scene, "--light", "sun"},
                  "strata-render: --light: unknown light 'sun' (valid: strata, openscad)");
}

TEST(StrataRender, OutputNamesMustHaveTheirFormatsExtension) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "-o", dir / "out.jpg"}, "strata-render: -o: expected a .png file name");
    expectFailure(dir, {scene, "--depth", dir / "z.png"}, "strata-render: --depth: expected a .exr file name");
    expectFailure(dir, {scene, "--normal=" + (dir / "n.tif")}, "strata-render: --normal: expected a .exr file name");
}

TEST(StrataRender, UnknownSceneTypeNamesTheFile) {
    TempDir dir;
    const std::string scene = dir.write("model.xyz", kCube);
    expectFailure(dir, {scene}, scene + ": unknown scene type '.xyz'");
}

TEST(StrataRender, ControlBytesInFileNamesReachNoTerminal) {
    TempDir dir;
    // A scene, and an import() inside one, named with an escape sequence
    // that would colour a terminal red and set its title.
    const std::string scene = dir.write("red\x1b[31m\x1b]0;x\x07.csg", "group() {\n\tcube(size = [1, 1, 1];\n}\n");
    expectFailure(dir, {scene}, (dir / "red\\x1b[31m\\x1b]0;x\\x07.csg") + ":2:");
    const std::string importer = dir.write("imports.csg", "import(file = \"gone\x1b[2J.stl\");\n");
    expectFailure(dir, {importer}, importer + ":1:15: import file not found: ");
    const ProcessResult r = runProcess({kExe, importer, "-o", dir / "out.png"});
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("gone\\x1b[2J.stl"), std::string::npos) << r.err;
}

// 44 bytes: a 2 x 2 grey PNG whose next chunk, text or compressed text,
// claims 2 GiB. libpng took the claim as a size to allocate and fill (its
// chunk limit is only a warning to a reader): 2 GB resident before the file
// was found short. Skipped unread, it is simply short.
TEST(StrataRender, APngChunkClaimingGigabytesIsNotAllocated) {
    TempDir dir;
    const std::string header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\x02\0\0\0\x02\x08\0\0\0\0\x57\xdd\x52\xf8\x7f\xff\xff\xff", 37);
    for (const char* kind : {"tEXt", "zTXt"}) {
        const std::string png = dir.write(std::string(kind) + ".png", header + kind + "abc");
        ASSERT_EQ(std::filesystem::file_size(png), 44u);
        const std::string scene = dir.write(std::string(kind) + ".csg", "surface(file = \"" + png + "\");\n");
        const std::string stl = dir / "out.stl";
        const ProcessResult r = runProcess({kExe, scene, "--export", stl});
        EXPECT_EQ(r.exitCode, 1) << kind << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << kind << ": " << r.err;
        EXPECT_NE(r.err.find("surface: cannot read '" + png + "': not a valid PNG image (truncated file)"), std::string::npos)
            << kind << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(stl));
        EXPECT_GT(r.peakKiB, 0) << kind;
        EXPECT_LT(r.peakKiB, 512 * 1024) << kind;
    }
}

// A mistake inside a drawing or a font name: the node's position once, then
// what is wrong (the drawing's own line where its parser gives one).
TEST(StrataRender, DrawingAndTextErrorsNameOnePosition) {
    TempDir dir;
    dir.write("arc.dxf", "0\nSECTION\n2\nENTITIES\n0\nARC\n10\n0\n20\n0\n40\n1\n50\n0\n51\n1e9\n0\nENDSEC\n0\nEOF\n");
    dir.write("tags.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 L 1 1 Z\"/>\n<g></svg>\n");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"cube(1);\nlinear_extrude(height = 1) import(file = \"arc.dxf\");\n",
         ":2:28: import: an ARC in the DXF file sweeps 2777777.777778 turns; at most one is drawn\n"},
        {"linear_extrude(height = 1) import(file = \"tags.svg\");\n",
         ":1:28: import: cannot parse '" + (dir / "tags.svg") + "': Opening and ending tag mismatch: g line 2 and svg (line 2)\n"},
        {"linear_extrude(height = 1) text(text = \"a\", font = \"Foo:weight=abc\");\n",
         ":1:28: text(): fontconfig cannot parse the font name 'Foo:weight=abc'\n"},
    };
    int n = 0;
    for (const auto& [text, message] : cases) {
        const std::string scene = dir.write("case" + std::to_string(n++) + ".csg", text);
        const ProcessResult r = runProcess({kExe, scene, "--export", dir / "out.stl"});
        EXPECT_EQ(r.exitCode, 1) << scene;
        EXPECT_EQ(r.err, scene + message);
    }
}

TEST(StrataRender, MissingOrUnreadableSceneNamesTheFile) {
    TempDir dir;
    expectFailure(dir, {dir / "missing.csg"}, (dir / "missing.csg") + ": ");
    expectFailure(dir, {dir / "missing.stl"}, (dir / "missing.stl") + ": ");
    std::filesystem::create_directories(dir / "folder.csg");
    expectFailure(dir, {dir / "folder.csg"}, (dir / "folder.csg") + ": ");
}

TEST(StrataRender, MalformedCsgNamesFileLineAndColumn) {
    TempDir dir;
    const std::string scene = dir.write("bad.csg", "group() {\n\tcube(size = [1, 1, 1];\n}\n");
    const std::vector<std::string> before = dir.files();
    const ProcessResult r = runProcess({kExe, scene, "-o", dir / "out.png"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    // "<path>:2:<col>: ..."
    EXPECT_EQ(r.err.rfind(scene + ":2:", 0), 0u) << r.err;
    EXPECT_EQ(dir.files(), before);
}

TEST(StrataRender, OpenMeshIsAnErrorNamingTheFile) {
    TempDir dir;
    // One triangle: every edge has a single face.
    const std::string scene = dir.write("open.stl",
                                        "solid open\n"
                                        "facet normal 0 0 1\n outer loop\n"
                                        "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
                                        " endloop\nendfacet\nendsolid open\n");
    expectFailure(dir, {scene}, scene);
}

TEST(StrataRender, MissingOutputFolderWritesNothing) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    // The PNG's folder exists, the depth's does not: neither may appear.
    expectFailure(dir, {scene, "-o", dir / "out.png", "--depth", dir / "nowhere/z.exr"}, dir / "nowhere/z.exr");
}

TEST(StrataRender, MissingEglIsOneLineAndWritesNothing) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    // glvnd finds no EGL vendor library: as on a machine without Mesa's EGL.
    expectFailure(dir, {scene}, "EGL: no OpenGL 4.5 core context available (",
                  {{"__EGL_VENDOR_LIBRARY_FILENAMES", dir / "no-such-vendor.json"},
                   {"__EGL_VENDOR_LIBRARY_DIRS", dir / "no-such-folder"}});
}

TEST(StrataRender, FifosDevicesAndFoldersAreRefusedWithoutBlocking) {
    TempDir dir;
    // A FIFO would block a reader that opens it; a device would feed one forever.
    ASSERT_EQ(::mkfifo((dir / "pipe.csg").c_str(), 0600), 0);
    expectFailure(dir, {dir / "pipe.csg"}, (dir / "pipe.csg") + ": cannot read (it is a FIFO)");
    std::filesystem::create_symlink("/dev/zero", dir / "zero.stl");
    expectFailure(dir, {dir / "zero.stl"}, (dir / "zero.stl") + ": cannot read (it is a device)");
    // The same inside a scene: an import of a device, a FIFO or a folder.
    const std::string scene = dir.write(
        "imports.csg", "import(file = \"zero.stl\");\nimport(file = \"pipe.csg.stl\");\nimport(file = \"sub.stl\");\n");
    expectFailure(dir, {scene}, scene + ":1:15: import cannot read '" + (dir / "zero.stl") + "': it is a device");
    ASSERT_EQ(::mkfifo((dir / "pipe.csg.stl").c_str(), 0600), 0);
    dir.write("imports2.csg", "import(file = \"pipe.csg.stl\");\n");
    expectFailure(dir, {dir / "imports2.csg"},
                  (dir / "imports2.csg") + ":1:15: import cannot read '" + (dir / "pipe.csg.stl") + "': it is a FIFO");
    std::filesystem::create_directories(dir / "sub.stl");
    dir.write("imports3.csg", "import(file = \"sub.stl\");\n");
    expectFailure(dir, {dir / "imports3.csg"},
                  (dir / "imports3.csg") + ":1:15: import cannot read '" + (dir / "sub.stl") + "': it is a folder");
    std::filesystem::create_directories(dir / "folder.csg");
    expectFailure(dir, {dir / "folder.csg"}, (dir / "folder.csg") + ": cannot read (it is a folder)");
}

TEST(StrataRender, TwoOutputsIntoOneFileIsAUsageError) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "--depth", dir / "s.exr", "--normal", dir / "s.exr"},
                  "strata-render: --depth and --normal name the same file");
    expectFailure(dir, {scene, "--depth", dir / "s.exr", "--normal", dir / "./s.exr"},
                  "strata-render: --depth and --normal name the same file");
}

TEST(StrataRender, HugeAndNonFiniteNumbersNameTheirNode) {
    TempDir dir;
    // Past strata's largest coordinate: named by the node, not by the camera it would break.
    const std::string big = dir.write("big.csg", "cube(size = 1e308);\n");
    expectFailure(dir, {big}, big + ":1:1: cube reaches 1e+308 after its transform; strata takes coordinates up to 1e12");
    const std::string far = dir.write("far.csg", "multmatrix([[1, 0, 0, 1e308], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(1);\n");
    expectFailure(dir, {far}, far + ":1:74: cube reaches 1e+308 after its transform");
    // OpenSCAD writes inf and nan as words: a matrix holding one is a matrix with a bad number.
    const std::string inf = dir.write("inf.csg", "multmatrix([[1, 0, 0, inf], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(1);\n");
    expectFailure(dir, {inf}, inf + ":1:12: multmatrix has a number that is not finite");
    // A NUL byte in an import's name is named, not a cut-off name.
    const std::string nul = dir.write("nul.csg", std::string("import(file = \"a\0b.stl\");\n", 26));
    expectFailure(dir, {nul}, nul + ":1:15: import file name holds a NUL byte: 'a\\0b.stl'");
}

TEST(StrataRender, HostilePlyHeadersAreOneLineNotACrashOrAHang) {
    TempDir dir;
    // 49 bytes: a property before any element (OpenMesh's reader crashes on it).
    const std::string noElement = dir.write("no_element.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
    expectFailure(dir, {noElement}, noElement + ":3: cannot read mesh: a property before any element");
    // No end_header (OpenMesh's reader never returns).
    const std::string noEnd = dir.write("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
    expectFailure(dir, {noEnd}, noEnd + ": cannot read mesh: the header has no end_header line");
    // A face list longer than the file (OpenMesh would reserve it and read on).
    const std::string longList = dir.write(
        "long_list.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n");
    expectFailure(dir, {longList}, longList + ":13: cannot read mesh: a list of 2000000000 values, more than the file holds");
    // The same files imported by a scene: named by the import, then the file.
    const std::string scene = dir.write("imports.csg", "import(file = \"no_element.ply\");\n");
    expectFailure(dir, {scene}, scene + ":1:1: " + noElement + ":3: cannot read mesh: a property before any element");
    const std::string scene2 = dir.write("imports2.csg", "cube(1);\nimport(file = \"no_end.ply\");\n");
    expectFailure(dir, {scene2}, scene2 + ":2:1: " + noEnd + ": cannot read mesh: the header has no end_header line");
}

TEST(StrataRender, AFailureAfterWarningsIsStillOneLine) {
    TempDir dir;
    // An unsupported node (a warning from the parser) and an open
    // polyhedron (an error in the geometry after it).
    const std::string scene = dir.write(
        "both.csg", "roof() square(1);\npolyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 2]]);\n");
    expectFailure(dir, {scene}, scene + ":2:1: polyhedron is not a closed solid");
}

// A .scad goes through the installed openscad; its mistakes name the .scad.
TEST(StrataRender, DefinitionsWithoutAScadAreAUsageError) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "-D", "size=3"},
                  "strata-render: -D: only a .scad scene takes definitions (the scene is '" + scene + "')");
    const ProcessResult r = runProcess({kExe, scene, "-D", "size=3", "-o", dir / "out.png"});
    EXPECT_EQ(r.exitCode, 2);
    const std::string scad = dir.write("a.scad", "cube(1);\n");
    expectFailure(dir, {scad, "-D", "size"}, "strata-render: -D: expected NAME=VALUE, got 'size'");
    expectFailure(dir, {scad, "-D", "=3"}, "strata-render: -D: expected NAME=VALUE, got '=3'");
}

TEST(StrataRender, ScadWithoutOpenscadSaysSoInOneLine) {
    TempDir dir;
    const std::string scad = dir.write("a.scad", "cube(1);\n");
    expectFailure(dir, {scad, "-D", "n=1"}, scad + ": cannot open .scad: openscad is not installed",
                  {{"PATH", dir / "nothing-here"}});
}

TEST(StrataRender, ScadMistakesNameTheScad) {
    if (runProcess({"/bin/sh", "-c", "command -v openscad"}).exitCode != 0) GTEST_SKIP() << "openscad not installed";
    TempDir dir;
    const std::string scad = dir.write("bad.scad", "cube(1);\nsphere(;\n");
    expectFailure(dir, {scad}, scad + ":2: openscad could not export CSG: ERROR: Parser error");
    // A bad value in a -D is named as the -D, not as a line past the .scad's end.
    const std::string good = dir.write("good.scad", "n = 1;\ncube(n);\n");
    expectFailure(dir, {good, "-D", "n=1", "-D", "m=2+"}, good + ": openscad could not export CSG: in -D m=2+: ERROR");
    // An error in the export's geometry names the .scad's line where the node
    // traces back to one call there (a file it uses included), else the
    // line of the .scad's CSG export.
    const std::string open = dir.write("open.scad", "\n\n  polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 2]]);\n");
    expectFailure(dir, {open}, open + ":3:3: polyhedron is not a closed solid");
    dir.write("shapes.scad", "module flat() {\n  polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 2]]);\n}\n");
    const std::string user = dir.write("user.scad", "use <shapes.scad>\ncube(1);\nflat();\n");
    expectFailure(dir, {user}, (dir / "shapes.scad") + ":2:3: polyhedron is not a closed solid");
    const std::string twice =
        dir.write("twice.scad", "polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 2]]);\n"
                                "if (false) polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], faces = "
                                "[[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);\n");
    expectFailure(dir, {twice}, twice + " (CSG export):1:1: polyhedron is not a closed solid");
}

TEST(StrataRender, OpenscadOptionsItDoesNotTakeAreOneLineEach) {
    TempDir dir;
    const std::string scene = dir.write("cube.csg", kCube);
    expectFailure(dir, {scene, "--animate", "10"}, "strata-render: --animate: strata-render renders one frame");
    expectFailure(dir, {scene, "--render"}, "strata-render: --render: strata-render draws OpenSCAD's preview");
    expectFailure(dir, {scene, "--preview=throwntogether"}, "strata-render: --preview=throwntogether: ");
    expectFailure(dir, {scene, "--export-format", "binstl"}, "strata-render: --export-format: ");
    expectFailure(dir, {scene, "--view", "axes"}, "strata-render: --view: ");
    expectFailure(dir, {scene, "-p", "params.json", "-P", "big"}, "strata-render: -p: strata-render gives openscad only -D");
    expectFailure(dir, {scene, "--hardwarnings"}, "strata-render: --hardwarnings: ");
    expectFailure(dir, {scene, "--camera", "0,0,0,55,0,25,100", "--viewall"},
                  "strata-render: --viewall with --camera: strata-render does not refit a given camera");
    expectFailure(dir, {scene, "--autocenter", "--camera=1,2,3,0,0,0"}, "strata-render: --autocenter with --camera: ");
}

namespace {

using strata::test::nested;

}  // namespace

TEST(StrataRender, DeeplyNestedShapesAreOneLine) {
    // Each level reads its children into a shape of its own, which building
    // the model walks on the C++ stack: these ran out of it (a crash) far
    // inside the nesting of blocks the parser takes. Refused where the
    // budget runs out.
    TempDir dir;
    const std::string budget = ": nesting too deep (more than 1000 hull, minkowski, resize, projection or extrusion levels)";
    const std::string projection = dir.write("projection.csg", nested(5000, "projection(cut = false) {", kCube, "}"));
    expectFailure(dir, {projection}, projection + ":1001:1" + budget);
    const std::string extruded = dir.write(
        "extruded.csg", nested(5000, "linear_extrude(height = 1) { projection(cut = false) {", kCube, "} }"));
    expectFailure(dir, {extruded}, extruded + ":501:1" + budget);
    const std::string hull = dir.write("hull.csg", nested(50000, "hull() { difference() {", kCube, "} }"));
    expectFailure(dir, {hull}, hull + ":1001:1" + budget);
    const std::string resize = dir.write("resize.csg", nested(50000, "resize([1, 1, 1]) { difference() {", kCube, "} }"));
    expectFailure(dir, {resize}, resize + ":1001:1" + budget);
    // The same refusal from --export, which evaluates the model on the CPU.
    expectFailure(dir, {hull, "--export", dir / "hull.stl"}, hull + ":1001:1" + budget);
}

// Just inside the budget: each hull or sum holds the one inside it, and
// copying that into every level cost memory quadratic in the depth (999
// nested minkowski()s: 234 MB; 10,000 nested hull()s grew past 7.7 GB).
// Each level's leaves are now moved into it.
TEST(StrataRender, NestedHullsAndSumsCostTheirLeavesOnce) {
    TempDir dir;
    const std::string sums = dir.write("sums.csg", nested(999, "minkowski() {", kCube, "}"));
    const std::string hulls = dir.write("hulls.csg", nested(999, "hull() { difference() {", kCube, "} }"));
    for (const std::string& scene : {sums, hulls}) {
        const ProcessResult r = runProcess({kExe, scene, "--export", dir / "out.stl"});
        EXPECT_EQ(r.exitCode, 0) << scene << ": " << r.err;
#if !defined(__SANITIZE_ADDRESS__)
        EXPECT_LT(r.peakKiB, 120 * 1024) << scene;
#endif
    }
}

TEST(StrataRender, AMistakeDeepInsideNestedShapesNamesOnePosition) {
    // The innermost node that knows where it is names the mistake; the
    // 999 shapes around it (the extrusion is the thousandth) add nothing to
    // the line.
    TempDir dir;
    const std::string scene = dir.write(
        "deep.csg", nested(999, "hull() { difference() {", "rotate_extrude() { square(size = [1, 1], center = true); }", "} }"));
    expectFailure(dir, {scene}, scene + ":1000:1: all points for rotate_extrude() must have the same X coordinate sign");
}
