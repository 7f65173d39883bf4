#include "strata/io/FlatWriter.h"
#include "strata/io/ExportFormats.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include "strata/core/Error.h"

namespace strata::io {
namespace {

// The fewest digits that read back to the same double; "-0" written as "0".
std::string number(double x) {
    if (x == 0.0) return "0";
    char text[32];
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, x);
    return std::string(text, r.ptr);
}

std::string svg(const flat::Outlines& shape) {
    glm::dvec2 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    for (const flat::Outline& o : shape.outlines) {
        for (const glm::dvec2& p : o.points) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    }
    if (shape.outlines.empty()) low = high = glm::dvec2(0.0);
    const glm::dvec2 size = high - low;
    std::string out = "<?xml version=\"1.0\" standalone=\"no\"?>\n"
                      "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" "
                      "\"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">\n";
    out += "<svg width=\"" + number(size.x) + "mm\" height=\"" + number(size.y) + "mm\" viewBox=\"" + number(low.x) +
           " " + number(-high.y) + " " + number(size.x) + " " + number(size.y) +
           "\" xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\">\n<title>strata model</title>\n<path d=\"\n";
    for (const flat::Outline& o : shape.outlines) {
        for (std::size_t i = 0; i < o.points.size(); ++i) {
            out += (i == 0 ? "M " : " L ") + number(o.points[i].x) + "," + number(-o.points[i].y);
        }
        if (!o.points.empty()) out += " z\n";
    }
    out += "\" stroke=\"black\" fill=\"lightgray\" stroke-width=\"0.5\"/>\n</svg>\n";
    return out;
}

// A DXF group: its code right-aligned in three columns, then its value.
void group(std::string& out, int code, const std::string& value) {
    std::string c = std::to_string(code);
    out += std::string(c.size() < 3 ? 3 - c.size() : 0, ' ') + c + "\n" + value + "\n";
}

std::string dxf(const flat::Outlines& shape) {
    std::string out;
    group(out, 0, "SECTION");
    group(out, 2, "BLOCKS");
    group(out, 0, "ENDSEC");
    group(out, 0, "SECTION");
    group(out, 2, "ENTITIES");
    for (const flat::Outline& o : shape.outlines) {
        for (std::size_t i = 0; i < o.points.size(); ++i) {
            const glm::dvec2& a = o.points[i];
            const glm::dvec2& b = o.points[(i + 1) % o.points.size()];
            group(out, 0, "LINE");
            group(out, 8, "0");
            group(out, 10, number(a.x));
            group(out, 20, number(a.y));
            group(out, 11, number(b.x));
            group(out, 21, number(b.y));
        }
    }
    group(out, 0, "ENDSEC");
    group(out, 0, "SECTION");
    group(out, 2, "OBJECTS");
    group(out, 0, "DICTIONARY");
    group(out, 0, "ENDSEC");
    group(out, 0, "EOF");
    return out;
}

}  // namespace

bool isFlatPath(const std::string& path) {
    const ExportFormat* format = exportFormatOf(path);
    return format != nullptr && format->kind == ExportKind::Drawing;
}

FlatFormat flatFormatOf(const std::string& path) {
    const ExportFormat* format = exportFormatOf(path);
    return format != nullptr && format->extension == ".svg" ? FlatFormat::Svg : FlatFormat::Dxf;
}

std::vector<unsigned char> flatBytes(const flat::Outlines& outlines, FlatFormat format) {
    const std::string text = format == FlatFormat::Svg ? svg(outlines) : dxf(outlines);
    return std::vector<unsigned char>(text.begin(), text.end());
}

StagedFile stageFlat(const std::string& path, const flat::Outlines& outlines) {
    return StagedFile::write(path, "drawing", flatBytes(outlines, flatFormatOf(path)));
}

}  // namespace strata::io
