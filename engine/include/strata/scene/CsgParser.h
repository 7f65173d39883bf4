#pragma once
// Reader for OpenSCAD's CSG export (`openscad -o x.csg x.scad`), the 2021.01
// dialect and the newer one. Streams its input: memory grows with the tree, not
// with the size of the text.

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

#include "strata/scene/Tree.h"

namespace strata::scene {

struct ParseOptions {
    // $fn above this is clamped (with a warning), so a sphere of $fn=1e9 cannot
    // eat the machine.
    double maxFragments = 1024.0;
    // Blocks ({ ... } or a single child statement) open inside one another;
    // one more is refused. The parser keeps them on the heap.
    int maxNesting = 1000000;
    // hull, minkowski, resize, projection, linear_extrude and rotate_extrude
    // nodes (and 2D shapes among solids) open inside one another; one more
    // is refused. Each reads its children into a shape of its own, which
    // building the model walks on the C++ stack, about 2 KiB a level.
    int maxNestedShapes = 1000;
    // Where messages and positions about the node on a line of the input
    // should point instead (a .scad's own lines, from ScadTrace), or nothing
    // to keep the input's line and column.
    std::function<std::optional<SourceLocation>(int line)> locate;
};

// Parses the file at `path`. Throws strata::Error("path:line:col: message") on
// any malformed input. Unsupported nodes become warnings in Tree::warnings.
Tree parseCsgFile(const std::string& path, const ParseOptions& options = {});

// Parses text from a stream; `name` is used in messages and `baseDir` resolves
// relative import() paths.
Tree parseCsg(std::istream& in, const std::string& name, const std::string& baseDir,
              const ParseOptions& options = {});

}  // namespace strata::scene
