#include "strata/scene/ScadExport.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "strata/core/Error.h"

extern char** environ;

namespace strata::scene {
namespace {

namespace fs = std::filesystem;

// A private folder under the system's temporary folder, removed with everything in it.
class TempFolder {
public:
    explicit TempFolder(const std::string& scad) {
        std::string pattern = (fs::temp_directory_path() / "strata-scad-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw Error(SourceLocation{scad, 0, 0}, "cannot create a temporary folder for openscad's CSG export");
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

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// OpenSCAD parses each -D as a line of its own after the .scad's text and
// one separating line, so a line past the .scad's own names a -D: the first
// on the .scad's newline count + 3. The -D it names, or null.
const std::string* defineOnLine(const std::string& scad, int line, const std::vector<std::string>& defines) {
    const std::string text = readText(scad);
    const long first = std::count(text.begin(), text.end(), '\n') + 3;
    const long index = line - first;
    return index >= 0 && index < static_cast<long>(defines.size()) ? &defines[static_cast<std::size_t>(index)]
                                                                   : nullptr;
}

// OpenSCAD's own complaint, as one line: its last "ERROR:" line (or its last
// line), with "line N" turned into our file:line: prefix where it names one
// of the .scad's lines, or the -D where it names one of theirs.
Error openscadError(const std::string& scad, const std::vector<std::string>& defines, const std::string& output,
                    int status) {
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
    if (line > 0 && !defines.empty()) {
        if (const std::string* define = defineOnLine(scad, line, defines))
            return Error(SourceLocation{scad, 0, 0}, "openscad could not export CSG: in -D " + *define + ": " + message);
    }
    return Error(SourceLocation{scad, line, 0}, "openscad could not export CSG: " + message);
}

// Runs `args` (args[0] the program) with stdin from /dev/null and stdout and
// stderr into `log`, so its chatter cannot interleave with ours; its exit
// status, or 128 + the signal that ended it.
int runLogged(const std::string& scad, std::vector<std::string> args, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw Error(SourceLocation{scad, 0, 0}, "cannot run openscad (" + args[0] + ")");
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// What the model printed (echo, warnings): not OpenSCAD's own progress chatter.
std::vector<std::string> printedLines(const std::string& output) {
    std::vector<std::string> printed;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        if (line.starts_with("ECHO:") || line.starts_with("WARNING:") || line.starts_with("ERROR:") ||
            line.starts_with("TRACE:") || line.starts_with("DEPRECATED:")) {
            printed.push_back(line);
        }
    }
    return printed;
}

}  // namespace

std::vector<std::string> makeRuleFiles(const std::string& rule) {
    std::vector<std::string> files;
    std::size_t i = 0;
    // The target, up to its colon (a colon escaped in a name does not end it).
    for (; i < rule.size() && rule[i] != ':'; ++i)
        if (rule[i] == '\\') ++i;
    std::string word;
    auto end = [&] {
        if (!word.empty()) files.push_back(word);
        word.clear();
    };
    for (++i; i < rule.size(); ++i) {
        const char c = rule[i];
        if (c == '\\' && i + 1 < rule.size()) {
            const char next = rule[++i];
            if (next == '\n' || next == '\r') {
                end();
            } else {
                word += next;
            }
        } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            end();
        } else {
            word += c;
        }
    }
    end();
    return files;
}

ScadExport exportScad(const std::string& scad, const std::vector<std::string>& defines) {
    const std::string openscad = findOnPath("openscad");
    if (openscad.empty())
        throw Error(SourceLocation{scad, 0, 0},
                    "cannot open .scad: openscad is not installed (not found on PATH); export a .csg from OpenSCAD "
                    "instead");
    const TempFolder folder(scad);
    const fs::path csg = folder.path() / "scene.csg";
    const fs::path log = folder.path() / "openscad.log";
    const fs::path rule = folder.path() / "scene.d";
    std::vector<std::string> args{openscad, "-o", csg.string(), "-d", rule.string()};
    for (const std::string& define : defines) {
        args.push_back("-D");
        args.push_back(define);
    }
    args.push_back(scad);
    const int code = runLogged(scad, std::move(args), log);
    const std::string output = readText(log);
    if (code != 0 || !fs::exists(csg)) throw openscadError(scad, defines, output, code);
    ScadExport exported{readText(csg), printedLines(output), {}};
    std::error_code ec;
    for (const std::string& file : makeRuleFiles(readText(rule))) {
        const fs::path absolute = fs::absolute(file, ec);
        exported.dependencies.push_back(ec ? file : absolute.lexically_normal().string());
    }
    return exported;
}

}  // namespace strata::scene
