#pragma once
// What strata-render and strata-view share of their command lines: how a
// usage mistake is reported (one line, "<program>: <message>", exit status
// 2), help, the --colorscheme check, and the look's options (--light,
// --no-outline). Each app keeps its other options and their messages.

#include <functional>
#include <string>
#include <string_view>

#include "strata/render/ColorScheme.h"

namespace CLI {
class App;
}

namespace strata::apps {

// A usage mistake found after CLI11's own checks; its message names the option.
struct UsageError {
    std::string message;
};

// What parsing decided: run, or stop (help to print, or a bad option's one
// line already formatted).
struct CliOutcome {
    bool exitNow = false;
    int exitCode = 0;
    std::string message;  // help for stdout when exitCode == 0, else one line for stderr
};

// Parses argv (argv[0] ignored) with `app`, then runs `check`, which reads
// the parsed values and throws UsageError for bad ones. Help, CLI11's errors
// and UsageError become the outcome. Never throws.
CliOutcome parseCommandLine(CLI::App& app, int argc, char** argv, std::string_view program,
                            const std::function<void()>& check);

// The canonical name of the OpenSCAD colour scheme `name`; UsageError naming
// --colorscheme when there is none.
std::string checkedColorScheme(const std::string& name);

// How the image is lit and outlined (RenderSettings::lighting, ::outline),
// with the same options and words in every program.
struct LookOptions {
    std::string light = "strata";  // --light strata|openscad
    bool outline = true;           // --no-outline clears it
};
void addLookOptions(CLI::App& app, LookOptions& look);
// The light --light names; UsageError naming --light when it names none.
render::Lighting checkedLighting(const LookOptions& look);

}  // namespace strata::apps
