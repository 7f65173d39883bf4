#include "strata/scene/SceneLoad.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "strata/scene/ScadExport.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/scene/CsgParser.h"
#include "strata/scene/ImportFormats.h"
#include "strata/scene/ScadTrace.h"

namespace strata::scene {

bool isSceneExtension(const std::string& ext) {
    return ext == ".csg" || ext == ".scad" || isImportExtension(ext, ImportKind::Mesh);
}

namespace {

namespace fs = std::filesystem;

// A source's text, or nothing when it is not a plain file of at most 16 MiB
// (the trace then does without it).
std::optional<std::string> sourceText(const std::string& path) {
    try {
        return readInputFile(path, "use", 16);
    } catch (const Error&) {
        return std::nullopt;
    }
}

// How messages name a file the .scad `main` uses or includes: beside or below
// the .scad's folder, through that folder as the user wrote it; else whole.
std::string sourceName(const std::string& dependency, const std::string& main) {
    std::error_code ec;
    const fs::path folder = fs::path(main).parent_path();
    const fs::path relative = fs::proximate(dependency, fs::absolute(folder.empty() ? fs::path(".") : folder, ec), ec);
    if (ec || relative.empty() || *relative.begin() == "..") return dependency;
    return folder.empty() ? relative.string() : (folder / relative).string();
}

// The .scad's positions for the nodes of its export (ScadTrace): the .scad
// and the .scad files it uses and includes, as openscad -d listed them.
std::shared_ptr<const scene::ScadTrace> scadTrace(const std::string& path, const ScadExport& exported) {
    std::vector<scene::ScadTrace::Source> sources;
    if (std::optional<std::string> text = sourceText(path)) sources.push_back({path, std::move(*text)});
    std::error_code ec;
    for (const std::string& dependency : exported.dependencies) {
        if (lowerExtension(dependency) != ".scad" || fs::equivalent(dependency, path, ec)) continue;
        if (std::optional<std::string> text = sourceText(dependency))
            sources.push_back({sourceName(dependency, path), std::move(*text)});
    }
    return std::make_shared<const scene::ScadTrace>(exported.csg, sources);
}

}  // namespace

SceneFile readSceneFile(const std::string& path, const std::vector<std::string>& defines) {
    const std::string ext = lowerExtension(path);
    if (!isSceneExtension(ext))
        throw Error(SourceLocation{path, 0, 0},
                    "unknown scene type '" + ext + "' (expected " +
                        scene::importExtensionList(scene::ImportKind::Mesh, ".csg, .scad") + ")");
    requireReadable(path);
    SceneFile file;
    if (ext == ".csg") {
        file.tree = scene::parseCsgFile(path);
    } else if (ext == ".scad") {
        ScadExport exported = exportScad(path, defines);
        // A node that traces back to one call in the .scad's sources is
        // positioned there; any other keeps its line in OpenSCAD's CSG
        // export, and messages say so ("a.scad (CSG export):9:6: ...").
        // Relative imports resolve from the .scad's folder.
        scene::ParseOptions options;
        options.locate = [trace = scadTrace(path, exported)](int line) { return trace->locate(line); };
        std::istringstream in(exported.csg);
        file.tree = scene::parseCsg(in, path + " (CSG export)", std::filesystem::path(path).parent_path().string(), options);
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

}  // namespace strata::scene
