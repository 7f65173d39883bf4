#pragma once
// The --script language of strata-view (docs/viewer.md, "Scripts"): one
// command per line, words separated by blanks, '#' starts a comment, a word
// with blanks in it goes in double quotes. The whole file is checked before
// the viewer opens, so a typo on line 40 costs nothing; every mistake is one
// "file:line:col: message" naming the offending word.

#include <string>
#include <vector>

#include "strata/core/Error.h"

namespace strata::view {

enum class CommandKind {
    Open,             // open PATH
    Size,             // size W H            (the 3D view, in pixels)
    Layers,           // layers N|auto
    Camera,           // camera NUMBERS      (strata-render's --camera: 6 or 7, commas)
    Projection,       // projection p|o
    Fov,              // fov DEG
    Orbit,            // orbit DX DY         (left drag, pixels)
    Pan,              // pan DX DY           (right drag)
    MiddleDrag,       // middle-drag DX DY   (along the view axis; DX is ignored, as OpenSCAD does)
    ZoomDrag,         // zoom-drag DY        (shift + right drag)
    Zoom,             // zoom NOTCHES [X Y]  (wheel; positive: closer; towards pixel X, Y when given)
    Preset,           // preset top|bottom|left|right|front|back|diagonal
    ViewAll,          // view-all
    DoubleClick,      // double-click X Y    (re-centre on the surface at pixel X, Y; row 0 at the top)
    Toggle,           // toggle NODE         (hide / show a subtree)
    Highlight,        // highlight NODE      (toggle '#')
    ColorScheme,      // colorscheme NAME...
    Debug,            // debug shaded|depth|normal|peel
    Panel,            // panel on|off|open|export|WIDTH
    Show,             // show axes|scale|edges|outline on|off
    Light,            // light strata|openscad
    Screenshot,       // screenshot PATH     (the 3D view as strata-render writes it)
    ScreenshotWindow, // screenshot-window PATH (the whole window, panel included)
    Export,           // export PATH         (the exact result, as strata-render --export; waits until written)
    ExportSampled,    // export-sampled PATH (sampled and contoured, as --export-sampled --reference; waits until written)
    SaveCsg,          // save-csg PATH.csg   (a .scad's CSG export, whose lines the positions name)
    Copy,             // copy SRC DST        (replace DST as an editor saves: temporary file, rename)
    Remove,           // remove PATH         (delete a file)
    WaitReload,       // wait-reload         (until a reload started after the previous command has finished)
    WaitLoading,      // wait-loading        (until a load is under way)
    Print,            // print camera|console|error|load|panel|recent|stats|title|tree
    Key,              // key [ctrl+]NAME     (a key pressed in the window: a letter, a digit, escape, f5 or f12)
    Sleep,            // sleep MS
    Quit,             // quit
};

struct Command {
    CommandKind kind;
    SourceLocation where;                // the command word
    std::vector<std::string> words;      // the arguments as written
    std::vector<SourceLocation> wordsAt; // where each argument starts
    std::vector<double> numbers;         // the numeric arguments, checked (camera: its 6 or 7 numbers)

    // "file:line:col: message" at argument `index` (or the command word for -1).
    Error error(const std::string& message, int index = -1) const;
};

// Parses a script's text; `name` is used in messages. Throws strata::Error at
// the first mistake. Paths are kept as written (see resolveScriptPath).
std::vector<Command> parseScript(const std::string& text, const std::string& name);
// Reads and parses the file at `path`.
std::vector<Command> parseScriptFile(const std::string& path);

// A script's relative path means relative to the script's folder.
std::string resolveScriptPath(const std::string& scriptPath, const std::string& path);

}  // namespace strata::view
