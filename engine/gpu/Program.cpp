#include "strata/gpu/Program.h"

#include <glm/gtc/type_ptr.hpp>
#include <cctype>
#include <string>

#include "strata/core/Error.h"
#include "strata/gpu/Check.h"

namespace strata::gpu {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
    GLint length = 0;
    if (isProgram)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    if (length <= 1) return {};
    std::string log(static_cast<std::size_t>(length), '\0');
    GLsizei written = 0;
    if (isProgram)
        glGetProgramInfoLog(object, length, &written, log.data());
    else
        glGetShaderInfoLog(object, length, &written, log.data());
    log.resize(static_cast<std::size_t>(written));
    return log;
}

// A tiny cursor over one log line, for the three log dialects below.
struct Cursor {
    std::string_view s;
    bool number(unsigned long& out) {
        std::size_t n = 0;
        out = 0;
        while (n < s.size() && n < 9 && std::isdigit(static_cast<unsigned char>(s[n]))) out = out * 10 + (s[n++] - '0');
        s.remove_prefix(n);
        return n > 0;
    }
    bool literal(std::string_view word) {
        if (s.substr(0, word.size()) != word) return false;
        s.remove_prefix(word.size());
        return true;
    }
    void blanks() {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    }
};

// Recognises "0:27(5): msg" (Mesa), "0(27) : msg" (NVIDIA) and
// "ERROR: 0:27: msg" (glslang, AMD); fills source number, line and message.
bool parseLogLine(std::string_view line, unsigned long& source, unsigned long& lineNumber, std::string& message) {
    Cursor c{line};
    c.blanks();
    std::string severity;
    if (c.literal("ERROR:")) severity = "error: ";
    else if (c.literal("WARNING:")) severity = "warning: ";
    c.blanks();
    if (!c.number(source)) return false;
    if (severity.empty() && c.literal("(")) {  // NVIDIA
        if (!c.number(lineNumber) || !c.literal(")")) return false;
        c.blanks();
        if (!c.literal(":")) return false;
    } else {
        if (!c.literal(":") || !c.number(lineNumber)) return false;
        if (severity.empty()) {  // Mesa: a column in parentheses
            unsigned long column = 0;
            if (!c.literal("(") || !c.number(column) || !c.literal(")")) return false;
        }
        if (!c.literal(":")) return false;
    }
    c.blanks();
    message = severity + std::string(c.s);
    return true;
}

}  // namespace

std::string formatShaderLog(std::string_view log, const std::vector<std::string>& sourceNames,
                            std::string_view fallback) {
    auto fileOf = [&](unsigned long k) -> std::string {
        return k < sourceNames.size() ? sourceNames[k] : std::string(fallback);
    };

    std::string out;
    std::size_t pos = 0;
    while (pos < log.size()) {
        std::size_t end = log.find('\n', pos);
        if (end == std::string_view::npos) end = log.size();
        std::string line(log.substr(pos, end - pos));
        pos = end + 1;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\0')) line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;

        unsigned long source = 0, lineNumber = 0;
        std::string message;
        std::string formatted;
        if (parseLogLine(line, source, lineNumber, message))
            formatted = "shaders/" + fileOf(source) + ":" + std::to_string(lineNumber) + ": " + message;
        else
            formatted = "shaders/" + std::string(fallback) + ": " + line;
        if (!out.empty()) out += '\n';
        out += formatted;
    }
    return out;
}

Program::Program(std::string_view label, std::span<const StageSource> stages) : label_(label) {
    GLuint program = glCreateProgram();
    name_ = GlName<ProgramDeleter>(program);
    setLabel(GL_PROGRAM, program, label);

    std::vector<GlName<ShaderDeleter>> shaders;
    std::string files;
    for (const StageSource& stage : stages) {
        GlName<ShaderDeleter> shader(glCreateShader(stage.stage));
        if (!shader) fail("cannot create a " + enumName(stage.stage) + " for shaders/" + stage.path);
        setLabel(GL_SHADER, shader.get(), stage.path);
        const char* text = stage.text.c_str();
        const GLint length = static_cast<GLint>(stage.text.size());
        glShaderSource(shader.get(), 1, &text, &length);
        glCompileShader(shader.get());
        GLint ok = GL_FALSE;
        glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE) {
            std::string log = formatShaderLog(infoLog(shader.get(), false), stage.sourceNames, stage.path);
            if (log.empty()) log = "shaders/" + stage.path + ": compilation failed (the driver gave no log)";
            throw Error(log);
        }
        glAttachShader(program, shader.get());
        files += (files.empty() ? "" : " + ") + ("shaders/" + stage.path);
        shaders.push_back(std::move(shader));
    }

    glLinkProgram(program);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    for (const auto& shader : shaders) glDetachShader(program, shader.get());
    if (ok != GL_TRUE) {
        std::string log = infoLog(program, true);
        std::string message = files + ": link failed";
        for (std::size_t pos = 0; pos < log.size();) {
            std::size_t end = log.find('\n', pos);
            if (end == std::string::npos) end = log.size();
            std::string line = log.substr(pos, end - pos);
            pos = end + 1;
            if (line.find_first_not_of(" \t\r") != std::string::npos) message += "\n" + files + ": " + line;
        }
        throw Error(message);
    }
}

Program Program::fromFiles(std::string_view label, std::initializer_list<std::string_view> paths,
                           const std::vector<ShaderDefine>& defines) {
    std::vector<StageSource> stages;
    for (std::string_view path : paths) stages.push_back(loadStage(path, defines));
    return Program(label, stages);
}

void Program::use() const { glUseProgram(id()); }

GLint Program::uniformLocation(const std::string& name) const { return glGetUniformLocation(id(), name.c_str()); }

void Program::setUniform(GLint location, int value) { glProgramUniform1i(id(), location, value); }
void Program::setUniform(GLint location, unsigned value) { glProgramUniform1ui(id(), location, value); }
void Program::setUniform(GLint location, float value) { glProgramUniform1f(id(), location, value); }
void Program::setUniform(GLint location, const glm::vec2& value) {
    glProgramUniform2fv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::vec3& value) {
    glProgramUniform3fv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::vec4& value) {
    glProgramUniform4fv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::ivec2& value) {
    glProgramUniform2iv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::ivec4& value) {
    glProgramUniform4iv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::uvec2& value) {
    glProgramUniform2uiv(id(), location, 1, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::mat3& value) {
    glProgramUniformMatrix3fv(id(), location, 1, GL_FALSE, glm::value_ptr(value));
}
void Program::setUniform(GLint location, const glm::mat4& value) {
    glProgramUniformMatrix4fv(id(), location, 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace strata::gpu
