#include "OverlayLines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

// While the distance is under this many times the power of ten below it,
// every second tick is labelled too (only one or two majors are in view).
constexpr double kMoreLabelsBelow = 3.0;
constexpr int kMoreLabelsEvery = 2;

// A label character's points on a unit cell: x 0 (left) to 1 (right) in the
// reading direction, y 0 (nearest the axis) to 1; A B top, C D middle, E F
// bottom, G H a short stroke at the bottom's middle, I J a short upright one
// through the middle.
glm::dvec2 glyphPoint(char point) {
    switch (point) {
        case 'A': return {0.0, 1.0};
        case 'B': return {1.0, 1.0};
        case 'C': return {0.0, 0.5};
        case 'D': return {1.0, 0.5};
        case 'E': return {0.0, 0.0};
        case 'F': return {1.0, 0.0};
        case 'G': return {0.35, 0.0};
        case 'H': return {0.65, 0.0};
        case 'I': return {0.5, 0.25};
        default: return {0.5, 0.75};  // 'J'
    }
}

// Each character as polylines through those points, separated by blanks.
std::string_view glyphStrokes(char c) {
    switch (c) {
        case '0': return "ABFEA";
        case '1': return "BF";
        case '2': return "ABDCEF";
        case '3': return "ABFE CD";
        case '4': return "ACD BF";
        case '5': return "BACDFE";
        case '6': return "BAEFDC";
        case '7': return "ABF";
        case '8': return "ABFEA CD";
        case '9': return "DCABFE";
        case '-': return "CD";
        case '.': return "GH";
        case 'e': return "DBAEF CD";
        case '+': return "CD IJ";
        default: return "";
    }
}

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

std::vector<ScaleLabel> scaleLabels(double distance) {
    const double l = distance;
    const double spacing = scaleTickSpacing(l);
    const double decade = spacing * 10.0;
    const bool moreLabels = l / decade < kMoreLabelsBelow;
    std::vector<ScaleLabel> out;
    for (int k = 1; k * spacing < l; ++k) {
        if (k % kTicksPerMajor != 0 && !(moreLabels && k % kMoreLabelsEvery == 0)) continue;
        char text[32];
        std::snprintf(text, sizeof text, "%g", k * spacing);
        for (int axis = 0; axis < 3; ++axis) {
            out.push_back({axis, k * spacing, text});
            out.push_back({axis, -k * spacing, std::string("-") + text});
        }
    }
    return out;
}

std::vector<WorldSegment> scaleLabelSegments(double distance) {
    const double u = distance / kTickDivisor;
    const double width = u / 2.0, pitch = 0.75 * u;
    // Distance from the axis of a cell's bottom, middle and top.
    const double bottom = u / 4.0, middle = 7.0 * u / 8.0, top = 5.0 * u / 4.0;
    auto height = [&](double y) {
        return y <= 0.5 ? bottom + (middle - bottom) * y * 2.0 : middle + (top - middle) * (y - 0.5) * 2.0;
    };
    std::vector<WorldSegment> out;
    for (const ScaleLabel& label : scaleLabels(distance)) {
        glm::dvec3 outward(0.0), up(0.0), reading(0.0);
        outward[label.axis] = label.at < 0.0 ? -1.0 : 1.0;
        up[label.axis == 0 ? 1 : 0] = 1.0;
        reading[label.axis] = label.axis == 0 ? 1.0 : -1.0;
        // Characters fill the slots from the tick outwards; the text reads
        // along `reading`, so where that points inwards it is laid last character first.
        const bool readsOutwards = glm::dot(reading, outward) > 0.0;
        const std::size_t n = label.text.size();
        for (std::size_t slot = 0; slot < n; ++slot) {
            const char c = label.text[readsOutwards ? slot : n - 1 - slot];
            const glm::dvec3 centre = outward * (std::abs(label.at) + static_cast<double>(slot) * pitch);
            auto place = [&](char point) {
                const glm::dvec2 g = glyphPoint(point);
                return centre + reading * ((g.x - 0.5) * width) + up * height(g.y);
            };
            const std::string_view strokes = glyphStrokes(c);
            for (std::size_t k = 0; k + 1 < strokes.size(); ++k)
                if (strokes[k] != ' ' && strokes[k + 1] != ' ')
                    out.push_back({place(strokes[k]), place(strokes[k + 1]), false});
        }
    }
    return out;
}

std::vector<ScreenSegment> gizmoSegments(const camera::Camera& camera, const glm::vec3& labelColor) {
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

void appendMeshEdges(const mesh::Mesh& mesh, std::vector<glm::vec3>& points) {
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
