#include "strata/geometry/FlatImport.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "FlatImportDetail.h"
#include "strata/core/Error.h"

// import() of a 2D file, dispatched on the file name's extension (compared in
// lower case) as OpenSCAD 2021.01's ImportModule does: .dxf (FlatImportDxf.cpp)
// or .svg (FlatImportSvg.cpp).

namespace strata::geometry {
namespace detail {

std::string quotedPath(std::string_view path) {
    std::string quoted;
    quoted.reserve(path.size() + 2);
    quoted += '\'';
    quoted += path;
    quoted += '\'';
    return quoted;
}

std::string readImportFile(const std::string& path) {
    constexpr std::uintmax_t kMaxBytes = std::uintmax_t(256) << 20;
    auto fail = [&](const std::string& why) -> void {
        throw Error("import: cannot read " + quotedPath(path) + ": " + why);
    };
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) fail("no such file");
    if (!std::filesystem::is_regular_file(status)) fail("not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(ec.message());
    if (size > kMaxBytes) fail("larger than 256 MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open it");
    std::string text(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(text.data(), static_cast<std::streamsize>(size))) fail("read error");
    return text;
}

}  // namespace detail

Outlines importFlat(const scene::FlatImport& import) {
    std::string ext = std::filesystem::path(import.path).extension().string();
    for (char& c : ext) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    if (ext != ".dxf" && ext != ".svg") {
        throw Error("import: " + detail::quotedPath(import.path) + " is not a 2D file (.dxf or .svg)");
    }
    const std::string text = detail::readImportFile(import.path);
    return ext == ".dxf" ? detail::importDxf(import, text) : detail::importSvg(import, text);
}

}  // namespace strata::geometry
