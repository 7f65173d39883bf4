#pragma once
// A scene file as the programs take it: OpenSCAD's .csg export through the
// parser, a .scad through the installed openscad's CSG export (ScadExport.h),
// or one closed mesh (.stl, .obj, .off, .ply) as a tree of a single Import
// leaf. strata-render, strata-bench, strata-view and an embedding host load
// their scenes through it, so all accept and refuse the same files with the
// same messages.

#include <string>
#include <vector>

#include "strata/core/InputFile.h"
#include "strata/scene/Tree.h"

namespace strata::scene {

// A scene file read, with what a .scad brings besides its tree.
struct SceneFile {
    scene::Tree tree;
    std::vector<std::string> openscadOutput;  // a .scad's ECHO, WARNING, ... lines, as OpenSCAD printed them
    // A .scad's CSG export as OpenSCAD wrote it, the text whose lines the
    // tree's positions name; empty for a .csg or a mesh.
    std::string csgExport;
    // A .scad's dependencies (ScadExport::dependencies: itself, its use and
    // include files, its imports); empty for a .csg or a mesh.
    std::vector<std::string> dependencies;
};

// Reads `path`; a .scad with each of `defines` ("name=value") given to
// openscad as -D. Throws strata::Error naming the file (and the line and
// column for a parse error) for an unknown extension, a missing or
// unreadable file, a directory, or a .scad openscad cannot export.
SceneFile readSceneFile(const std::string& path, const std::vector<std::string>& defines = {});

// readSceneFile's tree alone.
scene::Tree loadSceneFile(const std::string& path, const std::vector<std::string>& defines = {});

// Whether an extension in lower case (strata::lowerExtension,
// strata/core/InputFile.h) names a scene file: .csg, .scad or a mesh format.
bool isSceneExtension(const std::string& ext);

}  // namespace strata::scene
