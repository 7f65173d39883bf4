#pragma once
// The files strata reads besides its scenes, in one table: the meshes that
// import() reads and that a scene may be on its own, and the drawings that
// import() reads into 2D. The parser, the mesh and drawing readers
// (strata/geometry/MeshImport.h, FlatImport.h) and the programs' scene
// loading all read it.

#include <span>
#include <string>
#include <string_view>

namespace strata::scene {

enum class ImportKind { Mesh, Drawing };

struct ImportFormat {
    std::string_view extension;  // lower case, with its dot: ".stl"
    ImportKind kind;
};

// Every format, meshes first, in the order messages list them.
std::span<const ImportFormat> importFormats();

// Whether `path`'s extension (any case) names a format of `kind`; the
// same of an extension already in lower case, with its dot.
bool isImportPath(const std::string& path, ImportKind kind);
bool isImportExtension(std::string_view extension, ImportKind kind);

// The extensions of one kind as messages list them: ".stl, .off, .obj or
// .ply", ".dxf or .svg"; `first` (".csg, .scad") put before them.
std::string importExtensionList(ImportKind kind, std::string_view first = {});

}  // namespace strata::scene
