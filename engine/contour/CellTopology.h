#pragma once
// The cube of one grid cell as the contouring sees it: its corners, edges and
// faces numbered once, and the surface patches that its corner signs make.
//
// A patch is one cycle of the marching-cubes surface inside the cell: on
// every face the edges whose ends differ in sign are joined by segments, and
// the segments link the cell's sign-change edges into cycles. Contouring puts
// one vertex per patch, which is what keeps the dual surface 2-manifold where
// one vertex per cell would pinch two sheets together.

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

namespace strata::contour {

inline constexpr int kCellCorners = 8;
inline constexpr int kCellEdges = 12;
inline constexpr int kCellFaces = 6;

// Corner c sits at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1) from the
// cell's lowest corner. A cell's configuration has bit c set when corner c is
// inside the solid.
glm::ivec3 cornerOffset(int corner);
int cornerAt(const glm::ivec3& offset);

// Edge e runs along axis e / 4 from its start corner; the start's offsets in
// the other two axes u = (axis + 1) % 3 and v = (axis + 2) % 3 are bits 0 and
// 1 of e % 4.
int edgeAxis(int edge);
glm::ivec3 edgeStart(int edge);
int edgeAt(int axis, const glm::ivec3& start);
bool edgeChangesSign(std::uint8_t config, int edge);

// Face f is perpendicular to axis f / 2, on the cell's low side (f even) or
// high side (f odd). The cell across face f sees it as faceOpposite(f).
inline int faceAxis(int face) { return face / 2; }
inline bool faceIsHigh(int face) { return (face & 1) != 0; }
inline int faceOpposite(int face) { return face ^ 1; }

// A face is ambiguous when its corners alternate in sign: four sign-change
// edges that can be paired in two ways. The default pairing cuts off each
// inside corner (the inside corners stay apart on the face); a flipped face
// cuts off each outside corner. The choice depends only on the face, so the
// two cells that share it always agree.
bool ambiguousFace(std::uint8_t config, int face);

struct CellPatches {
    std::array<std::int8_t, kCellEdges> patchOfEdge{};  // -1 where the edge keeps its sign
    int count = 0;
};

// The patches of a cell; `flips` has bit f set where face f uses the flipped
// pairing (set only on ambiguous faces). A table lookup.
const CellPatches& cellPatches(std::uint8_t config, std::uint8_t flips);

// The ambiguous faces whose two segments end up in one patch of this cell
// under the default pairing. Where both cells of a face say so, welding the
// dual mesh by patch vertex would join the same two vertices by two mesh
// edges (four triangles on one edge); flipping that face splits the patch in
// both cells. At most one face of any cell is in this set, and flipping it
// never joins segments of another face (CellTopologyTest checks both over
// all 256 configurations), so the rule needs no iteration.
std::uint8_t facesJoinedInOnePatch(std::uint8_t config);

// Whether ambiguous face `face`'s two segments belong to one patch of the
// cell, with the faces in `flips` flipped (false for a face that is not
// ambiguous).
bool faceSegmentsInOnePatch(std::uint8_t config, int face, std::uint8_t flips);

}  // namespace strata::contour
