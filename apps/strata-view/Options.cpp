#include "Options.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <string>
#include <string_view>

#include "CommandLine.h"
#include "Script.h"
#include "strata/render/Limits.h"

namespace strata::view {
namespace {

bool parseWhole(std::string_view text, int& out) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

ParsedOptions parseOptions(int argc, char** argv) {
    ParsedOptions result;
    ViewerOptions& o = result.options;
    CLI::App app{"strata-view: interactive viewer of strata's image-space CSG rendering (see docs/viewer.md)",
                 "strata-view"};
    app.option_defaults()->always_capture_default(false);
    std::string imgsize, layers;
    app.add_option("SCENE", o.scene, "a .csg file, a .scad file (needs openscad), or one closed .stl/.obj/.off/.ply mesh")
        ->required();
    app.add_option("--script", o.script, "run the commands of FILE, then quit (docs/viewer.md)")->type_name("FILE");
    app.add_option("--imgsize", imgsize, "window size in pixels (default 1024,768)")->type_name("W,H");
    app.add_option("--layers", layers, "depth-peel layers per operand, or auto (default)")->type_name("N|auto");
    app.add_option("--colorscheme", o.colorScheme, "OpenSCAD colour scheme (default Cornfield)")->type_name("NAME");
    apps::LookOptions look;
    apps::addLookOptions(app, look);
    static_cast<apps::CliOutcome&>(result) = apps::parseCommandLine(app, argc, argv, "strata-view", [&] {
        if (app.count("--imgsize")) {
            const std::size_t comma = imgsize.find(',');
            if (comma == std::string::npos || !parseWhole(std::string_view(imgsize).substr(0, comma), o.width) ||
                !parseWhole(std::string_view(imgsize).substr(comma + 1), o.height) || o.width <= 0 ||
                o.height <= 0 || o.width > render::kMaxImageSide || o.height > render::kMaxImageSide)
                throw apps::UsageError{"--imgsize: expected W,H (two whole numbers from 1 to " +
                                       std::to_string(render::kMaxImageSide) + "), got '" + imgsize + "'"};
        }
        if (app.count("--layers") && layers != "auto") {
            if (!parseWhole(layers, o.layers) || o.layers < 1 || o.layers > render::kMaxLayers)
                throw apps::UsageError{"--layers: expected 'auto' or a whole number from 1 to " +
                                       std::to_string(render::kMaxLayers) + ", got '" + layers + "'"};
        }
        if (app.count("--colorscheme")) o.colorScheme = apps::checkedColorScheme(o.colorScheme);
        o.lighting = apps::checkedLighting(look);
        o.outline = look.outline;
    });
    return result;
}

}  // namespace strata::view
