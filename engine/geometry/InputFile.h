#pragma once
// The whole of a file that a node reads (surface() heights, a 2D import):
// refused with one line when missing, not a regular file (a FIFO or a device
// would block or never end) or larger than 256 MiB.

#include <string>

namespace strata::geometry::detail {

// Throws strata::Error "NODE: cannot read 'PATH': why" (no position: the
// caller adds the node's).
std::string readInputFile(const std::string& path, const char* node);

}  // namespace strata::geometry::detail
