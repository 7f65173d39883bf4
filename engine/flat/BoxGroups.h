#pragma once
// Groups of axis-aligned 2D boxes that meet, directly or through others:
// the pieces of a flat shape that a sweep can take one group at a time.
// Sweep-line algorithms (Clipper's booleans, GLU's tessellator) keep every
// edge the sweep line crosses in one list and walk it to insert each new
// edge, so n pieces side by side (the glyphs of a line of text) cost about
// n^2 taken together and about n taken group by group. Pieces whose boxes
// do not meet cannot touch, cross or lie inside one another.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace strata::flat::detail {

template <class T>
struct FlatBox {
    T x0, y0, x1, y1;  // x0 > x1: empty, in no group
};

// The groups, each its boxes' indices in ascending x0; closed ranges, so
// boxes that only touch are one group. Empty boxes are left out.
template <class T>
std::vector<std::vector<std::size_t>> meetingBoxGroups(const std::vector<FlatBox<T>>& boxes) {
    const std::size_t n = boxes.size();
    std::vector<std::size_t> order, parent(n);
    for (std::size_t i = 0; i < n; ++i) {
        parent[i] = i;
        if (boxes[i].x0 <= boxes[i].x1) order.push_back(i);
    }
    auto root = [&parent](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::sort(order.begin(), order.end(), [&boxes](std::size_t a, std::size_t b) { return boxes[a].x0 < boxes[b].x0; });
    // Along x: each box meets those still open (their x range reaches its
    // start) whose y ranges meet its own.
    std::vector<std::size_t> open;
    for (std::size_t i : order) {
        const FlatBox<T>& b = boxes[i];
        std::erase_if(open, [&](std::size_t j) { return boxes[j].x1 < b.x0; });
        for (std::size_t j : open) {
            if (boxes[j].y0 <= b.y1 && b.y0 <= boxes[j].y1) parent[root(i)] = root(j);
        }
        open.push_back(i);
    }
    std::vector<std::vector<std::size_t>> byRoot(n);
    for (std::size_t i : order) byRoot[root(i)].push_back(i);
    std::vector<std::vector<std::size_t>> groups;
    for (std::vector<std::size_t>& g : byRoot) {
        if (!g.empty()) groups.push_back(std::move(g));
    }
    return groups;
}

}  // namespace strata::flat::detail
