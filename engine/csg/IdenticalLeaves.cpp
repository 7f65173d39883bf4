#include "strata/csg/IdenticalLeaves.h"

#include <bit>
#include <cstdint>
#include <unordered_map>

namespace strata::csg {

namespace {

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    // FNV-1a style over 64-bit words, with a final avalanche below.
    return (h ^ v) * 0x100000001b3ull;
}

std::uint64_t meshHash(const mesh::Mesh& mesh) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const glm::dvec3& p : mesh.positions) {
        h = mix(h, std::bit_cast<std::uint64_t>(p.x));
        h = mix(h, std::bit_cast<std::uint64_t>(p.y));
        h = mix(h, std::bit_cast<std::uint64_t>(p.z));
    }
    for (const auto& t : mesh.triangles) h = mix(h, (std::uint64_t(t[0]) << 32) ^ (std::uint64_t(t[1]) << 16) ^ t[2]);
    h ^= h >> 33;
    return h * 0xff51afd7ed558ccdull;
}

bool sameSolid(const scene::Leaf& a, const mesh::Mesh& ma, const scene::Leaf& b, const mesh::Mesh& mb) {
    return a.display == b.display && a.color == b.color && ma.triangles == mb.triangles &&
           ma.positions == mb.positions;
}

}  // namespace

std::vector<int> identicalLeaves(const scene::Tree& tree, const model::Model& model) {
    const std::size_t n = tree.leaves.size();
    std::vector<int> same(n);
    std::unordered_map<std::uint64_t, std::vector<int>> byHash;  // hash -> the first leaf of each distinct solid
    for (std::size_t i = 0; i < n; ++i) {
        same[i] = static_cast<int>(i);
        if (i >= model.leafMeshes.size() || model.leafMeshes[i].triangles.empty()) continue;
        const mesh::Mesh& mesh = model.leafMeshes[i];
        std::vector<int>& firsts = byHash[meshHash(mesh)];
        for (int j : firsts) {
            const auto u = static_cast<std::size_t>(j);
            if (sameSolid(tree.leaves[u], model.leafMeshes[u], tree.leaves[i], mesh)) {
                same[i] = j;
                break;
            }
        }
        if (same[i] == static_cast<int>(i)) firsts.push_back(static_cast<int>(i));
    }
    return same;
}

}  // namespace strata::csg
