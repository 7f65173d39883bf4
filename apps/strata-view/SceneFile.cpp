#include "SceneFile.h"

#include <filesystem>
#include <utility>
#include <vector>

#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/io/ImageWriter.h"
#include "strata/scene/SceneLoad.h"

namespace strata::view {

namespace fs = std::filesystem;

LoadedScene loadSceneFile(const std::string& path) {
    LoadedScene scene;
    scene::SceneFile file = scene::readSceneFile(path);
    scene.tree = std::move(file.tree);
    scene.openscadOutput = std::move(file.openscadOutput);
    scene.csgExport = std::move(file.csgExport);
    scene.dependencies = std::move(file.dependencies);
    scene.model = model::buildModel(scene.tree);
    // What the model forgave (an inside-out polyhedron) is shown with the reader's warnings.
    scene.tree.warnings.insert(scene.tree.warnings.end(), scene.model.warnings.begin(), scene.model.warnings.end());
    return scene;
}

std::string defaultCsgExportPath(const std::string& scadPath) {
    return fs::path(scadPath).replace_extension(".csg").string();
}

void saveCsgExport(const LoadedScene& scene, const std::string& scenePath, const std::string& target) {
    if (scene.csgExport.empty())
        throw Error("cannot save a CSG export: " + scenePath + " is not a .scad, its positions are its own lines");
    if (lowerExtension(target) != ".csg")
        throw Error("cannot save the CSG export to '" + target + "': expected a .csg file name");
    // The .csg name keeps it off the .scad; a name that leads to the .scad
    // all the same (a link) is refused too.
    std::error_code ec;
    if (fs::equivalent(target, scenePath, ec))
        throw Error("cannot save the CSG export to '" + target + "': that is the .scad itself");
    io::StagedFile file = io::StagedFile::write(
        target, "CSG export", std::vector<unsigned char>(scene.csgExport.begin(), scene.csgExport.end()));
    file.commit();
}

}  // namespace strata::view
