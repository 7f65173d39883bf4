// libFuzzer target for the .csg parser (scene::parseCsg).
//
// Any input must either parse into a well-formed Tree or throw strata::Error;
// anything else (another exception, a crash, a leak, a sanitizer report, a
// broken tree) is a finding. scripts/fuzz.sh builds and runs it.
//
// Relative import() paths resolve against STRATA_FUZZ_DATA_DIR (the checked-in
// OpenSCAD exports), so `import(file = "example012.stl")` reaches the success
// path. Only the parser runs here: no tessellation, no mesh import.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

#include "strata/core/Error.h"
#include "strata/scene/CsgParser.h"

namespace {

using namespace strata::scene;

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "strata_fuzz_csg: the parser returned a broken tree: %s\n", what);
    std::abort();
}

bool finite(double v) { return std::isfinite(v); }
bool size(double v) { return std::isfinite(v) && v >= 0.0; }

void checkFragments(const Fragments& f, const ParseOptions& options) {
    if (!finite(f.fn) || !finite(f.fa) || !finite(f.fs)) broken("non-finite $fn/$fa/$fs");
    if (f.fn > options.maxFragments) broken("$fn above ParseOptions::maxFragments");
}

void checkLeaf(const Leaf& leaf, const ParseOptions& options);
void checkTree(const Tree& tree, const ParseOptions& options);

// The flat tree a leaf carries: children after their parents and in range,
// shapes in range, numbers finite, sizes not negative.
void checkFlat(const FlatTree& flat, const ParseOptions& options) {
    const auto nodeCount = static_cast<long>(flat.nodes.size());
    const auto shapeCount = static_cast<long>(flat.shapes.size());
    if (flat.root < -1 || flat.root >= nodeCount) broken("flat root out of range");
    for (long i = 0; i < nodeCount; ++i) {
        const FlatNode& n = flat.nodes[static_cast<std::size_t>(i)];
        for (int c : n.children) {
            if (c <= i || c >= nodeCount) broken("flat child index not after its parent or out of range");
        }
        if (n.op == FlatOp::Shape && (n.shape < 0 || n.shape >= shapeCount)) broken("flat shape index out of range");
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                if (!finite(n.matrix[c][r])) broken("non-finite flat transform");
            }
        }
        if (!finite(n.offset.amount)) broken("non-finite offset");
    }
    for (const FlatPrimitive& shape : flat.shapes) {
        std::visit(
            [&](const auto& p) {
                using T = std::decay_t<decltype(p)>;
                if constexpr (std::is_same_v<T, Square>) {
                    if (!size(p.size.x) || !size(p.size.y)) broken("bad square size");
                } else if constexpr (std::is_same_v<T, Circle>) {
                    if (!size(p.r)) broken("bad circle radius");
                    checkFragments(p.fragments, options);
                } else if constexpr (std::is_same_v<T, Polygon>) {
                    const auto points = static_cast<long>(p.points.size());
                    for (const auto& q : p.points) {
                        if (!finite(q.x) || !finite(q.y)) broken("non-finite polygon point");
                    }
                    for (const auto& path : p.paths) {
                        for (int i : path) {
                            if (i < 0 || i >= points) broken("polygon path index out of range");
                        }
                    }
                } else if constexpr (std::is_same_v<T, Text>) {
                    if (!finite(p.size) || !finite(p.spacing)) broken("non-finite text size");
                    checkFragments(p.fragments, options);
                } else if constexpr (std::is_same_v<T, Projection>) {
                    if (!p.solid) broken("projection with no solid");
                    checkTree(*p.solid, options);
                } else {
                    if (p.path.empty()) broken("2D import with an empty path");
                    if (!finite(p.scale) || !finite(p.origin.x) || !finite(p.origin.y) || !(p.dpi > 0)) broken("bad 2D import");
                }
            },
            shape);
    }
}


