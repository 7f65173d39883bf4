#pragma once
// Writing strata's images (libpng, OpenEXR): the shaded PNG and the EXR AOVs
// of docs/contract.md. Every image is W*H pixels, row 0 at the TOP (as in
// the files), pixel (i, j) at index j*W + i.
//
// No half-written files: each image is encoded in memory and written, every
// write checked (a full disk is an error, not a truncated file), into an
// unnamed file in the target's folder (O_TMPFILE; where the file system has
// none, a hidden ".strata-PID-N.tmp"), which commit() names and renames into
// place. Stage every output first, then commit them all together, so a
// failure on the last output leaves none of the others behind:
//
//   std::vector<io::StagedFile> staged;
//   staged.push_back(io::stagePng("out.png", w, h, rgba));
//   staged.push_back(io::stageDepthExr("z.exr", w, h, depth));  // may throw: out.png's file goes
//   io::commitAll(staged);                                       // both, or neither

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace strata::io {

// A written file waiting to be renamed onto its target path. Move-only.
// Destroying it uncommitted removes it.
class StagedFile {
public:
    StagedFile() = default;
    StagedFile(StagedFile&& other) noexcept;
    StagedFile& operator=(StagedFile&& other) noexcept;
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;
    ~StagedFile();

    // Writes `bytes` (the file's whole content) for `target`, in the target's
    // folder. Throws strata::Error("<target>: cannot write <what> (...)"),
    // also when no file can be written under that name (no folder; a folder,
    // FIFO or device there; a NUL in the name).
    static StagedFile write(const std::string& target, const std::string& what, const std::vector<unsigned char>& bytes);

    // Renames the file onto the target (replacing an old file of that
    // name). Throws strata::Error("<target>: cannot write (...)") on failure.
    void commit();

    const std::string& target() const noexcept { return target_; }

private:
    friend void commitAll(std::span<StagedFile> files);
    void nameTemporary();
    void discard() noexcept;
    std::string target_;
    std::string folder_;
    std::string named_;  // the file's temporary name while it has one
    int fd_ = -1;
    int slot_ = -1;      // its place in the list a signal handler removes
};

// Commits every file, all or none. Each is given its temporary name first
// and each file it replaces is kept under one too; if a rename then fails,
// the targets already replaced get their old files back (or are removed
// where there was none), and the failing file's error is thrown. Where the
// file system cannot keep an old file under a second name (no hard links),
// a rollback leaves the new file there: the old one is gone.
void commitAll(std::span<StagedFile> files);

// For programs: SIGINT, SIGTERM, SIGHUP and SIGQUIT remove any named
// temporary of a write in progress, then end the process as the signal
// would have. (Unnamed files need no help; SIGKILL cannot be caught, and the
// next write into that folder removes what it left.) SIGXFSZ is ignored, so
// a write past the file-size limit fails with an error like a full disk.
void removeTemporariesOnSignals();

// 8-bit RGBA PNG, straight (unassociated) alpha, written as given.
// rgba: W*H*4 bytes. Throws strata::Error("<path>: cannot write PNG (<why>)").
StagedFile stagePng(const std::string& path, int width, int height, std::span<const std::uint8_t> rgba);

// float32 OpenEXR with one channel named exactly "Z". depth: W*H values; +inf survives.
StagedFile stageDepthExr(const std::string& path, int width, int height, std::span<const float> depth);

// float32 OpenEXR with channels "R", "G", "B". normal: W*H vectors.
StagedFile stageNormalExr(const std::string& path, int width, int height,
                          std::span<const glm::vec3> normal);

// float32 OpenEXR with any channel names; pixels: W*H*channels.size(), interleaved.
StagedFile stageExr(const std::string& path, int width, int height, std::span<const std::string> channels,
                    std::span<const float> pixels);

// Stage and commit in one step.
void writePng(const std::string& path, int width, int height, std::span<const std::uint8_t> rgba);
void writeDepthExr(const std::string& path, int width, int height, std::span<const float> depth);
void writeNormalExr(const std::string& path, int width, int height, std::span<const glm::vec3> normal);

}  // namespace strata::io
