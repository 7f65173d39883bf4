#pragma once
// A .scad turned into OpenSCAD's CSG export by the installed `openscad`
// (`openscad -o <temporary>.csg [-D name=value ...] file.scad`), for the
// programs that take a .scad as their scene. strata reads the export, never
// the .scad itself.

#include <string>
#include <vector>

namespace strata::scene {

struct ScadExport {
    std::string csg;                   // the CSG export, as OpenSCAD wrote it
    std::vector<std::string> printed;  // the model's ECHO, WARNING, ... lines, as OpenSCAD printed them
    // Every file the export read: the .scad, the files it uses and
    // includes, and those it imports (openscad's -d list), as absolute paths.
    std::vector<std::string> dependencies;
};

// The files of a make rule as openscad -d writes it ("out.csg: a.scad
// lib/b\ c.scad ..." over lines continued by a backslash): the words after
// the first colon, with "\ " read as a space.
std::vector<std::string> makeRuleFiles(const std::string& rule);

// Runs openscad on `scad` with each of `defines` ("name=value") given to it
// as `-D name=value`, in order. Throws strata::Error naming the .scad, in one
// line, when openscad is not on PATH, cannot be run, or fails (with its own
// complaint and, where it names one, the line).
ScadExport exportScad(const std::string& scad, const std::vector<std::string>& defines = {});

}  // namespace strata::scene
