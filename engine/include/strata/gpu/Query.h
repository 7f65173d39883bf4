#pragma once
// Query: one GL query object. Occlusion (did a pass draw anything?) and timer
// (how long did a pass take on the GPU?) are what strata uses.
//
//   Query drawn("peel drawn", GL_ANY_SAMPLES_PASSED);
//   drawn.begin(); ...draw...; drawn.end();
//   if (drawn.result() == 0) stop peeling;

#include <cstdint>
#include <string_view>

#include "strata/gpu/GlName.h"

namespace strata::gpu {

class Query {
public:
    Query() = default;  // holds no object (id() == 0)
    // `target`: GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED,
    // GL_ANY_SAMPLES_PASSED_CONSERVATIVE, GL_TIME_ELAPSED, GL_TIMESTAMP,
    // GL_PRIMITIVES_GENERATED.
    Query(std::string_view label, GLenum target);

    // glBeginQuery / glEndQuery (not for GL_TIMESTAMP).
    void begin();
    void end();
    // GL_TIMESTAMP: records the GPU time when the commands before it finish.
    void timestamp();

    // True when result() would not wait.
    bool available() const;
    // Waits for and returns the result: samples, 0/1, nanoseconds, primitives.
    std::uint64_t result() const;

    GLuint id() const noexcept { return name_.get(); }
    GLenum target() const noexcept { return target_; }

private:
    GlName<QueryDeleter> name_;
    GLenum target_ = 0;
};

}  // namespace strata::gpu
