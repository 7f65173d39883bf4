#pragma once
// What strata accepts as an input file (a scene, a mesh, an imported drawing,
// a height map, a .scad's sources): a regular file, symbolic links followed.
// Anything else is refused before it is opened, so that a FIFO cannot block
// a reader and a device (/dev/zero, /dev/urandom) cannot feed one forever.

#include <string>

namespace strata {

// Why `path` cannot be read as an input file, or "" when it can: "no such
// file", "it is a folder", "it is a FIFO", "it is a device", "it is a
// socket", "its name holds a NUL byte", "permission denied", ...
std::string unreadableReason(const std::string& path);

// The whole of the input file at `path`. Throws strata::Error "WHAT: cannot
// read 'PATH': why" (no position: the caller adds its own) where
// unreadableReason names a reason, or the file is larger than `maxMiB`.
std::string readInputFile(const std::string& path, const char* what, unsigned maxMiB = 256);

// Throws strata::Error "PATH: cannot read (why)" (named by the file, no
// line) where unreadableReason names a reason.
void requireReadable(const std::string& path);

// The extension of `path`'s file name with its dot, in ASCII lower case
// (".stl" for "Part.STL"); "" where the name has none.
std::string lowerExtension(const std::string& path);

}  // namespace strata
