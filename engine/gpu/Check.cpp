#include "strata/gpu/Check.h"

#include <new>
#include <string>

#include "DebugOutput.h"
#include "strata/gpu/Gl.h"

namespace strata::gpu {

SourceLocation sourcePosition(const std::source_location& where) {
    std::string file = where.file_name();
    // Messages name files relative to the project root, not by the absolute
    // path of the checkout they were built from.
    const std::string root = STRATA_SOURCE_DIR;
    if (file.compare(0, root.size(), root) == 0) file.erase(0, root.size());
    return SourceLocation{file, static_cast<int>(where.line()), 0};
}

void fail(std::string_view message, std::source_location where) {
    throw Error(sourcePosition(where), std::string(message));
}

void checkErrors(std::source_location where) {
    std::string message;
    if (DebugState* state = currentDebugState(); state != nullptr && !state->firstError.empty()) {
        message = std::move(state->firstError);
        state->firstError.clear();
    }
    // Drain every flag (a context may hold several) and report the first.
    GLenum first = GL_NO_ERROR;
    for (int i = 0; i < 16; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        if (first == GL_NO_ERROR) first = e;
    }
    if (message.empty() && first == GL_NO_ERROR) return;
    // The driver could not allocate: the programs' out-of-memory line, as for
    // any other allocation, not a GL error of strata's.
    if (first == GL_OUT_OF_MEMORY) throw std::bad_alloc();
    if (first != GL_NO_ERROR) message = enumName(first) + (message.empty() ? "" : ": " + message);
    fail(message, where);
}

}  // namespace strata::gpu
