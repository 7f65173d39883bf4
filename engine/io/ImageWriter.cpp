#include "strata/io/ImageWriter.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
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

// Named temporaries that exist right now, for the signal handler to remove:
// fixed slots of fixed size, so that the handler touches no allocator.
constexpr int kSlots = 16;
constexpr std::size_t kSlotBytes = 4096;
char slotPaths[kSlots][kSlotBytes];
std::atomic<bool> slotUsed[kSlots];

int claimSlot(const std::string& path) {
    if (path.size() >= kSlotBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        bool expected = false;
        if (slotUsed[i].compare_exchange_strong(expected, true)) {
            std::memcpy(slotPaths[i], path.c_str(), path.size() + 1);
            return i;
        }
    }
    return -1;  // more than 16 at once: not removed on a signal, still removed on every other path
}

void releaseSlot(int slot) {
    if (slot >= 0) slotUsed[slot] = false;
}

extern "C" void removeTemporariesAndDie(int signal) {
    for (int i = 0; i < kSlots; ++i)
        if (slotUsed[i]) ::unlink(slotPaths[i]);
    ::signal(signal, SIG_DFL);
    ::raise(signal);
}

// "<folder>/.strata-<pid>-<n>.tmp": short whatever the target's name (a
// 255-byte name must still be writable), hidden, unique among processes,
// and in the target's folder so that the rename is atomic.
std::string temporaryName(const fs::path& folder) {
    static std::atomic<unsigned> counter{0};
    return (folder / (".strata-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)) + ".tmp"))
        .string();
}

// Removes temporaries of this naming whose process is gone (killed with
// SIGKILL between writing and renaming); another live process's are left.
void removeStaleTemporaries(const fs::path& folder) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(".strata-", 0) != 0 || !name.ends_with(".tmp")) continue;
        const long pid = std::strtol(name.c_str() + 8, nullptr, 10);
        if (pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
            fs::remove(it->path(), ec);
            ec.clear();
        }
    }
}

// Writes all of `bytes` to `fd` and flushes them to the disk; "" or why not.
std::string writeAll(int fd, const std::vector<unsigned char>& bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? std::strerror(errno) : "nothing written";
        done += static_cast<std::size_t>(n);
    }
    // A file system may report a full disk only when the data reaches it.
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) return std::strerror(errno);
    return {};
}

// Encodes one image through OpenImageIO into memory, then writes the bytes
// into an unnamed file in the target's folder (O_TMPFILE), or where the file
// system has none, into a named temporary there.
StagedFile stage(const std::string& path, const std::string& what, const char* format, const OIIO::ImageSpec& spec,
                 const void* pixels) {
    std::vector<unsigned char> bytes;
    {
        OIIO::Filesystem::IOVecOutput memory(bytes);
        auto out = OIIO::ImageOutput::create(format);
        if (!out) cannotWrite(path, what, oneLine(OIIO::geterror()));
        if (!out->supports("ioproxy") || !out->set_ioproxy(&memory)) {
            cannotWrite(path, what, "OpenImageIO cannot write it to memory");
        }
        // The name is only a label here: the proxy takes the bytes.
        if (!out->open(path, spec)) cannotWrite(path, what, oneLine(out->geterror()));
        if (!out->write_image(spec.format, pixels)) {
            const std::string why = oneLine(out->geterror());
            out->close();
            cannotWrite(path, what, why);
        }
        if (!out->close()) cannotWrite(path, what, oneLine(out->geterror()));
    }
    return StagedFile::write(path, what, bytes);
}

// The folder a file named `path` goes into; throws unless a file can be
// written there under that name (not a folder, FIFO or device).
fs::path checkedFolder(const std::string& path, const std::string& what) {
    if (path.empty()) cannotWrite("<empty path>", what, "no file name");
    if (path.find('\0') != std::string::npos) cannotWrite(path, what, "the name holds a NUL byte");
    const fs::path target(path);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) cannotWrite(path, what, "no folder '" + folder.string() + "'");
    if (fs::is_directory(target, ec)) cannotWrite(path, what, "it is a folder");
    const fs::file_status status = fs::status(target, ec);
    if (!ec && fs::exists(status) && !fs::is_regular_file(status)) cannotWrite(path, what, "it is not a regular file");
    return folder;
}

}  // namespace
StagedFile StagedFile::write(const std::string& target, const std::string& what, const std::vector<unsigned char>& bytes) {
    const std::string folder = checkedFolder(target, what).string();
    removeStaleTemporaries(folder);
    StagedFile staged;
    staged.target_ = target;
    staged.folder_ = folder;
    // An unnamed file: nothing is left behind however the process ends.
    staged.fd_ = ::open(folder.c_str(), O_WRONLY | O_TMPFILE | O_CLOEXEC, 0666);
    if (staged.fd_ < 0) {
        if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL && errno != ENOENT) {
            cannotWrite(target, what, std::strerror(errno));
        }
        // No O_TMPFILE on this file system: a named temporary, removed on
        // every way out but SIGKILL (and then by the next write here).
        staged.named_ = temporaryName(folder);
        staged.slot_ = claimSlot(staged.named_);
        staged.fd_ = ::open(staged.named_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (staged.fd_ < 0) {
            const std::string why = std::strerror(errno);
            releaseSlot(staged.slot_);
            staged.slot_ = -1;
            staged.named_.clear();
            cannotWrite(target, what, why);
        }
    }
    const std::string why = writeAll(staged.fd_, bytes);
    if (!why.empty()) cannotWrite(target, what, why);  // staged's destructor removes what was written
    return staged;
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : target_(std::exchange(other.target_, {})),
      folder_(std::exchange(other.folder_, {})),
      named_(std::exchange(other.named_, {})),
      fd_(std::exchange(other.fd_, -1)),
      slot_(std::exchange(other.slot_, -1)) {}

StagedFile& StagedFile::operator=(StagedFile&& other) noexcept {
    if (this != &other) {
        discard();
        target_ = std::exchange(other.target_, {});
        folder_ = std::exchange(other.folder_, {});
        named_ = std::exchange(other.named_, {});
        fd_ = std::exchange(other.fd_, -1);
        slot_ = std::exchange(other.slot_, -1);
    }
    return *this;
}

StagedFile::~StagedFile() { discard(); }

void StagedFile::discard() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!named_.empty()) ::unlink(named_.c_str());
    named_.clear();
    releaseSlot(slot_);
    slot_ = -1;
}

void StagedFile::commit() {
    if (fd_ < 0) return;
    if (named_.empty()) {
        // Give the unnamed file a temporary name, then rename it into place.
        named_ = temporaryName(folder_);
        slot_ = claimSlot(named_);
        const std::string self = "/proc/self/fd/" + std::to_string(fd_);
        if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, named_.c_str(), AT_SYMLINK_FOLLOW) != 0) {
            const std::string why = std::strerror(errno);
            releaseSlot(slot_);
            slot_ = -1;
            named_.clear();
            discard();
            throw Error(SourceLocation{target_, 0, 0}, "cannot write (" + why + ")");
        }
    }
    const int closed = ::close(fd_);
    fd_ = -1;
    if (closed != 0 || std::rename(named_.c_str(), target_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        discard();
        throw Error(SourceLocation{target_, 0, 0}, "cannot write (" + why + ")");
    }
    named_.clear();
    releaseSlot(slot_);
    slot_ = -1;
}

void removeTemporariesOnSignals() {
    for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        struct sigaction action {};
        action.sa_handler = removeTemporariesAndDie;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
    }
    // A file past the size limit is a failed write (EFBIG), not a dead process.
    ::signal(SIGXFSZ, SIG_IGN);
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
