#include "strata/core/InputFile.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "strata/core/Error.h"

namespace strata {

std::string unreadableReason(const std::string& path) {
    if (path.empty()) return "no file name";
    if (path.find('\0') != std::string::npos) return "its name holds a NUL byte";
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return errno == ENOENT || errno == ENOTDIR ? "no such file" : std::strerror(errno);
    if (S_ISDIR(st.st_mode)) return "it is a folder";
    if (S_ISFIFO(st.st_mode)) return "it is a FIFO";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "it is a device";
    if (S_ISSOCK(st.st_mode)) return "it is a socket";
    if (!S_ISREG(st.st_mode)) return "it is not a regular file";
    if (::access(path.c_str(), R_OK) != 0) return std::strerror(errno);
    return {};
}

std::string readInputFile(const std::string& path, const char* what, unsigned maxMiB) {
    auto fail = [&](const std::string& why) {
        throw Error(std::string(what) + ": cannot read '" + path + "': " + why);
    };
    std::error_code ec;
    if (const std::string why = unreadableReason(path); !why.empty()) fail(why);
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(ec.message());
    if (size > (std::uintmax_t(maxMiB) << 20)) fail("larger than " + std::to_string(maxMiB) + " MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open it");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size))) fail("read error");
    return bytes;
}

void requireReadable(const std::string& path) {
    const std::string why = unreadableReason(path);
    if (!why.empty()) throw Error(SourceLocation{path, 0, 0}, "cannot read (" + why + ")");
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    return ext;
}

}  // namespace strata
