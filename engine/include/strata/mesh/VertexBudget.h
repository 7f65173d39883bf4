#pragma once
// The most vertices one leaf's mesh may have: a primitive, an extrusion, a
// surface() or a text() that would pass it is refused with one line instead
// of exhausting memory (a huge $fn, a large height map). docs/limits.md
// states it with each message.

#include <cstddef>

namespace strata::mesh {

constexpr std::size_t kMaxVertices = std::size_t(1) << 24;

}  // namespace strata::mesh
