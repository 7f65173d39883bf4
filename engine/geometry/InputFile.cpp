#include "InputFile.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "strata/core/Error.h"
#include "strata/core/InputFile.h"

namespace strata::geometry::detail {

std::string readInputFile(const std::string& path, const char* node) {
    constexpr std::uintmax_t kMaxBytes = std::uintmax_t(256) << 20;
    auto fail = [&](const std::string& why) {
        throw Error(std::string(node) + ": cannot read '" + path + "': " + why);
    };
    std::error_code ec;
    if (const std::string why = unreadableReason(path); !why.empty()) fail(why);
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(ec.message());
    if (size > kMaxBytes) fail("larger than 256 MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open it");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size))) fail("read error");
    return bytes;
}

}  // namespace strata::geometry::detail
