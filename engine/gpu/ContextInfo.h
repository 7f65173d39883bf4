#pragma once
// Private to engine/gpu: what the current GL context is, asked without GL
// headers, so Context.cpp can include EGL's headers (whose khrplatform.h
// clashes with epoxy's GL header in one translation unit).

#include <string>

namespace strata::gpu {

// 45 for OpenGL 4.5; 0 when no context is current.
int currentGlVersion();
bool currentGlIsCoreProfile();

enum class GlString { Vendor, Renderer, Version };
std::string currentGlString(GlString which);

}  // namespace strata::gpu
