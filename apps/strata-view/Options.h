#pragma once
// strata-view's command line. Options shared with strata-render keep its
// names and value formats (docs/contract.md).

#include <string>

#include "Viewer.h"

namespace strata::view {

struct ParsedOptions {
    ViewerOptions options;
    bool exitNow = false;
    int exitCode = 0;
    std::string message;  // help for stdout when exitCode == 0, else one line for stderr
};

// argv[0] is ignored. Never throws.
ParsedOptions parseOptions(int argc, char** argv);

}  // namespace strata::view
