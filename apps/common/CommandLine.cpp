#include "CommandLine.h"

#include <CLI/CLI.hpp>

#include <algorithm>

#include "strata/core/Error.h"
#include "strata/render/ColorScheme.h"

namespace strata::apps {
namespace {

// CLI11's messages can span lines; the contract wants one.
std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

}  // namespace

CliOutcome parseCommandLine(CLI::App& app, int argc, char** argv, std::string_view program,
                            const std::function<void()>& check) {
    CliOutcome out;
    try {
        app.parse(argc, argv);
        check();
    } catch (const CLI::CallForHelp&) {
        out.exitNow = true;
        out.message = app.help();
    } catch (const CLI::ParseError& e) {
        out.exitNow = true;
        out.exitCode = 2;
        out.message = std::string(program) + ": " + oneLine(e.what());
    } catch (const UsageError& e) {
        out.exitNow = true;
        out.exitCode = 2;
        out.message = std::string(program) + ": " + e.message;
    }
    return out;
}

std::string checkedColorScheme(const std::string& name) {
    try {
        return render::colorScheme(name).name;
    } catch (const Error& e) {
        throw UsageError{std::string("--colorscheme: ") + e.what()};
    }
}

void addLookOptions(CLI::App& app, LookOptions& look) {
    app.add_option("--light", look.light,
                   "strata (default): Lambert from beside the eye plus ambient; openscad: OpenSCAD's preview light")
        ->type_name("strata|openscad");
    app.add_flag("!--no-outline", look.outline, "no dark outline on creases and silhouettes (OpenSCAD draws none)");
}

render::Lighting checkedLighting(const LookOptions& look) {
    try {
        return render::lightingNamed(look.light);
    } catch (const Error& e) {
        throw UsageError{std::string("--light: ") + e.what()};
    }
}

}  // namespace strata::apps
