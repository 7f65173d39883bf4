#include "strata/io/ImageWriter.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
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

// The process id of a name temporaryName gives (".strata-<pid>-<n>.tmp",
// both numbers in decimal and nothing else), or 0 for any other name.
long temporaryOwner(const std::string& name) {
    const auto digits = [&](std::size_t from, char end) -> std::size_t {  // past them, at `end`; 0 if none
        std::size_t at = from;
        while (at < name.size() && name[at] >= '0' && name[at] <= '9') ++at;
        return at > from && at - from <= 18 && at < name.size() && name[at] == end ? at : 0;
    };
    if (!name.starts_with(".strata-") || !name.ends_with(".tmp")) return 0;
    const std::size_t dash = digits(8, '-');
    if (dash == 0 || digits(dash + 1, '.') != name.size() - 4) return 0;
    return std::strtol(name.c_str() + 8, nullptr, 10);
}

// Removes temporaries of this naming whose process is gone (killed with
// SIGKILL between writing and renaming): regular files of this user named
// exactly as temporaryName names them. Another live process's are left.
void removeStaleTemporaries(const fs::path& folder) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const long pid = temporaryOwner(it->path().filename().string());
        struct stat status {};
        if (pid <= 0 || ::lstat(it->path().c_str(), &status) != 0 || !S_ISREG(status.st_mode) ||
            status.st_uid != ::getuid())
            continue;
        if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
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

// ---------------------------------------------------------------------------
// PNG through libpng, into memory. libpng reports errors by longjmp, so all
// of its state lives in *e and in libpng's own structures: the jump skips no
// C++ destructor.

struct PngEncode {
    std::vector<unsigned char> bytes;
    char message[200] = {0};
};

void pngError(png_structp png, png_const_charp message) {
    auto* e = static_cast<PngEncode*>(png_get_error_ptr(png));
    std::snprintf(e->message, sizeof e->message, "%s", message ? message : "libpng error");
    png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}

void pngWrite(png_structp png, png_bytep data, png_size_t length) {
    auto* e = static_cast<PngEncode*>(png_get_io_ptr(png));
    bool grown = true;
    try {
        e->bytes.insert(e->bytes.end(), data, data + length);
    } catch (const std::bad_alloc&) {
        grown = false;
    }
    if (!grown) png_error(png, "out of memory");
}

void pngFlush(png_structp) {}

bool writePngRows(png_structp png, png_infop info, int width, int height, const std::uint8_t* rgba, PngEncode* e) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, e, pngWrite, pngFlush);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    // Rendered images are runs of flat or slowly shaded colour: unfiltered
    // rows at zlib's fastest level encode a 1024x768 frame in a third of
    // the time of libpng's defaults (adaptive filters, level 6), for files
    // about 1.4 times as large.
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    png_set_compression_level(png, 1);
    png_text software{};
    software.compression = PNG_TEXT_COMPRESSION_NONE;
    software.key = const_cast<png_charp>("Software");
    software.text = const_cast<png_charp>("strata");
    png_set_text(png, info, &software, 1);
    png_write_info(png, info);
    const std::size_t rowBytes = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y) png_write_row(png, rgba + static_cast<std::size_t>(y) * rowBytes);
    png_write_end(png, info);
    return true;
}

bool encodePng(PngEncode* e, int width, int height, const std::uint8_t* rgba) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, e, pngError, pngWarning);
    if (!png) {
        std::snprintf(e->message, sizeof e->message, "out of memory");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    const bool ok = info != nullptr && writePngRows(png, info, width, height, rgba, e);
    if (!info) std::snprintf(e->message, sizeof e->message, "out of memory");
    png_destroy_write_struct(&png, &info);
    return ok;
}

// ---------------------------------------------------------------------------
// OpenEXR, into memory.

class MemoryStream final : public Imf::OStream {
public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (n < 0) throw std::length_error("negative write");
        const std::size_t end = position_ + static_cast<std::size_t>(n);
        if (end > bytes.size()) bytes.resize(end);
        std::memcpy(bytes.data() + position_, c, static_cast<std::size_t>(n));
        position_ = end;
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t pos) override { position_ = static_cast<std::size_t>(pos); }

    std::vector<unsigned char> bytes;

private:
    std::size_t position_ = 0;
};

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

