#include "OverlayLines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

#include <glm/geometric.hpp>

#include "strata/render/ColorScheme.h"

namespace strata::view {
namespace {

// OpenSCAD's ticks are distance / 60 long, every tenth one twice that.
constexpr double kTickDivisor = 60.0;
constexpr int kTicksPerMajor = 10;

// The small axis cross (GLView::showSmallaxes at one pixel per point): an
// orthographic view of half-height 90 whose origin sits at (-0.8, -0.8) in
// normalized device coordinates, axes 10 long, letters centred 12 out, 3 either side.
constexpr double kGizmoHalfHeight = 90.0, kGizmoAxis = 10.0, kGizmoLabel = 12.0, kGizmoLetter = 3.0;
constexpr double kGizmoInset = 0.1;  // (1 - 0.8) / 2 of the view

glm::vec3 rgb(unsigned v) {
    return {((v >> 16) & 0xff) / 255.0f, ((v >> 8) & 0xff) / 255.0f, (v & 0xff) / 255.0f};
}

}  // namespace

double scaleTickSpacing(double distance) {
    return std::pow(10.0, std::floor(std::log10(std::max(distance, 1e-300)))) / 10.0;
}

std::vector<WorldSegment> axisSegments(double distance, bool ticks) {
    const double l = distance;
    std::vector<WorldSegment> out;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 end(0.0);
        end[axis] = l;
        out.push_back({glm::dvec3(0.0), end, false});
        out.push_back({glm::dvec3(0.0), -end, true});
    }
    if (!ticks) return out;
    const double spacing = scaleTickSpacing(l);
    // Counted, not summed, so the last tick does not drift off by rounding.
    for (int k = 0; k * spacing < l; ++k) {
        const double at = k * spacing;
        const double length = l / (k > 0 && k % kTicksPerMajor == 0 ? kTickDivisor / 2.0 : kTickDivisor);
        for (const double sign : {1.0, -1.0}) {
            const double p = sign * at;
            const bool dashed = sign < 0.0;
            out.push_back({{p, 0, 0}, {p, -length, 0}, dashed});
            out.push_back({{0, p, 0}, {-length, p, 0}, dashed});
            out.push_back({{0, 0, p}, {-length, 0, p}, dashed});
        }
    }
    return out;
}

std::vector<ScreenSegment> gizmoSegments(const render::Camera& camera, const glm::vec3& labelColor) {
    const double pixelsPerUnit = camera.height / 2.0 / kGizmoHalfHeight;
    const glm::dvec2 origin(kGizmoInset * camera.width, kGizmoInset * camera.height);
    const glm::dvec3 right = camera.right(), up = camera.up();
    auto project = [&](const glm::dvec3& p) {
        return origin + pixelsPerUnit * glm::dvec2(glm::dot(p, right), glm::dot(p, up));
    };
    std::vector<ScreenSegment> out;
    const std::array<glm::vec3, 3> colors{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
    std::array<glm::dvec2, 3> labels;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 end(0.0);
        end[axis] = kGizmoAxis;
        out.push_back({origin, project(end), colors[axis]});
        end[axis] = kGizmoLabel;
        const glm::dvec2 at = project(end);
        labels[axis] = {std::round(at.x), std::round(at.y)};
    }
    const double d = kGizmoLetter;
    auto letter = [&](const glm::dvec2& c, glm::dvec2 a, glm::dvec2 b) {
        out.push_back({c + a * d, c + b * d, labelColor});
    };
    // X: two diagonals; Y: one diagonal and half of the other; Z: top, bottom and a diagonal.
    letter(labels[0], {-1, -1}, {1, 1});
    letter(labels[0], {-1, 1}, {1, -1});
    letter(labels[1], {-1, -1}, {1, 1});
    letter(labels[1], {-1, 1}, {0, 0});
    letter(labels[2], {-1, -1}, {1, -1});
    letter(labels[2], {-1, 1}, {1, 1});
    letter(labels[2], {-1, -1}, {1, 1});
    return out;
}

void appendMeshEdges(const geometry::Mesh& mesh, std::vector<glm::vec3>& points) {
    std::unordered_set<std::uint64_t> seen;
    seen.reserve(mesh.triangles.size() * 2);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
            if (!seen.insert((std::uint64_t(a) << 32) | b).second) continue;
            points.emplace_back(mesh.positions[a]);
            points.emplace_back(mesh.positions[b]);
        }
}

glm::vec3 axesColor(std::string_view scheme) {
    struct Entry {
        std::string_view name;
        unsigned color;
    };
    static constexpr std::array<Entry, 10> kAxes{{
        {"BeforeDawn", 0xc1c1c1},
        {"DeepOcean", 0xc1c1c1},
        {"Metallic", 0x222233},
        {"Monotone", 0x191916},
        {"Nature", 0x323232},
        {"Solarized", 0x191816},
        {"Starnight", 0xe5e5e5},
        {"Sunset", 0x220d0d},
        {"Tomorrow Night", 0xe8e8e8},
        {"Tomorrow", 0x181818},
    }};
    const render::ColorScheme& found = render::colorScheme(scheme);
    for (const Entry& e : kAxes)
        if (e.name == found.name) return rgb(e.color);
    // Cornfield's is black; schemes that 2021.01 does not ship get black or
    // Starnight's light grey, whichever stands out from their background.
    const glm::vec4 bg = found.background;
    return 0.299f * bg.r + 0.587f * bg.g + 0.114f * bg.b > 0.5f ? rgb(0x000000) : rgb(0xe5e5e5);
}

}  // namespace strata::view
