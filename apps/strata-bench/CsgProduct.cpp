#include "CsgProduct.h"

#include <cctype>
#include <cstdlib>
#include <map>
#include <fstream>
#include <type_traits>
#include <variant>

namespace strata::bench {
namespace {

bool convexPrimitive(const scene::Primitive& primitive) {
    return std::visit(
        [](const auto& p) {
            using T = std::decay_t<decltype(p)>;
            return std::is_same_v<T, scene::Cube> || std::is_same_v<T, scene::Sphere> ||
                   std::is_same_v<T, scene::Cylinder> || std::is_same_v<T, scene::Hull>;
        },
        primitive);
}

// The lines of the files leaves come from, each file read once.
class SourceLines {
public:
    const std::string& line(const std::string& path, int number) {
        auto [it, added] = files_.try_emplace(path);
        if (added) {
            std::ifstream in(path);
            for (std::string text; std::getline(in, text);) it->second.push_back(std::move(text));
        }
        const std::vector<std::string>& lines = it->second;
        return number >= 1 && std::size_t(number) <= lines.size() ? lines[std::size_t(number - 1)] : none_;
    }

private:
    std::map<std::string, std::vector<std::string>> files_;
    std::string none_;
};

unsigned convexityOf(const scene::Leaf& leaf, SourceLines& sources) {
    if (convexPrimitive(leaf.primitive) || leaf.where.file.empty() || leaf.where.line < 1) return 1;
    return convexityOnLine(sources.line(leaf.where.file, leaf.where.line));
}

}  // namespace

unsigned convexityOnLine(const std::string& line) {
    static const std::string key = "convexity";
    for (std::size_t at = line.find(key); at != std::string::npos; at = line.find(key, at + key.size())) {
        // A whole argument name: not the tail of a longer identifier.
        if (at > 0) {
            const char before = line[at - 1];
            if (std::isalnum(static_cast<unsigned char>(before)) || before == '_' || before == '$') continue;
        }
        std::size_t p = at + key.size();
        while (p < line.size() && line[p] == ' ') ++p;
        if (p >= line.size() || line[p] != '=') continue;
        ++p;
        while (p < line.size() && line[p] == ' ') ++p;
        const char* start = line.c_str() + p;
        char* end = nullptr;
        const double value = std::strtod(start, &end);
        if (end == start) continue;
        return value >= 1.0 && value < 1e6 ? static_cast<unsigned>(value) : 1u;
    }
    return 1;
}

CsgProducts csgProducts(const scene::Tree& tree, const model::Model& model, std::size_t renderingLimit) {
    CsgProducts out;
    std::vector<std::optional<LeafBox>> boxes(tree.leaves.size());
    for (std::size_t i = 0; i < tree.leaves.size() && i < model.leafMeshes.size(); ++i) {
        const mesh::Mesh& mesh = model.leafMeshes[i];
        if (mesh.triangles.empty()) continue;
        const mesh::Bounds b = mesh::boundsOf(mesh);
        boxes[i] = LeafBox{b.min, b.max};
    }
    out.sum = sumOfProducts(tree, boxes, 2 * renderingLimit);
    if (out.sum.gaveUp) {
        out.unavailable = "gave up: the normalized tree grew past " + std::to_string(out.sum.limit) +
                          " elements (OpenSCAD aborts normalization and draws nothing)";
        return out;
    }
    if (out.sum.products.empty()) {
        out.unavailable = "empty scene: nothing left after normalization";
        return out;
    }
    if (out.sum.primitives() > renderingLimit) {
        out.unavailable = "OpenCSG off: the normalized tree has " + std::to_string(out.sum.primitives()) +
                          " primitives, over " + std::to_string(renderingLimit) +
                          " (OpenSCAD disables OpenCSG rendering)";
        return out;
    }

    std::vector<bool> used(tree.leaves.size(), false);
    for (const NormalizedProduct& product : out.sum.products) {
        for (int leaf : product.intersections) used[std::size_t(leaf)] = true;
        for (int leaf : product.subtractions) used[std::size_t(leaf)] = true;
    }
    SourceLines sources;
    out.leaves.resize(tree.leaves.size());
    for (std::size_t i = 0; i < tree.leaves.size(); ++i) {
        if (!used[i]) continue;
        ProductLeaf& leaf = out.leaves[i];
        leaf.convex = convexPrimitive(tree.leaves[i].primitive);
        leaf.convexity = convexityOf(tree.leaves[i], sources);
        const mesh::Mesh& mesh = model.leafMeshes[i];
        leaf.positions.reserve(mesh.triangles.size() * 9);
        for (const auto& triangle : mesh.triangles)
            for (std::uint32_t v : triangle) {
                const glm::dvec3& p = mesh.positions[v];
                out.bounds.extend(p);
                leaf.positions.insert(leaf.positions.end(),
                                      {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
            }
    }
    return out;
}

}  // namespace strata::bench