void StagedFile::nameTemporary() {
    if (fd_ < 0 || !named_.empty()) return;
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

void StagedFile::commit() {
    if (fd_ < 0) return;
    nameTemporary();  // an unnamed file gets a temporary name, then is renamed into place
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

namespace {

// An old file kept under a temporary name while the files of a commitAll
// replace their targets; `kept` empty where there is none or it could not
// be kept.
struct KeptFile {
    bool existed = false;
    std::string kept;
    int slot = -1;
};

// `target`'s present file under a temporary name beside it (a second hard
// link), or none where there is no file or it cannot be linked.
KeptFile keepOldFile(const std::string& target, const std::string& folder) {
    KeptFile old;
    struct stat status {};
    old.existed = ::lstat(target.c_str(), &status) == 0;
    if (!old.existed || !S_ISREG(status.st_mode)) return old;
    old.kept = temporaryName(folder);
    old.slot = claimSlot(old.kept);
    if (::link(target.c_str(), old.kept.c_str()) != 0) {
        releaseSlot(old.slot);
        old = KeptFile{true, {}, -1};
    }
    return old;
}

}  // namespace

void commitAll(std::span<StagedFile> files) {
    if (files.size() == 1) {  // a rename is all or nothing by itself
        files[0].commit();
        return;
    }
    // Every file named first: a failure here has replaced nothing.
    for (StagedFile& file : files) file.nameTemporary();
    std::vector<bool> pending(files.size());
    std::vector<KeptFile> old(files.size());
    for (std::size_t k = 0; k < files.size(); ++k) {
        pending[k] = files[k].fd_ >= 0;
        if (pending[k]) old[k] = keepOldFile(files[k].target_, files[k].folder_);
    }
    const auto dropKept = [&] {
        for (KeptFile& kept : old) {
            if (!kept.kept.empty()) ::unlink(kept.kept.c_str());
            releaseSlot(kept.slot);
        }
    };
    std::size_t done = 0;
    try {
        for (; done < files.size(); ++done) files[done].commit();
    } catch (const Error&) {
        // Put back what the files before the failing one replaced: the old
        // file, or none. (Where an old file was not kept, or cannot be put
        // back, the new one stays rather than neither.)
        for (std::size_t k = 0; k < done; ++k) {
            if (!pending[k]) continue;
            if (!old[k].existed)
                ::unlink(files[k].target_.c_str());
            else if (!old[k].kept.empty() && ::rename(old[k].kept.c_str(), files[k].target_.c_str()) == 0)
                old[k].kept.clear();
        }
        dropKept();
        throw;
    }
    dropKept();
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
    PngEncode e;
    if (!encodePng(&e, width, height, rgba.data())) cannotWrite(path, "PNG", e.message);
    return StagedFile::write(path, "PNG", e.bytes);
}

StagedFile stageExr(const std::string& path, int width, int height, std::span<const std::string> channels,
                    std::span<const float> pixels) {
    if (channels.empty()) cannotWrite(path, "EXR", "no channels");
    checkSize(path, "EXR", width, height, pixels.size(), channels.size());
    MemoryStream memory;
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.lineOrder() = Imf::INCREASING_Y;
        header.insert("Software", Imf::StringAttribute("strata"));
        Imf::FrameBuffer frame;
        const std::size_t stride = channels.size() * sizeof(float);
        for (std::size_t c = 0; c < channels.size(); ++c) {
            if (channels[c].empty()) cannotWrite(path, "EXR", "a channel without a name");
            if (header.channels().findChannel(channels[c]) != nullptr) {
                cannotWrite(path, "EXR", "channel '" + channels[c] + "' twice");
            }
            header.channels().insert(channels[c], Imf::Channel(Imf::FLOAT));
            // The slice's base is only ever offset by in-range pixels.
            char* base = reinterpret_cast<char*>(const_cast<float*>(pixels.data() + c));
            frame.insert(channels[c], Imf::Slice(Imf::FLOAT, base, stride, stride * static_cast<std::size_t>(width)));
        }
        Imf::OutputFile file(memory, header, 1);
        file.setFrameBuffer(frame);
        file.writePixels(height);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& ex) {
        cannotWrite(path, "EXR", oneLine(ex.what()));
    }
    return StagedFile::write(path, "EXR", memory.bytes);
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
