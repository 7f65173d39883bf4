#pragma once
// Where the nodes of OpenSCAD's CSG export of a .scad were written in the
// .scad. The export carries no positions, so the sources are read for the
// calls that can have made each node: a node traces back to a call when it is
// the only call of that name in the .scad and the .scad files it uses or
// includes (any number of nodes may come from it: a loop, a module called
// twice), or the only one of them whose string arguments hold the node's
// file name (import, surface) or text (text). Anything else (a node whose
// name no source writes, as multmatrix for translate; a name called in two
// places) keeps its position in the export.

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "strata/core/Error.h"

namespace strata::scene {

class ScadTrace {
public:
    struct Source {
        std::string name;  // as messages should name it
        std::string text;
    };

    // `csg`: the export's text; `sources`: the .scad first, then the files it
    // uses or includes.
    ScadTrace(std::string csg, const std::vector<Source>& sources);

    // The call in the sources that made the node starting on line `line` of
    // the export (1-based), where only one can have; nothing otherwise.
    std::optional<SourceLocation> locate(int line) const;

    // How many nodes of the export trace back to a call (for tests and docs).
    int tracedLines() const;

private:
    struct Call {
        SourceLocation where;
        std::vector<std::string> strings;  // the string literals among its own arguments
    };
    std::string csg_;
    std::vector<std::size_t> lineStarts_;
    std::unordered_map<std::string, std::vector<Call>> calls_;
};

}  // namespace strata::scene
