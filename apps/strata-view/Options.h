#pragma once
// strata-view's command line. Options shared with strata-render keep its
// names and value formats (docs/contract.md).

#include <string>

#include "CommandLine.h"
#include "Viewer.h"

namespace strata::view {

// What parsing decided: run with the options, or stop (apps::CliOutcome).
struct ParsedOptions : apps::CliOutcome {
    ViewerOptions options;
};

// argv[0] is ignored. Never throws.
ParsedOptions parseOptions(int argc, char** argv);

}  // namespace strata::view
