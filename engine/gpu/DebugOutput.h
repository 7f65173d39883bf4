#pragma once
// Private to engine/gpu: KHR_debug plumbing shared by Context and WindowContext.
//
// The driver calls the debug callback from inside a GL call, where throwing
// is undefined behaviour. So the callback only records the first error message
// in the DebugState of the current context; checkErrors() throws it later.

#include <string>

namespace strata::gpu {

struct DebugState {
    bool enabled = false;
    std::string firstError;  // first GL_DEBUG_TYPE_ERROR message since the last check
};

// Turns on synchronous debug output into `state` (the context must be current
// and created with the debug flag). Does nothing when KHR_debug is absent.
void enableDebugOutput(DebugState& state);

// The state that checkErrors() reads on this thread; set when a context is made current.
void setCurrentDebugState(DebugState* state);
DebugState* currentDebugState();

}  // namespace strata::gpu
