#include "OpenscadOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <regex>

#include "CommandLine.h"
#include "strata/core/InputFile.h"

namespace strata::apps {
namespace {

// One of OpenSCAD's options that strata-render refuses, and why.
struct Refused {
    const char* name;    // as CLI11 takes it: "-d", "--animate"
    bool takesValue;     // OpenSCAD's takes one (kept off SCENE, so the refusal is the line said)
    const char* reason;
};

const char* const kOnlyDefines = "strata-render gives openscad only -D";

const Refused kRefused[] = {
    {"--export-format", true, "strata-render picks --export's format from the file name (.stl, .off, .obj, .3mf, .svg, .dxf)"},
    {"--animate", true, "strata-render renders one frame; for an animation run it once a frame with -D '$t=...'"},
    {"--view", true, "strata-render draws no axes, crosshairs, edges, scales or wireframe"},
    {"--csglimit", true, "strata-render has no limit on the number of CSG elements"},
    {"-p", true, kOnlyDefines},
    {"-P", true, kOnlyDefines},
    {"--check-parameters", true, kOnlyDefines},
    {"--check-parameter-ranges", true, kOnlyDefines},
    {"--hardwarnings", false, "strata-render does not stop at a warning; it prints them once its outputs are written"},
    {"-d", true, "strata-render writes no dependency file"},
    {"-m", true, "strata-render runs no make command"},
    {"--debug", true, "strata-render has no debug output"},
    {"-s", true, "OpenSCAD's old STL export: use --export FILE.stl"},
    {"-x", true, "OpenSCAD's old DXF export: use --export FILE.dxf"},
    {"--render", false,
     "strata-render draws OpenSCAD's preview, not CGAL's render; for CGAL's exact result as a mesh use --export "
     "FILE"},
};

// A definition as openscad takes it: a name (a $ may lead), '=', a value.
bool isDefinition(const std::string& text) {
    static const std::regex form(R"(\s*\$?[A-Za-z0-9_]+\s*=[\s\S]*\S[\s\S]*)");
    return std::regex_match(text, form);
}

}  // namespace

void addDefineOption(CLI::App& app, std::vector<std::string>& defines) {
    // One value each time: `-D a=1 model.scad` leaves model.scad to SCENE.
    app.add_option("-D", defines, "define a .scad's variable, as OpenSCAD's -D (repeatable; a .scad scene only)")
        ->type_name("NAME=VALUE")
        ->allow_extra_args(false);
}

void checkDefines(const std::vector<std::string>& defines, const std::vector<std::string>& scenes) {
    if (defines.empty()) return;
    for (const std::string& define : defines)
        if (!isDefinition(define)) throw UsageError{"-D: expected NAME=VALUE, got '" + define + "'"};
    const bool anyScad =
        std::any_of(scenes.begin(), scenes.end(), [](const std::string& s) { return lowerExtension(s) == ".scad"; });
    if (!anyScad) {
        const std::string given = scenes.size() == 1 ? " (the scene is '" + scenes[0] + "')" : "";
        throw UsageError{"-D: only a .scad scene takes definitions" + given};
    }
}

void addOpenscadOptions(CLI::App& app) {
    app.add_flag("--viewall")->description("as OpenSCAD: fit the view to the scene (the default view does)");
    app.add_flag("--autocenter")->description("as OpenSCAD: centre the view on the scene (the default view does)");
    // A flag, so that a bare --preview never takes SCENE as its value;
    // --preview=throwntogether still reaches checkOpenscadOptions.
    app.add_flag("--preview")->description("as OpenSCAD: draw the preview (strata-render always does)");
    for (const Refused& r : kRefused) {
        CLI::Option* option = r.takesValue ? app.add_option_function<std::string>(r.name, [](const std::string&) {})
                                           : app.add_flag(r.name);
        option->group("");  // not in the help
    }
}

void checkOpenscadOptions(const CLI::App& app, bool cameraGiven) {
    for (const Refused& r : kRefused)
        if (app.count(r.name) != 0) throw UsageError{std::string(r.name) + ": " + r.reason};
    for (const std::string& value : app.get_option("--preview")->results())
        if (value == "throwntogether")
            throw UsageError{"--preview=throwntogether: strata-render draws the CSG result only, not the thrown-together view"};
    for (const char* fit : {"--viewall", "--autocenter"})
        if (app.count(fit) != 0 && cameraGiven)
            throw UsageError{std::string(fit) +
                             " with --camera: strata-render does not refit a given camera; without --camera it draws "
                             "OpenSCAD's --viewall --autocenter view"};
}

}  // namespace strata::apps