// What the parser promises of every tree it returns (Tree.h, CsgParser.h):
// indices in range, numbers finite, sizes not negative, $fn clamped.
void checkTree(const Tree& tree, const ParseOptions& options) {
    const auto nodeCount = static_cast<long>(tree.nodes.size());
    const auto leafCount = static_cast<long>(tree.leaves.size());
    if (tree.root < -1 || tree.root >= nodeCount) broken("root out of range");
    for (int b : tree.background) {
        if (b < 0 || b >= nodeCount) broken("background root out of range");
    }
    for (const Node& n : tree.nodes) {
        if (n.kind == NodeKind::Leaf) {
            if (n.leaf < 0 || n.leaf >= leafCount) broken("leaf index out of range");
            if (!n.children.empty()) broken("leaf node with children");
        }
        for (int c : n.children) {
            if (c < 0 || c >= nodeCount) broken("child index out of range");
        }
    }
    for (const Leaf& leaf : tree.leaves) checkLeaf(leaf, options);
    for (const Resize& r : tree.resizes) {
        if (r.leaves.empty()) broken("resize with no leaves");
        for (int l : r.leaves) {
            if (l < 0 || l >= leafCount) broken("resize leaf out of range");
        }
        for (int i = 0; i < 3; ++i) {
            if (!finite(r.newsize[i])) broken("non-finite resize");
        }
    }
}

void checkLeaf(const Leaf& leaf, const ParseOptions& options) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!finite(leaf.transform[c][r])) broken("non-finite transform");
        }
    }
    if (leaf.color) {
        for (int i = 0; i < 4; ++i) {
            if (!finite((*leaf.color)[i])) broken("non-finite colour");
        }
    }
    std::visit(
        [&](const auto& p) {
            using T = std::decay_t<decltype(p)>;
            if constexpr (std::is_same_v<T, Cube>) {
                if (!size(p.size.x) || !size(p.size.y) || !size(p.size.z)) broken("bad cube size");
            } else if constexpr (std::is_same_v<T, Sphere>) {
                if (!size(p.r)) broken("bad sphere radius");
                checkFragments(p.fragments, options);
            } else if constexpr (std::is_same_v<T, Cylinder>) {
                if (!size(p.h) || !size(p.r1) || !size(p.r2)) broken("bad cylinder size");
                checkFragments(p.fragments, options);
            } else if constexpr (std::is_same_v<T, Polyhedron>) {
                const auto points = static_cast<long>(p.points.size());
                for (const auto& q : p.points) {
                    if (!finite(q.x) || !finite(q.y) || !finite(q.z)) broken("non-finite polyhedron point");
                }
                for (const auto& face : p.faces) {
                    if (face.size() < 3) broken("polyhedron face with fewer than 3 points");
                    for (int i : face) {
                        if (i < 0 || i >= points) broken("polyhedron face index out of range");
                    }
                }
            } else if constexpr (std::is_same_v<T, LinearExtrude>) {
                if (!size(p.height) || !finite(p.twist) || !size(p.scale.x) || !size(p.scale.y)) {
                    broken("bad linear_extrude");
                }
                if (p.hasSlices && (p.slices < 1 || p.slices > options.maxFragments)) broken("slices out of range");
                checkFragments(p.fragments, options);
                checkFlat(p.shape, options);
            } else if constexpr (std::is_same_v<T, RotateExtrude>) {
                if (!(p.angle > -360.0 && p.angle <= 360.0) || !finite(p.start)) broken("bad rotate_extrude");
                checkFragments(p.fragments, options);
                checkFlat(p.shape, options);
            } else if constexpr (std::is_same_v<T, FlatSlab>) {
                checkFlat(p.shape, options);
            } else if constexpr (std::is_same_v<T, Exact>) {
                if (!p.solid) broken("exact leaf with no solid");
                checkTree(*p.solid, options);
            } else if constexpr (std::is_same_v<T, MinkowskiSum>) {
                if (p.operands.empty()) broken("minkowski with no operands");
                for (const auto& operand : p.operands) {
                    if (!operand) broken("minkowski operand with no tree");
                    checkTree(*operand, options);
                }
            } else if constexpr (std::is_same_v<T, Hull>) {
                if (p.parts.empty()) broken("hull with no parts");
                for (const Leaf& part : p.parts) checkLeaf(part, options);
                for (const Leaf& summand : p.summands) checkLeaf(summand, options);
            } else {
                if (p.path.empty()) broken("import or surface with an empty path");
            }
        },
        leaf.primitive);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::istringstream in(text);
    const ParseOptions options;
    try {
        const Tree tree = parseCsg(in, "fuzz.csg", STRATA_FUZZ_DATA_DIR, options);
        checkTree(tree, options);
    } catch (const strata::Error&) {
        // Bad input, reported the way it should be.
    }
    return 0;
}
