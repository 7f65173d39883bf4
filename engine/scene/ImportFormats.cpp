#include "strata/scene/ImportFormats.h"

#include <array>
#include <vector>

#include "strata/core/InputFile.h"

namespace strata::scene {

namespace {

constexpr std::array<ImportFormat, 6> kFormats{{
    {".stl", ImportKind::Mesh},
    {".off", ImportKind::Mesh},
    {".obj", ImportKind::Mesh},
    {".ply", ImportKind::Mesh},
    {".dxf", ImportKind::Drawing},
    {".svg", ImportKind::Drawing},
}};

}  // namespace

std::span<const ImportFormat> importFormats() { return kFormats; }

bool isImportExtension(std::string_view extension, ImportKind kind) {
    for (const ImportFormat& f : kFormats)
        if (f.kind == kind && f.extension == extension) return true;
    return false;
}

bool isImportPath(const std::string& path, ImportKind kind) { return isImportExtension(lowerExtension(path), kind); }

std::string importExtensionList(ImportKind kind, std::string_view first) {
    std::vector<std::string_view> names;
    for (const ImportFormat& f : kFormats)
        if (f.kind == kind) names.push_back(f.extension);
    std::string list(first);
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (!list.empty()) list += i + 1 == names.size() ? " or " : ", ";
        list += names[i];
    }
    return list;
}

}  // namespace strata::scene
