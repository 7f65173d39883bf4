#pragma once
// What a PLY file must be before OpenMesh reads it. OpenMesh's reader
// crashes on a property declared before any element, never ends on a header
// without end_header, and believes every count and list length it reads (a
// list of 2000000000 values reserves gigabytes, then reads on past the end
// of the file). These checks refuse such files with one line instead.

#include <cstddef>
#include <cstdint>
#include <string>

namespace strata::mesh::detail {

// The first bytes of a PLY file that may hold its header.
constexpr std::size_t kPlyHeaderLimit = std::size_t(1) << 16;

// Checks the PLY file at `path`, `size` bytes long. The header: the magic
// line `ply`, one format (ascii, binary_little_endian, binary_big_endian;
// version 1.0), `element NAME COUNT` lines, properties of known types only
// inside an element, a vertex element with x, y and z before a face element
// with a list of vertex indices, end_header within kPlyHeaderLimit bytes,
// and counts the rest of the file can hold. The body: every element the
// header declares is there, and every list's length is a whole number no
// larger than what the file still holds. Throws strata::Error
// "path:line: cannot read mesh: why" (or "path: ..." where no line is at
// fault, as in a binary body).
void checkPly(const std::string& path, std::uintmax_t size);

// The first `limit` bytes of the file at `path` (fewer where it is shorter).
std::string readHead(const std::string& path, std::size_t limit);

}  // namespace strata::mesh::detail
