// strata-algorithm-figures: the pictures of docs/algorithm.md, rendered by
// strata itself through its public API, in the manner of the original
// image-space CSG papers' figures: each operand's peeled layers, the evaluated
// result (depth, leaf id, normal), the shaded image, the one-layer failure
// next to its fix, and the evaluator's form per 16x16 block. Not a test;
// scripts/algorithm-figures.sh runs it.
//
//   strata-algorithm-figures OUTPUT_DIR
//
// Writes OUTPUT_DIR/*.png (192x192 each) and prints the figures the document
// quotes (layers per operand, pixels that differ, tiles). Exits non-zero if a
// picture would contradict the document (e.g. the one-layer render came out
// right, or tiling changed a pixel), so a regenerated document cannot
// silently show the wrong thing.
//
// Scenes (world Z up, as in OpenSCAD):
//   stack   a block minus ONE polyhedron operand made of three disjoint
//           spheres lined up on the view axis (the paper's failure case):
//
//             z= 3.8   ( s1 )   s1 pokes out of the top face
//             z= 3    ==|  |==  block top
//             z= 0     ( s2 )   s2 inside the block
//             z=-3    ==|  |==  block bottom
//             z=-3.8   ( s3 )   s3 pokes out below
//
//   cheese  a centred cube of side 2 and a sphere of radius 1.3: union,
//           intersection and difference (the paper's three operations).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "strata/camera/Camera.h"
#include "strata/core/Error.h"
#include "strata/csg/CompiledTree.h"
#include "strata/gpu/Context.h"
#include "strata/io/ImageWriter.h"
#include "strata/mesh/Primitives.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "strata/scene/Tree.h"

using namespace strata;
using scene::NodeKind;

