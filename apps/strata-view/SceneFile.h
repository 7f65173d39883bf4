#pragma once
// Reading the file strata-view shows: what strata-render accepts (a .csg, a
// .scad through the installed openscad, or one closed .stl/.obj/.off/.ply
// mesh; strata/scene/SceneLoad.h), meshed, with a .scad's CSG export kept for
// saving. CPU only, so it runs on the loader thread.

#include <string>
#include <vector>

#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::view {

struct LoadedScene {
    scene::Tree tree;
    model::Model model;
    std::vector<std::string> openscadOutput;  // a .scad's ECHO, WARNING, ... lines, as OpenSCAD printed them
    // A .scad's CSG export as OpenSCAD wrote it, the text whose lines the
    // tree's positions name; empty for a .csg or a mesh.
    std::string csgExport;
    // The files besides the scene's own that a reload must follow: a
    // .scad's use and include files and imports (scene::SceneFile).
    std::vector<std::string> dependencies;
};

// Parses and tessellates. Throws strata::Error with strata-render's one-line
// messages ("file:line:col: message") on any bad input.
LoadedScene loadSceneFile(const std::string& path);

// Where the panel offers to save a .scad's CSG export: beside it, its stem with .csg.
std::string defaultCsgExportPath(const std::string& scadPath);

// Writes `scene`'s CSG export (loaded from `scenePath`) to `target`, as
// strata's other outputs are written: complete or not at all. Throws
// strata::Error with one line when the scene has no export (not a .scad),
// `target` is not a .csg name or is the .scad itself, or the write fails.
void saveCsgExport(const LoadedScene& scene, const std::string& scenePath, const std::string& target);

}  // namespace strata::view
