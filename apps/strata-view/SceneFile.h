#pragma once
// Reading the file strata-view shows: what strata-render accepts (a .csg, or
// one closed .stl/.obj/.off/.ply mesh) plus .scad, converted to CSG by running
// `openscad -o <temporary>.csg file.scad` when openscad is installed.
// CPU only, so it runs on the loader thread.

#include <string>
#include <vector>

#include "strata/geometry/Model.h"
#include "strata/scene/Tree.h"

namespace strata::view {

struct LoadedScene {
    scene::Tree tree;
    geometry::Model model;
    std::vector<std::string> openscadOutput;  // a .scad's ECHO, WARNING, ... lines, as OpenSCAD printed them
};

// Parses and tessellates. Throws strata::Error with strata-render's one-line
// messages ("file:line:col: message") on any bad input.
LoadedScene loadSceneFile(const std::string& path);

}  // namespace strata::view
