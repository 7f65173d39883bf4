#include "SceneFile.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "SceneLoad.h"
#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"
#include "strata/scene/CsgParser.h"

extern char** environ;

namespace strata::view {
namespace {

namespace fs = std::filesystem;

// A private folder under the system's temporary folder, removed with everything in it.
class TempFolder {
public:
    TempFolder() {
        std::string pattern = (fs::temp_directory_path() / "strata-view-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) throw Error("strata-view: cannot create a temporary folder");
        path_ = pattern;
    }
    ~TempFolder() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

// The first executable `name` on PATH; empty when there is none.
std::string findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path != nullptr ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate.string();
    }
    return {};
}

// OpenSCAD's own complaint, as one line: its last "ERROR:" line (or its last
// line), with "line N" turned into our file:line: prefix where it names one.
Error openscadError(const std::string& scad, const std::string& output, int status) {
    std::string last, lastError;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        if (line.empty()) continue;
        last = line;
        if (line.find("ERROR") != std::string::npos) lastError = line;
    }
    std::string message = !lastError.empty() ? lastError : last;
    if (message.empty()) message = "exit status " + std::to_string(status);
    std::smatch m;
    int line = 0;
    if (std::regex_search(message, m, std::regex(R"(line (\d+))"))) line = std::stoi(m[1].str());
    return Error(SourceLocation{scad, line, 0}, "openscad could not export CSG: " + message);
}

// Runs openscad to turn `scad` into CSG at `csg`; its chatter goes to a log file
// so it cannot interleave with ours.
std::vector<std::string> convertScad(const std::string& scad, const std::string& csg, const fs::path& log) {
    const std::string openscad = findOnPath("openscad");
    if (openscad.empty())
        throw Error(SourceLocation{scad, 0, 0},
                    "cannot open .scad: openscad is not installed (not found on PATH); export a .csg from OpenSCAD "
                    "instead");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<std::string> args{openscad, "-o", csg, scad};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, openscad.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw Error(SourceLocation{scad, 0, 0}, "cannot run openscad (" + openscad + ")");
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::ifstream in(log);
    std::ostringstream output;
    output << in.rdbuf();
    if (code != 0 || !fs::exists(csg)) throw openscadError(scad, output.str(), code);
    // What the model printed (echo, warnings), for the viewer's console; not
    // OpenSCAD's own progress chatter.
    std::vector<std::string> printed;
    std::istringstream lines(output.str());
    for (std::string line; std::getline(lines, line);) {
        if (line.starts_with("ECHO:") || line.starts_with("WARNING:") || line.starts_with("ERROR:") ||
            line.starts_with("TRACE:") || line.starts_with("DEPRECATED:")) {
            printed.push_back(line);
        }
    }
    return printed;
}

// As strata-render: a .csg through the parser, a mesh as a tree of one Import
// leaf; a .scad through openscad, whose printed lines go to `printed` and
// whose CSG export goes to `exported`.
scene::Tree readTree(const std::string& path, std::vector<std::string>& printed, std::string& exported) {
    const std::string ext = apps::lowerExtension(path);
    if (ext != ".csg" && ext != ".scad" && !apps::isMeshExtension(ext))
        throw Error(SourceLocation{path, 0, 0},
                    "unknown scene type '" + ext + "' (expected .csg, .scad, .stl, .obj, .off or .ply)");
    apps::checkReadable(path);
    if (ext == ".csg") return scene::parseCsgFile(path);
    if (ext == ".scad") {
        const TempFolder folder;
        const std::string csg = (folder.path() / "scene.csg").string();
        printed = convertScad(path, csg, folder.path() / "openscad.log");
        // Positions are in OpenSCAD's CSG export, not in the .scad: messages
        // say so ("a.scad (CSG export):9:6: ..."). Relative imports resolve
        // from the .scad's folder.
        std::ifstream file(csg, std::ios::binary);
        std::ostringstream text;
        text << file.rdbuf();
        exported = text.str();
        std::istringstream in(exported);
        scene::Tree tree = scene::parseCsg(in, path + " (CSG export)", fs::path(path).parent_path().string());
        tree.source = path;
        return tree;
    }
    return scene::meshFileTree(path);
}

}  // namespace

LoadedScene loadSceneFile(const std::string& path) {
    LoadedScene scene;
    scene.tree = readTree(path, scene.openscadOutput, scene.csgExport);
    scene.model = geometry::buildModel(scene.tree);
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
    if (apps::lowerExtension(target) != ".csg")
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
