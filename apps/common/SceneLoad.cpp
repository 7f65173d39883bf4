#include "SceneLoad.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

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

scene::Tree loadSceneFile(const std::string& path) {
    const std::string ext = lowerExtension(path);
    const bool isMesh = isMeshExtension(ext);
    if (ext != ".csg" && !isMesh)
        throw Error(SourceLocation{path, 0, 0}, "unknown scene type '" + ext +
                                                    "' (expected .csg, .stl, .obj, .off or .ply)");
    checkReadable(path);
    if (!isMesh) return scene::parseCsgFile(path);
    return scene::meshFileTree(path);
}

}  // namespace strata::apps
