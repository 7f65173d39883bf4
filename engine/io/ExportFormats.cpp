#include "strata/io/ExportFormats.h"

#include <array>
#include <cctype>
#include <filesystem>
#include <vector>

namespace strata::io {
namespace {

constexpr std::array<ExportFormat, 6> kFormats{{
    {".stl", ExportKind::Mesh, false},
    {".off", ExportKind::Mesh, false},
    {".obj", ExportKind::Mesh, false},
    {".3mf", ExportKind::Mesh, true},
    {".svg", ExportKind::Drawing, false},
    {".dxf", ExportKind::Drawing, false},
}};

// "a, b or c".
std::string listed(const std::vector<std::string_view>& words) {
    std::string out;
    for (std::size_t k = 0; k < words.size(); ++k) {
        if (k != 0) out += k + 1 == words.size() ? " or " : ", ";
        out += words[k];
    }
    return out;
}

}  // namespace

std::span<const ExportFormat> exportFormats() { return kFormats; }

const ExportFormat* exportFormatOf(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const ExportFormat& format : kFormats)
        if (format.extension == ext) return &format;
    return nullptr;
}

std::string extensionList(ExportKind kind) {
    std::vector<std::string_view> words;
    for (const ExportFormat& format : kFormats)
        if (format.kind == kind) words.push_back(format.extension);
    return listed(words);
}

std::string extensionList() {
    std::vector<std::string_view> words;
    for (const ExportFormat& format : kFormats) words.push_back(format.extension);
    return listed(words);
}

}  // namespace strata::io
