#pragma once
// OpenSCAD's own command-line options as strata's programs take them: -D
// for a .scad scene (strata-render and strata-bench), and for strata-render,
// which follows OpenSCAD's PNG export, the rest of OpenSCAD's options: those
// that mean what strata-render does anyway (--viewall, --autocenter,
// --preview) accepted, each of the others refused with one line saying why.
// Options strata-render has of its own (--imgsize, --camera, --projection,
// --colorscheme) stay in its Options.

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::apps {

// -D name=value, repeatable: definitions given to openscad in order.
void addDefineOption(CLI::App& app, std::vector<std::string>& defines);

// UsageError, naming -D, for a definition that is not name=value, or for
// definitions when none of `scenes` is a .scad.
void checkDefines(const std::vector<std::string>& defines, const std::vector<std::string>& scenes);

// OpenSCAD's options strata-render does not add itself: the accepted ones
// in its help, the refused ones hidden.
void addOpenscadOptions(CLI::App& app);

// UsageError for a refused OpenSCAD option given, naming it and saying why;
// `cameraGiven`: whether --camera was (strata-render does not refit a given
// camera, as --viewall and --autocenter would).
void checkOpenscadOptions(const CLI::App& app, bool cameraGiven);

}  // namespace strata::apps
