#pragma once
// The cache of exact results (Exact.cpp), shared with the other nodes whose
// geometry takes CGAL's time (minkowski sums of non-convex solids): results
// are kept by a key over their input's content, up to about 256 MiB in all.

#include <cstdint>
#include <optional>

#include "strata/mesh/Mesh.h"

namespace strata::exact {

// FNV-1a over 64-bit words: operations as numbers, meshes bit for bit.
class ContentKey {
public:
    void mix(std::uint64_t v) { h_ = (h_ ^ v) * 0x100000001b3ull; }
    void mix(const mesh::Mesh& m);
    std::uint64_t value() const { return h_; }

private:
    std::uint64_t h_ = 0xcbf29ce484222325ull;
};

// A kept result, counted as a cache hit (exactCacheHits), or nothing.
std::optional<mesh::Mesh> cachedResult(std::uint64_t key);
// Keeps `mesh` under `key`, dropping the oldest results past the budget.
void keepResult(std::uint64_t key, const mesh::Mesh& mesh);

}  // namespace strata::exact
