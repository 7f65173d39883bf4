#pragma once
// Writing strata's images through OpenImageIO: the shaded PNG and the EXR AOVs
// of docs/contract.md. Every image is W*H pixels, row 0 at the TOP (as in
// the files), pixel (i, j) at index j*W + i.
//
// No half-written files: each image goes to a temporary file in the target's
// folder and is renamed into place. Stage every output first, then commit them
// all, so a failure on the last output leaves none of the others behind:
//
//   std::vector<io::StagedFile> staged;
//   staged.push_back(io::stagePng("out.png", w, h, rgba));
//   staged.push_back(io::stageDepthExr("z.exr", w, h, depth));  // may throw: out.png's temporary goes
//   for (auto& s : staged) s.commit();

#include <cstdint>
#include <span>
#include <string>

#include <glm/vec3.hpp>

namespace strata::io {

// A written temporary file waiting to be renamed onto its target path.
// Move-only. Destroying it uncommitted removes the temporary.
class StagedFile {
public:
    StagedFile() = default;
    StagedFile(std::string temporary, std::string target) noexcept;
    StagedFile(StagedFile&& other) noexcept;
    StagedFile& operator=(StagedFile&& other) noexcept;
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;
    ~StagedFile();

    // Renames the temporary onto the target (replacing an old file of that
    // name). Throws strata::Error("<target>: cannot write (...)") on failure.
    void commit();

    const std::string& target() const noexcept { return target_; }
    const std::string& temporary() const noexcept { return temporary_; }

private:
    void discard() noexcept;
    std::string temporary_;
    std::string target_;
};

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
