#include "strata/flat/FlatImport.h"

#include <filesystem>
#include <string>

#include "FlatImportDetail.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/scene/ImportFormats.h"

// import() of a 2D file, dispatched on the file name's extension (compared in
// lower case) as OpenSCAD 2021.01's ImportModule does: .dxf (FlatImportDxf.cpp)
// or .svg (FlatImportSvg.cpp).

namespace strata::flat {
namespace detail {

std::string quotedPath(std::string_view path) {
    std::string quoted;
    quoted.reserve(path.size() + 2);
    quoted += '\'';
    quoted += path;
    quoted += '\'';
    return quoted;
}

}  // namespace detail

Outlines importFlat(const scene::FlatImport& import) {
    if (!scene::isImportPath(import.path, scene::ImportKind::Drawing)) {
        throw Error("import: " + detail::quotedPath(import.path) + " is not a 2D file (" +
                    scene::importExtensionList(scene::ImportKind::Drawing) + ")");
    }
    const std::string ext = lowerExtension(import.path);
    const std::string text = readInputFile(import.path, "import");
    return ext == ".dxf" ? detail::importDxf(import, text) : detail::importSvg(import, text);
}

}  // namespace strata::flat
