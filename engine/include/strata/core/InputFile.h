#pragma once
// What strata accepts as an input file (a scene, a mesh, an imported drawing,
// a height map): a regular file, symbolic links followed. Anything else is
// refused before it is opened, so that a FIFO cannot block a reader and a
// device (/dev/zero, /dev/urandom) cannot feed one forever.

#include <string>

namespace strata {

// Why `path` cannot be read as an input file, or "" when it can: "no such
// file", "it is a folder", "it is a FIFO", "it is a device", "it is a
// socket", "its name holds a NUL byte", "permission denied", ...
std::string unreadableReason(const std::string& path);

}  // namespace strata
