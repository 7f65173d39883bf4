#include "strata/gpu/ShaderSource.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

#include "strata/core/Error.h"

namespace strata::gpu {
namespace detail {
struct EmbeddedEntry {
    std::string_view path;
    std::string_view text;
};
// Defined in the generated EmbeddedShaders.cpp (engine/gpu/EmbedShaders.cmake), sorted by path.
extern const EmbeddedEntry* const kEmbeddedShaders;
extern const std::size_t kEmbeddedShaderCount;
}  // namespace detail

namespace {

constexpr int kMaxIncludeDepth = 16;

const detail::EmbeddedEntry* findEntry(std::string_view path) {
    const detail::EmbeddedEntry* begin = detail::kEmbeddedShaders;
    const detail::EmbeddedEntry* end = begin + detail::kEmbeddedShaderCount;
    if (begin == nullptr) return nullptr;
    auto it = std::lower_bound(begin, end, path,
                               [](const detail::EmbeddedEntry& e, std::string_view p) { return e.path < p; });
    return it != end && it->path == path ? it : nullptr;
}

// STRATA_SHADER_DIR, when set, names a folder laid out like shaders/ whose
// files replace the embedded ones of the same path: edit a shader and rerun,
// with no rebuild. Texts read are kept for the life of the process, so the
// views handed out stay valid.
std::string_view overrideText(std::string_view path) {
    static const char* dir = std::getenv("STRATA_SHADER_DIR");
    if (dir == nullptr || *dir == 0) return {};
    static std::mutex mutex;
    static std::map<std::string, std::string, std::less<>> texts;
    const std::lock_guard lock(mutex);
    auto it = texts.find(path);
    if (it == texts.end()) {
        std::ifstream in(std::string(dir) + "/" + std::string(path), std::ios::binary);
        std::ostringstream text;
        if (in) text << in.rdbuf();
        it = texts.emplace(std::string(path), in ? text.str() : std::string()).first;
    }
    return it->second;
}

// The text of `path`: STRATA_SHADER_DIR's copy where there is one, else the
// embedded one; empty when neither exists.
std::string_view sourceText(std::string_view path) {
    const std::string_view text = overrideText(path);
    if (!text.empty()) return text;
    const detail::EmbeddedEntry* entry = findEntry(path);
    return entry == nullptr ? std::string_view{} : entry->text;
}

// `#include "x"` with only blanks around it (a trailing // comment is allowed).
// Returns the quoted path, or an empty view when the line is not an include.
std::string_view includeTarget(std::string_view line) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || line[i] != '#') return {};
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos || line.substr(i, 7) != "include") return {};
    i = line.find_first_not_of(" \t", i + 7);
    if (i == std::string_view::npos || line[i] != '"') return {};
    const std::size_t close = line.find('"', i + 1);
    if (close == std::string_view::npos) return {};
    return line.substr(i + 1, close - i - 1);
}

struct Assembler {
    std::string text;
    std::vector<std::string> sourceNames;
    std::vector<std::string> included;  // each file once per stage

    // Appends `source` (GLSL source-string number `number`), expanding includes.
    void append(std::string_view name, std::string_view source, int number, int depth) {
        int lineNumber = 0;
        std::size_t pos = 0;
        while (pos < source.size()) {
            std::size_t end = source.find('\n', pos);
            if (end == std::string_view::npos) end = source.size();
            const std::string_view line = source.substr(pos, end - pos);
            pos = end + 1;
            ++lineNumber;

            const std::string_view target = includeTarget(line);
            if (target.empty()) {
                text.append(line);
                text.push_back('\n');
                continue;
            }
            const SourceLocation here{"shaders/" + std::string(name), lineNumber, 0};
            if (depth >= kMaxIncludeDepth) throw Error(here, "#include nested too deeply");
            const std::string_view includedText = sourceText(target);
            if (includedText.empty())
                throw Error(here, "#include \"" + std::string(target) + "\": no such file under shaders/");
            if (std::find(included.begin(), included.end(), target) == included.end()) {
                included.emplace_back(target);
                const int child = static_cast<int>(sourceNames.size());
                sourceNames.emplace_back(target);
                text += "#line 1 " + std::to_string(child) + "\n";
                append(target, includedText, child, depth + 1);
            }
            // Resume this file on the line after the include.
            text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(number) + "\n";
        }
    }
};

}  // namespace

std::vector<EmbeddedFile> embeddedShaderFiles() {
    std::vector<EmbeddedFile> files;
    for (std::size_t i = 0; i < detail::kEmbeddedShaderCount; ++i)
        files.push_back({detail::kEmbeddedShaders[i].path, detail::kEmbeddedShaders[i].text});
    return files;
}

bool hasEmbeddedShader(std::string_view path) { return findEntry(path) != nullptr; }

std::string_view embeddedShader(std::string_view path) {
    const detail::EmbeddedEntry* entry = findEntry(path);
    if (entry == nullptr) throw Error("shaders/" + std::string(path) + ": no such embedded shader file");
    return entry->text;
}

GLenum stageFromPath(std::string_view path) {
    const std::size_t dot = path.rfind('.');
    const std::string_view ext = dot == std::string_view::npos ? std::string_view{} : path.substr(dot);
    if (ext == ".vert") return GL_VERTEX_SHADER;
    if (ext == ".frag") return GL_FRAGMENT_SHADER;
    if (ext == ".geom") return GL_GEOMETRY_SHADER;
    if (ext == ".comp") return GL_COMPUTE_SHADER;
    if (ext == ".tesc") return GL_TESS_CONTROL_SHADER;
    if (ext == ".tese") return GL_TESS_EVALUATION_SHADER;
    throw Error("shaders/" + std::string(path) +
                ": unknown shader stage (expected .vert, .frag, .geom, .comp, .tesc or .tese)");
}

StageSource assembleStage(std::string_view path, std::string_view text, const std::vector<ShaderDefine>& defines) {
    StageSource stage;
    stage.stage = stageFromPath(path);
    stage.path = std::string(path);

    Assembler assembler;
    assembler.sourceNames = {std::string(path), std::string(path) + " (#defines)"};
    assembler.included = {std::string(path)};
    assembler.text = "#version 450 core\n";
    if (!defines.empty()) {
        assembler.text += "#line 1 1\n";
        for (const ShaderDefine& d : defines) {
            assembler.text += "#define " + d.name;
            if (!d.value.empty()) assembler.text += " " + d.value;
            assembler.text += "\n";
        }
    }
    assembler.text += "#line 1 0\n";
    assembler.append(path, text, 0, 0);

    stage.text = std::move(assembler.text);
    stage.sourceNames = std::move(assembler.sourceNames);
    return stage;
}

StageSource loadStage(std::string_view path, const std::vector<ShaderDefine>& defines) {
    const std::string_view text = sourceText(path);
    if (text.empty()) throw Error("shaders/" + std::string(path) + ": no such shader file");
    return assembleStage(path, text, defines);
}

}  // namespace strata::gpu
