#pragma once
// The files --export writes, in one table: each format's extension, whether
// it holds a solid (a mesh) or a 2D result (a drawing), and whether it keeps
// per-triangle colours. The writers (MeshWriter, FlatWriter), the command
// lines and strata-view's panel and scripts all read it; it depends on no
// writer, so a reader of names alone (a script's checks) links nothing else.

#include <span>
#include <string>
#include <string_view>

namespace strata::io {

enum class ExportKind { Mesh, Drawing };

struct ExportFormat {
    std::string_view extension;  // lower case, with its dot: ".stl"
    ExportKind kind;
    bool colors;                 // keeps each triangle's colour (3MF)
};

// Every format, meshes first, in the order messages list them.
std::span<const ExportFormat> exportFormats();

// The format `path`'s extension names (any case), or nullptr.
const ExportFormat* exportFormatOf(const std::string& path);

// The extensions of one kind, or of all, as messages list them:
// ".stl, .off, .obj or .3mf", ".svg or .dxf",
// ".stl, .off, .obj, .3mf, .svg or .dxf".
std::string extensionList(ExportKind kind);
std::string extensionList();

}  // namespace strata::io
