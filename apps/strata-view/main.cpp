// strata-view: the interactive viewer (docs/viewer.md). Thin: options, the
// script checked, the scene loaded, then the window's loop. What can be wrong
// with the input is found before a window opens, and reported as
// strata-render reports it: one line, non-zero status; only a scene whose
// load takes longer than kWindowAfter opens the window first, showing the
// load's progress (its errors are then the window's).

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <vector>

#include "Loader.h"
#include "Options.h"
#include "SceneFile.h"
#include "Script.h"
#include "Viewer.h"
#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"

namespace {

// A scene that takes longer than this to load opens the window first.
constexpr std::chrono::milliseconds kWindowAfter{700};

}  // namespace

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
        // A script, or no display to open a window on, waits for the scene
        // as long as it takes.
        const bool display = std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
        const bool early = script.empty() && display;
        view::Loader loader(view::Viewer::wakeWindow);
        loader.request(parsed.options.scene);
        std::optional<view::LoadResult> first = loader.waitFor(kWindowAfter);
        while (!early && !first) first = loader.waitFor(std::chrono::seconds(1));
        if (first && !first->scene) throw Error(first->error);
        view::Viewer viewer(parsed.options, first ? std::move(*first->scene) : view::LoadedScene{},
                            first ? nullptr : &loader);
        return viewer.run(script);
    } catch (const Error& e) {
        std::cerr << e.what() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "strata-view: " << e.what() << '\n';
    }
    return 1;
}
