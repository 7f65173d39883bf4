// strata-view: the interactive viewer (docs/viewer.md). Thin: options, the
// script checked, the scene loaded, then the window's loop. Everything that
// can be wrong with the input is found before a window opens, and reported as
// strata-render reports it: one line, non-zero status.

#include <iostream>
#include <vector>

#include "Options.h"
#include "SceneFile.h"
#include "Script.h"
#include "Viewer.h"
#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"

int main(int argc, char** argv) {
    using namespace strata;
    io::removeTemporariesOnSignals();
    const view::ParsedOptions parsed = view::parseOptions(argc, argv);
    if (parsed.exitNow) {
        (parsed.exitCode == 0 ? std::cout : std::cerr)
            << parsed.message << (parsed.message.ends_with('\n') ? "" : "\n");
        return parsed.exitCode;
    }
    try {
        std::vector<view::Command> script;
        if (!parsed.options.script.empty()) script = view::parseScriptFile(parsed.options.script);
        view::LoadedScene scene = view::loadSceneFile(parsed.options.scene);
        view::Viewer viewer(parsed.options, std::move(scene));
        return viewer.run(script);
    } catch (const Error& e) {
        std::cerr << e.what() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "strata-view: " << e.what() << '\n';
    }
    return 1;
}
