#pragma once
// A scene file as the programs take it: OpenSCAD's .csg export through the
// parser, or one closed mesh (.stl, .obj, .off, .ply) as a tree of a single
// Import leaf. strata-render and strata-bench load their scenes through it,
// so both accept and refuse the same files with the same messages.

#include <string>

#include "strata/scene/Tree.h"

namespace strata::apps {

// Throws strata::Error naming the file (and the line and column for a
// parse error) for an unknown extension, a missing or unreadable file, or a
// directory.
scene::Tree loadSceneFile(const std::string& path);

// Its parts, for a program that takes more kinds of file (strata-view's
// .scad): the extension, dot included, in lower case ("model.STL" -> ".stl");
// whether it names a mesh format; and a throw, naming the file, unless
// `path` is a file that can be opened.
std::string lowerExtension(const std::string& path);
bool isMeshExtension(const std::string& ext);
void checkReadable(const std::string& path);

}  // namespace strata::apps