namespace {

constexpr int kSize = 192;
constexpr double kSphereRadius = 1.2;
constexpr double kSphereZ[3] = {2.6, 0.0, -2.6};  // gaps of 0.2 between the shells
constexpr double kBlockHalf = 3.0;                // the block spans z in [-3, 3]

// Colours of the false-colour images (8-bit RGB).
struct Rgb {
    std::uint8_t r, g, b;
};
constexpr Rgb kNothing{28, 32, 56};  // no surface: a dark blue, apart from every grey
// Okabe–Ito's colour-blind-safe palette, one per leaf.
constexpr Rgb kLeafColors[] = {{230, 159, 0}, {86, 180, 233}, {0, 158, 115}, {204, 121, 167}, {240, 228, 66}};

using Image = std::vector<std::uint8_t>;  // kSize * kSize * 4, RGBA, row 0 at the top

void put(Image& image, std::size_t pixel, Rgb c) {
    image[pixel * 4 + 0] = c.r;
    image[pixel * 4 + 1] = c.g;
    image[pixel * 4 + 2] = c.b;
    image[pixel * 4 + 3] = 255;
}

// The range of view depths a scene's grey images share, so that one grey
// means one depth in every picture of the scene.
struct DepthRange {
    float nearest = std::numeric_limits<float>::infinity();
    float farthest = -std::numeric_limits<float>::infinity();
    void extend(const std::vector<float>& depths) {
        for (float d : depths) {
            if (!std::isfinite(d)) continue;
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
        }
    }
};

// Near is light (grey 240), far is dark (grey 48); no surface is kNothing.
Image depthImage(const std::vector<float>& depths, const DepthRange& range) {
    Image image(depths.size() * 4);
    const float span = std::max(range.farthest - range.nearest, 1e-6f);
    for (std::size_t p = 0; p < depths.size(); ++p) {
        if (!std::isfinite(depths[p])) {
            put(image, p, kNothing);
            continue;
        }
        const float t = std::clamp((depths[p] - range.nearest) / span, 0.0f, 1.0f);
        const auto grey = static_cast<std::uint8_t>(std::lround(240.0f - 192.0f * t));
        put(image, p, {grey, grey, grey});
    }
    return image;
}

Image leafImage(const std::vector<std::int32_t>& leaves) {
    Image image(leaves.size() * 4);
    for (std::size_t p = 0; p < leaves.size(); ++p) {
        const int leaf = leaves[p];
        put(image, p, leaf < 0 ? kNothing : kLeafColors[static_cast<std::size_t>(leaf) % std::size(kLeafColors)]);
    }
    return image;
}

// RGB = 0.5 * n + 0.5, the usual normal-map colours: +X red, +Y green, +Z blue.
Image normalImage(const std::vector<glm::vec3>& normals, const std::vector<std::int32_t>& leaves) {
    Image image(normals.size() * 4);
    for (std::size_t p = 0; p < normals.size(); ++p) {
        if (leaves[p] < 0) {
            put(image, p, kNothing);
            continue;
        }
        const glm::vec3 c = glm::clamp(normals[p] * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f;
        put(image, p, {static_cast<std::uint8_t>(std::lround(c.x)), static_cast<std::uint8_t>(std::lround(c.y)),
                       static_cast<std::uint8_t>(std::lround(c.z))});
    }
    return image;
}

// Where two results disagree: the first result dimmed, and red where the
// depths differ by more than `tolerance` (or one of them misses).
Image differenceImage(const render::Frame& right, const render::Frame& wrong, float tolerance, int& differing) {
    Image image = right.rgba;
    differing = 0;
    for (std::size_t p = 0; p < right.depth.size(); ++p) {
        const float a = right.depth[p], b = wrong.depth[p];
        const bool same = (std::isinf(a) && std::isinf(b)) || std::abs(a - b) <= tolerance;
        if (same) {
            for (int c = 0; c < 3; ++c) image[p * 4 + c] = static_cast<std::uint8_t>(image[p * 4 + c] / 3 + 100);
        } else {
            put(image, p, {220, 30, 30});
            ++differing;
        }
    }
    return image;
}

class Writer {
public:
    explicit Writer(std::filesystem::path dir) : dir_(std::move(dir)) {}
    void operator()(const std::string& name, const Image& rgba) const {
        io::writePng((dir_ / (name + ".png")).string(), kSize, kSize, rgba);
        std::printf("  wrote %s.png\n", name.c_str());
    }

private:
    std::filesystem::path dir_;
};

scene::Leaf cubeLeaf(glm::dvec3 min, glm::dvec3 max) {
    scene::Leaf leaf;
    leaf.primitive = scene::Cube{max - min, false};
    leaf.transform = glm::translate(glm::dmat4(1.0), min);
    return leaf;
}

scene::Leaf sphereLeaf(double radius, int fn) {
    scene::Sphere sphere;
    sphere.r = radius;
    sphere.fragments.fn = fn;
    scene::Leaf leaf;
    leaf.primitive = sphere;
    return leaf;
}

// ONE leaf holding several sphere shells: a non-convex operand, which a
// single dual-peel pass cannot describe when more than two of its surfaces
// lie on one ray. OpenSCAD's polyhedron lists faces clockwise seen from
// outside, so the tessellated (counter-clockwise) triangles are reversed.
scene::Leaf shellsLeaf(double radius, int fn) {
    scene::Sphere sphere;
    sphere.r = radius;
    sphere.fragments.fn = fn;
    const mesh::Mesh shell = mesh::tessellate(sphere);
    scene::Polyhedron poly;
    for (double z : kSphereZ) {
        const int base = static_cast<int>(poly.points.size());
        for (const glm::dvec3& p : shell.positions) poly.points.push_back(p + glm::dvec3(0.0, 0.0, z));
        for (const auto& t : shell.triangles) {
            poly.faces.push_back({base + static_cast<int>(t[2]), base + static_cast<int>(t[1]),
                                  base + static_cast<int>(t[0])});
        }
    }
    scene::Leaf leaf;
    leaf.primitive = poly;
    return leaf;
}

render::Frame draw(render::Renderer& renderer, const scene::Tree& tree, const camera::Camera& camera,
                   render::RenderSettings settings) {
    renderer.setScene(tree, model::buildModel(tree));
    return renderer.render(camera, settings);
}

void printLayers(const char* what, const render::Frame& frame) {
    std::printf("  %s: layers per leaf", what);
    for (int n : frame.stats.layersPerLeaf) std::printf(" %d", n);
    std::printf("; covered pixels %zu; tiles %d\n", frame.stats.coveredPixels, frame.stats.tiles);
}

// Writes every kept peel layer as two grey images, <prefix>-leafL-layerK-{near,far}.
void writeLayers(const Writer& write, const std::string& prefix, const render::Frame& frame,
                 const DepthRange& range) {
    for (const render::PeelLayerImage& layer : frame.peelLayers) {
        const std::string name =
            prefix + "-leaf" + std::to_string(layer.leaf) + "-layer" + std::to_string(layer.layer);
        write(name + "-near", depthImage(layer.nearDepth, range));
        write(name + "-far", depthImage(layer.farDepth, range));
    }
}

DepthRange rangeOf(const render::Frame& frame) {
    DepthRange range;
    for (const render::PeelLayerImage& layer : frame.peelLayers) {
        range.extend(layer.nearDepth);
        range.extend(layer.farDepth);
    }
    range.extend(frame.depth);
    return range;
}

std::size_t centre(const render::Frame& f) {
    return static_cast<std::size_t>(f.height / 2) * static_cast<std::size_t>(f.width) +
           static_cast<std::size_t>(f.width / 2);
}

int stackFigures(render::Renderer& renderer, const Writer& write) {
    std::printf("stack: a block minus one operand of three sphere shells on the view axis\n");
    scene::Tree tree;
    const int block = tree.addLeaf(cubeLeaf({-2.0, -2.0, -kBlockHalf}, {2.0, 2.0, kBlockHalf}));
    const int shells = tree.addLeaf(shellsLeaf(kSphereRadius, 32));
    tree.root = tree.addNode(NodeKind::Difference, {block, shells});

    // Nearly straight down the stack: 12 degrees off the Z axis, so the
    // block's side shows, and the centre ray still crosses all six shells.
    const double tilt = 12.0 * std::numbers::pi / 180.0;
    camera::Camera camera;
    camera.center = {0.0, 0.0, 0.0};
    camera.eye = 18.0 * glm::dvec3(-std::sin(tilt) * 0.6, -std::sin(tilt) * 0.8, std::cos(tilt));
    camera.width = camera.height = kSize;

    render::RenderSettings automatic;
    automatic.keepPeelLayers = true;
    const render::Frame right = draw(renderer, tree, camera, automatic);
    render::RenderSettings one;
    one.layers = 1;  // its layer 0 is auto's layer 0: not written again
    const render::Frame wrong = draw(renderer, tree, camera, one);
    printLayers("auto", right);
    printLayers("--layers 1", wrong);

    const DepthRange range = rangeOf(right);
    writeLayers(write, "stack-auto", right, range);
    write("stack-auto-depth", depthImage(right.depth, range));
    write("stack-auto-leaf", leafImage(right.leaf));
    write("stack-auto-normal", normalImage(right.normal, right.leaf));
    write("stack-auto-shaded", right.rgba);
    write("stack-one-depth", depthImage(wrong.depth, range));
    write("stack-one-leaf", leafImage(wrong.leaf));
    write("stack-one-shaded", wrong.rgba);
    int differing = 0;
    // 1e-4 of the scene's diagonal, the accuracy suite's depth tolerance.
    const float tolerance = 1e-4f * static_cast<float>(std::sqrt(4.0 * 4.0 * 2.0 + 7.6 * 7.6));
    write("stack-difference", differenceImage(right, wrong, tolerance, differing));
    std::printf("  pixels whose depth differs (one layer against auto): %d of %d\n", differing, kSize * kSize);

    const std::size_t c = centre(right);
    std::printf("  centre pixel: auto depth %.4f leaf %d; one layer depth %.4f leaf %d\n", right.depth[c],
                right.leaf[c], wrong.depth[c], wrong.leaf[c]);

    // The same frame in tiles: a budget too small for the whole frame's layers.
    render::RenderSettings tight;
    tight.memoryBudget = std::size_t(256) << 10;  // 256 KiB
    const render::Frame tiled = draw(renderer, tree, camera, tight);
    // The tiles' viewports differ, so the rasterizer may interpolate a depth
    // a few ulps apart: count what differs beyond the tolerance.
    int tiledDiffering = 0;
    float largest = 0.0f;
    for (std::size_t p = 0; p < right.depth.size(); ++p) {
        const float a = right.depth[p], b = tiled.depth[p];
        const bool bothMiss = std::isinf(a) && std::isinf(b);
        if (!bothMiss) largest = std::max(largest, std::abs(a - b));
        if (right.leaf[p] != tiled.leaf[p] || (!bothMiss && !(std::abs(a - b) <= tolerance))) ++tiledDiffering;
    }
    std::printf("  with a budget of 256 KiB: %d tiles, texture %zu bytes; against one tile: %d pixels differ, "
                "largest depth difference %.3g\n",
                tiled.stats.tiles, tiled.stats.textureBytes, tiledDiffering, largest);
    for (const std::string& note : tiled.stats.notes) std::printf("    note: %s\n", note.c_str());
    std::printf("  one tile: texture %zu bytes\n", right.stats.textureBytes);

    int failures = 0;
    if (right.stats.layersPerLeaf != std::vector<int>{1, 3}) {
        std::fprintf(stderr, "stack: expected 1 layer for the block and 3 for the shells\n");
        ++failures;
    }
    if (differing < kSize * kSize / 100) {
        std::fprintf(stderr, "stack: the one-layer render should differ visibly from auto\n");
        ++failures;
    }
    const int shellsIndex = tree.nodes[static_cast<std::size_t>(shells)].leaf;  // addLeaf gave a node index
    if (std::isfinite(wrong.depth[c]) || !std::isfinite(right.depth[c]) || right.leaf[c] != shellsIndex) {
        std::fprintf(stderr, "stack: expected a through-hole with one layer and a cavity with auto at the centre\n");
        ++failures;
    }
    if (tiled.stats.tiles < 2 || tiledDiffering != 0) {
        std::fprintf(stderr, "stack: tiling should split the frame and change no pixel beyond the tolerance\n");
        ++failures;
    }
    return failures;
}

int cheeseFigures(render::Renderer& renderer, const Writer& write) {
    std::printf("cheese: a cube and a sphere, the paper's three operations\n");
    auto makeTree = [](NodeKind kind) {
        scene::Tree tree;
        const int cube = tree.addLeaf(cubeLeaf({-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}));
        const int sphere = tree.addLeaf(sphereLeaf(1.3, 48));
        tree.root = tree.addNode(kind, {cube, sphere});
        return tree;
    };
    // OpenSCAD's default view, fitted to the cube: what `strata-render` shows.
    mesh::Bounds bounds;
    bounds.extend(glm::dvec3(-1.0));
    bounds.extend(glm::dvec3(1.0));
    camera::Camera base;
    base.width = base.height = kSize;
    const camera::Camera camera = camera::defaultCamera(bounds, base);

    render::RenderSettings settings;
    settings.keepPeelLayers = true;
    const render::Frame difference = draw(renderer, makeTree(NodeKind::Difference), camera, settings);
    printLayers("difference", difference);
    const DepthRange range = rangeOf(difference);
    writeLayers(write, "cheese", difference, range);
    write("cheese-depth", depthImage(difference.depth, range));
    write("cheese-leaf", leafImage(difference.leaf));
    write("cheese-normal", normalImage(difference.normal, difference.leaf));
    write("cheese-difference", difference.rgba);

    settings.keepPeelLayers = false;
    write("cheese-union", draw(renderer, makeTree(NodeKind::Union), camera, settings).rgba);
    write("cheese-intersection", draw(renderer, makeTree(NodeKind::Intersection), camera, settings).rgba);
    for (const char* scheme : {"Metallic", "Tomorrow Night", "Sunset"}) {
        settings.colorScheme = scheme;
        std::string name = scheme;
        std::transform(name.begin(), name.end(), name.begin(),
                       [](char ch) { return ch == ' ' ? '-' : static_cast<char>(std::tolower(ch)); });
        write("cheese-scheme-" + name, draw(renderer, makeTree(NodeKind::Difference), camera, settings).rgba);
    }
    if (difference.stats.layersPerLeaf != std::vector<int>{1, 1}) {
        std::fprintf(stderr, "cheese: convex operands should take one layer each\n");
        return 1;
    }
    return 0;
}

// Which form of the evaluator drew each 16x16 block (RenderSettings::
// keepBlockForms), over the shaded image: a cube with four holes in front
// and a cluster of twelve small ones on top, united with a lens (a sphere
// cut by a box) that overlaps part of the cluster. The cube alone: the
// first-surface form; a few holes: the register form; the cluster: the
// product form (more than eight operands under one AND); cluster and lens
// together: the array form (more than eight, not one AND or OR).
int formFigures(render::Renderer& renderer, const Writer& write) {
    std::printf("forms: the evaluator's form per 16x16 block\n");
    scene::Tree tree;
    std::vector<int> body{tree.addLeaf(cubeLeaf({-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}))};
    auto addSphere = [&](std::vector<int>& to, glm::dvec3 centre, double radius) {
        scene::Leaf leaf = sphereLeaf(radius, 16);
        leaf.transform = glm::translate(glm::dmat4(1.0), centre);
        to.push_back(tree.addLeaf(std::move(leaf)));
    };
    for (double x : {-0.5, 0.5}) {
        for (double z : {-0.5, 0.4}) addSphere(body, {x, -1.0, z}, 0.28);
    }
    for (int i = 0; i < 12; ++i) addSphere(body, {-0.45 + 0.1 * (i % 4), -0.1 + 0.1 * (i / 4), 1.0}, 0.14);
    const int holed = tree.addNode(NodeKind::Difference, body);
    std::vector<int> lens;
    addSphere(lens, {0.1, 0.45, 1.1}, 0.4);
    lens.push_back(tree.addLeaf(cubeLeaf({-0.35, 0.05, 1.0}, {0.55, 0.9, 1.8})));
    tree.root = tree.addNode(NodeKind::Union, {holed, tree.addNode(NodeKind::Intersection, lens)});

    mesh::Bounds bounds;
    bounds.extend(glm::dvec3(-1.0));
    bounds.extend(glm::dvec3(1.0, 1.0, 1.6));
    camera::Camera base;
    base.width = base.height = kSize;
    const camera::Camera camera = camera::defaultCamera(bounds, base);
    render::RenderSettings settings;
    settings.keepBlockForms = true;
    const render::Frame frame = draw(renderer, tree, camera, settings);
    const render::FrameStats& s = frame.stats;
    std::printf("  blocks: first-surface %zu, register %zu, product %zu, array %zu (of %d)\n",
                s.firstSurfaceBlocks, s.registerBlocks, s.productBlocks, s.arrayBlocks, (kSize / 16) * (kSize / 16));

    // Each drawn block tinted by its form; undrawn blocks dimmed.
    constexpr Rgb kFormColors[] = {{0, 0, 0}, {0, 158, 115}, {86, 180, 233}, {230, 159, 0}, {204, 121, 167}};
    Image image = frame.rgba;
    for (std::size_t p = 0; p < frame.blockForms.size(); ++p) {
        const auto form = static_cast<std::size_t>(frame.blockForms[p]);
        const std::size_t x = p % kSize, y = p / kSize;
        const bool edge = x % 16 == 0 || (kSize - 1 - y) % 16 == 0;  // blocks count from the bottom row
        for (int c = 0; c < 3; ++c) {
            const int shaded = image[p * 4 + static_cast<std::size_t>(c)];
            const Rgb tint = kFormColors[form];
            const int t = c == 0 ? tint.r : c == 1 ? tint.g : tint.b;
            const int v = form == 0 ? shaded / 2 + 40 : (edge ? t * 3 / 4 : (shaded + t) / 2);
            image[p * 4 + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(v);
        }
    }
    write("forms", image);
    const bool all = s.firstSurfaceBlocks > 0 && s.registerBlocks > 0 && s.productBlocks > 0 && s.arrayBlocks > 0;
    if (!all) std::fprintf(stderr, "forms: every form should draw some blocks\n");
    return all ? 0 : 1;
}

// The compiled code of a small tree, as docs/algorithm.md lists it:
// (A ∪ B) − (C ∩ D) − E. Only the tree matters here, not the meshes.
void printProgram() {
    scene::Tree tree;
    std::vector<int> leaf;
    for (int i = 0; i < 5; ++i) leaf.push_back(tree.addLeaf(sphereLeaf(1.0, 8)));
    const int ab = tree.addNode(NodeKind::Union, {leaf[0], leaf[1]});
    const int cd = tree.addNode(NodeKind::Intersection, {leaf[2], leaf[3]});
    tree.root = tree.addNode(NodeKind::Difference, {ab, cd, leaf[4]});
    const csg::CompiledTree compiled = csg::compileTree(tree);
    std::printf("program of (A u B) - (C n D) - E, operands A..E = 0..4, stack depth %d:\n", compiled.stackDepth);
    std::string text = csg::disassemble(compiled);
    std::printf("%s", text.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: strata-algorithm-figures OUTPUT_DIR\n");
        return 2;
    }
    try {
        const std::filesystem::path dir = argv[1];
        std::filesystem::create_directories(dir);
        gpu::Context context;  // first made, last destroyed
        std::printf("renderer: %s\n", context.renderer().c_str());
        render::Renderer renderer;
        const Writer write(dir);
        printProgram();
        const int failures =
            stackFigures(renderer, write) + cheeseFigures(renderer, write) + formFigures(renderer, write);
        if (failures != 0) {
            std::fprintf(stderr, "strata-algorithm-figures: %d figure(s) contradict docs/algorithm.md\n", failures);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strata-algorithm-figures: %s\n", e.what());
        return 1;
    }
}
