#pragma once
// The passes' side of shaders/csg/interface.glsl: the uniform locations,
// binding points and encodings the C++ passes share with their shaders, as
// constants and functions in strata::render::shader. The one file is read
// by both languages, so a change there changes both.

#include <cstdint>

namespace strata::render::shader {

using uint = std::uint32_t;

#include "csg/interface.glsl"

}  // namespace strata::render::shader
