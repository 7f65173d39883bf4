#include "SceneLoad.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "ScadExport.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/scene/CsgParser.h"

namespace strata::apps {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool isMeshExtension(const std::string& ext) { return ext == ".stl" || ext == ".obj" || ext == ".off" || ext == ".ply"; }

void checkReadable(const std::string& path) {
    const std::string why = unreadableReason(path);
    if (!why.empty()) throw Error(SourceLocation{path, 0, 0}, "cannot read (" + why + ")");
}

SceneFile readSceneFile(const std::string& path, const std::vector<std::string>& defines) {
    const std::string ext = lowerExtension(path);
    if (ext != ".csg" && ext != ".scad" && !isMeshExtension(ext))
        throw Error(SourceLocation{path, 0, 0},
                    "unknown scene type '" + ext + "' (expected .csg, .scad, .stl, .obj, .off or .ply)");
    checkReadable(path);
    SceneFile file;
    if (ext == ".csg") {
        file.tree = scene::parseCsgFile(path);
    } else if (ext == ".scad") {
        ScadExport exported = exportScad(path, defines);
        // Positions are in OpenSCAD's CSG export, not in the .scad: messages
        // say so ("a.scad (CSG export):9:6: ..."). Relative imports resolve
        // from the .scad's folder.
        std::istringstream in(exported.csg);
        file.tree = scene::parseCsg(in, path + " (CSG export)", std::filesystem::path(path).parent_path().string());
        file.tree.source = path;
        file.openscadOutput = std::move(exported.printed);
        file.csgExport = std::move(exported.csg);
        file.dependencies = std::move(exported.dependencies);
    } else {
        file.tree = scene::meshFileTree(path);
    }
    return file;
}

scene::Tree loadSceneFile(const std::string& path, const std::vector<std::string>& defines) {
    return readSceneFile(path, defines).tree;
}

}  // namespace strata::apps
