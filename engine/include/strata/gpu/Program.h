#pragma once
// Program: one linked GL program object.
//
// Compile and link errors throw strata::Error with the driver's messages
// mapped back to the files they came from, one message per line:
//   shaders/csg/evaluate.frag:27: error: `idTex' undeclared
// (see ShaderSource.h for how the line numbers are kept).

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "strata/gpu/GlName.h"
#include "strata/gpu/ShaderSource.h"

namespace strata::gpu {

class Program {
public:
    Program() = default;  // holds no object (id() == 0)
    // Compiles each stage and links them.
    Program(std::string_view label, std::span<const StageSource> stages);

    // Loads, assembles, compiles and links the embedded files `paths`
    // ("csg/evaluate.vert", "csg/evaluate.frag"), each with the same defines.
    static Program fromFiles(std::string_view label, std::initializer_list<std::string_view> paths,
                             const std::vector<ShaderDefine>& defines = {});

    void use() const;  // glUseProgram

    // -1 when the program has no active uniform of that name (the setters ignore -1, as GL does).
    GLint uniformLocation(const std::string& name) const;

    // glProgramUniform*: no need to use() first.
    void setUniform(GLint location, int value);
    void setUniform(GLint location, unsigned value);
    void setUniform(GLint location, float value);
    void setUniform(GLint location, const glm::vec2& value);
    void setUniform(GLint location, const glm::vec3& value);
    void setUniform(GLint location, const glm::vec4& value);
    void setUniform(GLint location, const glm::ivec2& value);
    void setUniform(GLint location, const glm::ivec4& value);
    void setUniform(GLint location, const glm::uvec2& value);
    void setUniform(GLint location, const glm::mat3& value);
    void setUniform(GLint location, const glm::mat4& value);
    template <class T>
    void setUniform(const std::string& name, const T& value) {
        setUniform(uniformLocation(name), value);
    }

    GLuint id() const noexcept { return name_.get(); }
    const std::string& label() const noexcept { return label_; }

private:
    GlName<ProgramDeleter> name_;
    std::string label_;
};

// Rewrites a driver's info log so each message names the file and line it
// came from ("shaders/<file>:<line>: <message>"), using `sourceNames` to map
// GLSL source-string numbers to files. Understands Mesa ("0:27(5): error: ...")
// and NVIDIA ("0(27) : error C1008: ...") logs; other lines are kept as they are
// with "shaders/<fallback>: " in front. Empty lines are dropped.
std::string formatShaderLog(std::string_view log, const std::vector<std::string>& sourceNames,
                            std::string_view fallback);

}  // namespace strata::gpu
