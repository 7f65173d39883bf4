// strata-view's --script language (apps/strata-view/Script.h): what it
// accepts, and that every mistake is one file:line:col line at the right word.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdio>
#include <string>
#include <utility>

#include "Script.h"

using namespace strata;
using view::CommandKind;

namespace {

// The message of the error parsing `text` gives; empty when it parses.
std::string errorOf(const std::string& text) {
    try {
        view::parseScript(text, "s.txt");
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(Script, ParsesEveryCommandWithItsArguments) {
    const auto commands = view::parseScript(
        "# a comment\n"
        "size 320 240\n"
        "\n"
        "layers auto   # trailing comment\n"
        "layers 3\n"
        "camera 1,2,3,0,0,0\n"
        "camera 0,0,0,55,0,25,140\n"
        "orbit 10 -2.5\n"
        "preset top\n"
        "toggle line:4\n"
        "toggle 7\n"
        "colorscheme Tomorrow Night\n"
        "screenshot \"my shots/a.png\"\n"
        "wait-reload\n"
        "light openscad\n"
        "show outline off\n"
        "key ctrl+q\n"
        "quit\n",
        "s.txt");
    ASSERT_EQ(commands.size(), 16u);
    EXPECT_EQ(commands[0].kind, CommandKind::Size);
    EXPECT_EQ(commands[0].numbers, (std::vector<double>{320, 240}));
    EXPECT_EQ(commands[0].where.str(), "s.txt:2:1");
    EXPECT_EQ(commands[1].words, (std::vector<std::string>{"auto"}));
    EXPECT_EQ(commands[2].numbers, (std::vector<double>{3}));
    EXPECT_EQ(commands[3].numbers.size(), 6u);
    EXPECT_EQ(commands[4].numbers.size(), 7u);
    EXPECT_EQ(commands[5].numbers, (std::vector<double>{10, -2.5}));
    EXPECT_EQ(commands[9].words[0], "Tomorrow Night");
    EXPECT_EQ(commands[10].words[0], "my shots/a.png");
    EXPECT_EQ(commands[12].kind, CommandKind::Light);
    EXPECT_EQ(commands[12].words[0], "openscad");
    EXPECT_EQ(commands[13].kind, CommandKind::Show);
    EXPECT_EQ(commands[13].words, (std::vector<std::string>{"outline", "off"}));
    EXPECT_EQ(commands[14].kind, CommandKind::Key);
    EXPECT_EQ(commands[14].words[0], "ctrl+q");
    EXPECT_EQ(commands[15].kind, CommandKind::Quit);
}

TEST(Script, MistakesNameLineColumnAndWord) {
    EXPECT_EQ(errorOf("size 320 240\n  jump 3\n"),
              "s.txt:2:3: unknown command 'jump' (valid: open, size, layers, camera, projection, fov, orbit, pan, "
              "middle-drag, zoom-drag, zoom, preset, view-all, double-click, toggle, highlight, colorscheme, light, debug, panel, show, screenshot, "
              "screenshot-window, export, export-exact, export-sampled, save-csg, copy, remove, wait-reload, wait-loading, print, key, sleep, quit)");
    EXPECT_EQ(errorOf("layers many\n"), "s.txt:1:8: layers: expected 'auto' or a whole number from 1 to 1024, got 'many'");
    EXPECT_EQ(errorOf("layers 0\n"), "s.txt:1:8: layers: expected 'auto' or a whole number from 1 to 1024, got '0'");
    EXPECT_EQ(errorOf("size 320\n"), "s.txt:1:1: size: expected 2 arguments, got 1");
    EXPECT_EQ(errorOf("quit now\n"), "s.txt:1:6: quit: expected 0 arguments, got 1");
    EXPECT_EQ(errorOf("camera 1,2,x,4,5,6\n"), "s.txt:1:8: camera: 'x' is not a finite number");
    EXPECT_EQ(errorOf("camera 1,2,3\n"),
              "s.txt:1:8: camera: expected 6 numbers (eye, center) or 7 (translate, rotate, distance), got 3");
    EXPECT_EQ(errorOf("preset sideways\n"),
              "s.txt:1:8: preset: unknown view 'sideways' (valid: top, bottom, left, right, front, back, diagonal)");
    EXPECT_EQ(errorOf("orbit 1 nan\n"), "s.txt:1:9: orbit: expected pixels, got 'nan'");
    EXPECT_EQ(errorOf("screenshot a.jpg\n"), "s.txt:1:12: screenshot: expected a .png file name, got 'a.jpg'");
    EXPECT_EQ(errorOf("export a.ply\n"),
              "s.txt:1:8: export: expected a .stl, .off, .obj or .3mf (or, for a 2D model, .svg or .dxf) file name, got 'a.ply'");
    EXPECT_EQ(errorOf("export-sampled a.svg\n"),
              "s.txt:1:16: export-sampled: expected a .stl, .off, .obj or .3mf file name, got 'a.svg'");
    EXPECT_EQ(errorOf("save-csg a.scad\n"), "s.txt:1:10: save-csg: expected a .csg file name, got 'a.scad'");
    EXPECT_EQ(errorOf("open \"a.csg\n"), "s.txt:1:6: unterminated quoted word");
    EXPECT_EQ(errorOf("toggle line:x\n"), "s.txt:1:8: toggle: expected line:N with N from 1 to 1000000000");
    EXPECT_EQ(errorOf("toggle line:99999999999\n"), "s.txt:1:8: toggle: expected line:N with N from 1 to 1000000000");
    EXPECT_EQ(errorOf("light sun\n"), "s.txt:1:7: light: expected one of strata, openscad, got 'sun'");
    EXPECT_EQ(errorOf("show outline maybe\n"), "s.txt:1:14: show: expected on or off, got 'maybe'");
    EXPECT_EQ(errorOf("debug xray\n"),
              "s.txt:1:7: debug: expected one of shaded, depth, normal, peel, forms, got 'xray'");
    EXPECT_EQ(errorOf("key Escape\n"),
              "s.txt:1:5: key: expected [ctrl+] and a lower-case letter, a digit, escape, f5 or f12, got 'Escape'");
    EXPECT_EQ(errorOf("key ctrl+\n"),
              "s.txt:1:5: key: expected [ctrl+] and a lower-case letter, a digit, escape, f5 or f12, got 'ctrl+'");
    EXPECT_EQ(errorOf("panel half\n"), "s.txt:1:7: panel: expected on, off, open, export or a width from 220 to 16384, got 'half'");
    EXPECT_EQ(errorOf("panel 100\n"), "s.txt:1:7: panel: expected on, off, open, export or a width from 220 to 16384, got '100'");
}

TEST(Script, RelativePathsAreFromTheScriptsFolder) {
    EXPECT_EQ(view::resolveScriptPath("dir/s.txt", "shots/a.png"), "dir/shots/a.png");
    EXPECT_EQ(view::resolveScriptPath("dir/s.txt", "/tmp/a.png"), "/tmp/a.png");
    EXPECT_EQ(view::resolveScriptPath("s.txt", "a.png"), "a.png");
}

TEST(Script, MissingFileIsAnError) {
    EXPECT_THROW(view::parseScriptFile("/nonexistent/strata-view-script.txt"), Error);
}

TEST(Script, AScriptIsARegularFile) {
    // A FIFO nobody writes would block the viewer, /dev/zero feed it for
    // good: each is one line naming the file, before anything is read.
    const std::string fifo = ::testing::TempDir() + "strata-view-script-fifo";
    std::remove(fifo.c_str());
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const auto& [path, why] : {std::pair<std::string, std::string>{fifo, "it is a FIFO"}, {"/dev/zero", "it is a device"}}) {
        try {
            view::parseScriptFile(path);
            ADD_FAILURE() << path << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), path + ": cannot read script: " + why);
        }
    }
    std::remove(fifo.c_str());
}
