#include "strata/mesh/LastCorners.h"

namespace strata::mesh {

LastCornerLayout lastCornerLayout(const Mesh& mesh) {
    LastCornerLayout out;
    out.source.resize(mesh.positions.size());
    for (std::size_t v = 0; v < out.source.size(); ++v) out.source[v] = static_cast<std::uint32_t>(v);
    std::vector<char> taken(mesh.positions.size(), 0);
    out.triangles = mesh.triangles;
    for (std::array<std::uint32_t, 3>& t : out.triangles) {
        if (!taken[t[2]]) {
            taken[t[2]] = 1;
            continue;
        }
        // Another triangle ends on this vertex: this one ends on a copy.
        out.source.push_back(t[2]);
        t[2] = static_cast<std::uint32_t>(out.source.size() - 1);
    }
    return out;
}

}  // namespace strata::mesh
