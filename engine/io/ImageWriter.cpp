#include "strata/io/ImageWriter.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "strata/core/Error.h"

namespace strata::io {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void cannotWrite(const std::string& path, const std::string& what, const std::string& why) {
    throw Error(SourceLocation{path, 0, 0}, "cannot write " + what + (why.empty() ? "" : " (" + why + ")"));
}

// A name beside `target`, hidden, unique in this process and among processes:
// "<dir>/.<name>.<pid>-<n>.tmp". Same folder, so the final rename stays on one
// file system and is atomic.
std::string temporaryFor(const std::string& target) {
    static std::atomic<unsigned> counter{0};
    const fs::path path(target);
    // Appended piece by piece: GCC 12's -Wrestrict misfires on `"." + string`.
    std::string name(1, '.');
    name += path.filename().string();
    name += '.';
    name += std::to_string(::getpid());
    name += '-';
    name += std::to_string(counter.fetch_add(1));
    name += ".tmp";
    return (path.parent_path() / name).string();
}

std::string oneLine(std::string s) {
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

void checkSize(const std::string& path, const std::string& what, int width, int height, std::size_t have,
               std::size_t perPixel) {
    if (width <= 0 || height <= 0)
        cannotWrite(path, what, "image size " + std::to_string(width) + "x" + std::to_string(height));
    const std::size_t want = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * perPixel;
    if (have != want)
        cannotWrite(path, what, std::to_string(have) + " values for a " + std::to_string(width) + "x" +
                                    std::to_string(height) + " image, expected " + std::to_string(want));
}

// Writes one image through OpenImageIO into a temporary beside `path`.
StagedFile stage(const std::string& path, const std::string& what, const char* format, const OIIO::ImageSpec& spec,
                 const void* pixels) {
    if (path.empty()) cannotWrite("<empty path>", what, "no file name");
    const fs::path target(path);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) cannotWrite(path, what, "no folder '" + folder.string() + "'");
    if (fs::is_directory(target, ec)) cannotWrite(path, what, "it is a folder");

    const std::string temporary = temporaryFor(path);
    StagedFile staged(temporary, path);  // from here on, any throw removes the temporary

    auto out = OIIO::ImageOutput::create(format);
    if (!out) cannotWrite(path, what, oneLine(OIIO::geterror()));
    if (!out->open(temporary, spec)) cannotWrite(path, what, oneLine(out->geterror()));
    if (!out->write_image(spec.format, pixels)) {
        const std::string why = oneLine(out->geterror());
        out->close();
        cannotWrite(path, what, why);
    }
    if (!out->close()) cannotWrite(path, what, oneLine(out->geterror()));
    return staged;
}

}  // namespace

StagedFile::StagedFile(std::string temporary, std::string target) noexcept
    : temporary_(std::move(temporary)), target_(std::move(target)) {}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : temporary_(std::exchange(other.temporary_, {})), target_(std::exchange(other.target_, {})) {}

StagedFile& StagedFile::operator=(StagedFile&& other) noexcept {
    if (this != &other) {
        discard();
        temporary_ = std::exchange(other.temporary_, {});
        target_ = std::exchange(other.target_, {});
    }
    return *this;
}

StagedFile::~StagedFile() { discard(); }

void StagedFile::discard() noexcept {
    if (temporary_.empty()) return;
    std::error_code ec;
    fs::remove(temporary_, ec);
    temporary_.clear();
}

void StagedFile::commit() {
    if (temporary_.empty()) return;
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        discard();
        throw Error(SourceLocation{target_, 0, 0}, "cannot write (" + why + ")");
    }
    temporary_.clear();
}

StagedFile stagePng(const std::string& path, int width, int height, std::span<const std::uint8_t> rgba) {
    checkSize(path, "PNG", width, height, rgba.size(), 4);
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    // Straight alpha, written as given: without this OpenImageIO assumes
    // premultiplied values and divides colour by alpha on the way out.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("Software", "strata");
    return stage(path, "PNG", "png", spec, rgba.data());
}

StagedFile stageExr(const std::string& path, int width, int height, std::span<const std::string> channels,
                    std::span<const float> pixels) {
    if (channels.empty()) cannotWrite(path, "EXR", "no channels");
    checkSize(path, "EXR", width, height, pixels.size(), channels.size());
    OIIO::ImageSpec spec(width, height, static_cast<int>(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames.assign(channels.begin(), channels.end());
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    for (std::size_t c = 0; c < channels.size(); ++c)
        if (channels[c] == "Z") spec.z_channel = static_cast<int>(c);
    spec.attribute("compression", "zip");
    spec.attribute("Software", "strata");
    return stage(path, "EXR", "openexr", spec, pixels.data());
}

StagedFile stageDepthExr(const std::string& path, int width, int height, std::span<const float> depth) {
    const std::string channels[] = {"Z"};
    return stageExr(path, width, height, channels, depth);
}

StagedFile stageNormalExr(const std::string& path, int width, int height, std::span<const glm::vec3> normal) {
    const std::string channels[] = {"R", "G", "B"};
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be three packed floats");
    const std::span<const float> flat(reinterpret_cast<const float*>(normal.data()), normal.size() * 3);
    return stageExr(path, width, height, channels, flat);
}

void writePng(const std::string& path, int width, int height, std::span<const std::uint8_t> rgba) {
    stagePng(path, width, height, rgba).commit();
}

void writeDepthExr(const std::string& path, int width, int height, std::span<const float> depth) {
    stageDepthExr(path, width, height, depth).commit();
}

void writeNormalExr(const std::string& path, int width, int height, std::span<const glm::vec3> normal) {
    stageNormalExr(path, width, height, normal).commit();
}

}  // namespace strata::io
