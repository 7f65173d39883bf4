#pragma once
// Failing loudly on GL errors.
//
// A KHR_debug callback cannot throw through the driver, so with debug output on
// (see Context) the callback records the first error message, and checkErrors()
// turns it, or anything glGetError() reports, into a strata::Error that starts
// with the caller's source position:
//   engine/render/PeelPass.cpp:88: GL_INVALID_OPERATION: <driver message>
// Call it at the end of each pass; it costs one glGetError() when all is well.

#include <source_location>
#include <string_view>

#include "strata/core/Error.h"

namespace strata::gpu {

// Throws strata::Error if GL reported an error since the last check (either
// through the debug callback or glGetError()), std::bad_alloc for
// GL_OUT_OF_MEMORY. Clears GL's error flags.
void checkErrors(std::source_location where = std::source_location::current());

// Throws strata::Error("<where>: <message>").
[[noreturn]] void fail(std::string_view message,
                       std::source_location where = std::source_location::current());

// A source position in strata, as printed in messages: the path relative to the
// project root ("engine/gpu/Framebuffer.cpp") and the line.
SourceLocation sourcePosition(const std::source_location& where);

}  // namespace strata::gpu
