#pragma once
// GLSL sources: the files under shaders/, embedded into the library at build
// time (so apps run from any folder), and assembled into one stage's text.
//
// A stage is assembled as
//
//   #version 450 core
//   #define NAME VALUE            (the pass's defines, in order)
//   #line 1 0
//   <the file, with each  #include "common/x.glsl"  line replaced by that file>
//
// Each included file gets its own GLSL source-string number (`#line 1 K`), and
// `#line N 0` resumes the outer file after it, so the driver's "K:LINE" in a
// log maps back to the exact file and line (Program formats them as
// "shaders/common/x.glsl:12: ..."). A file is included at most once per stage.
// #extension lines may stand at the top of a file, before its includes.

#include <string>
#include <string_view>
#include <vector>

#include "strata/gpu/Gl.h"

namespace strata::gpu {

// The text of an embedded file, keyed by its path under shaders/
// ("csg/evaluate.frag"). Empty view with found == false when absent.
struct EmbeddedFile {
    std::string_view path;
    std::string_view text;
};
// Every embedded file, sorted by path.
std::vector<EmbeddedFile> embeddedShaderFiles();
// Throws strata::Error("shaders/<path>: no such embedded shader file") when absent.
std::string_view embeddedShader(std::string_view path);
bool hasEmbeddedShader(std::string_view path);

struct ShaderDefine {
    std::string name;
    std::string value;  // may be empty: "#define NAME"
};

// One assembled stage, ready for Program.
struct StageSource {
    GLenum stage = 0;                      // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
    std::string path;                      // "csg/evaluate.frag": names the stage in messages
    std::string text;                      // the assembled GLSL
    std::vector<std::string> sourceNames;  // [k] = path of GLSL source-string number k
};

// The stage of a file by its extension: .vert .frag .geom .comp .tesc .tese.
// Throws strata::Error for any other.
GLenum stageFromPath(std::string_view path);

// Assembles the embedded file `path` (see above).
StageSource loadStage(std::string_view path, const std::vector<ShaderDefine>& defines = {});

// Assembles `text` as if it were the file `path`; its #include lines are
// resolved against the embedded files. For tests and for embedders' own shaders.
StageSource assembleStage(std::string_view path, std::string_view text,
                          const std::vector<ShaderDefine>& defines = {});

}  // namespace strata::gpu
