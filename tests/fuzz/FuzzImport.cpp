// libFuzzer targets for the file readers behind import() and surface(): one
// executable per format (STRATA_FUZZ_FORMAT: stl, obj, off, ply, dxf, svg,
// dat, png), each handing the input to the reader as a file of that
// extension, as a scene names one.
//
// Any input must either be read into a well-formed result or throw
// strata::Error; anything else (another exception, a crash, a leak, a
// sanitizer report, a result with indices out of range or non-finite
// numbers) is a finding. scripts/fuzz.sh builds and runs them.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "strata/core/Error.h"
#include "strata/flat/FlatImport.h"
#include "strata/mesh/MeshImport.h"
#include "strata/mesh/Surface.h"

#ifndef STRATA_FUZZ_FORMAT
#error "STRATA_FUZZ_FORMAT names the format (stl, obj, off, ply, dxf, svg, dat, png)"
#endif

namespace {

using namespace strata;

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "strata_fuzz_%s: the reader returned a broken result: %s\n", STRATA_FUZZ_FORMAT, what);
    std::abort();
}

// The file the reader is given: one per process, rewritten for every input.
const std::string& inputPath() {
    static const std::string path = [] {
        const char* dir = std::getenv("TMPDIR");
        return std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/strata-fuzz-" +
               std::to_string(::getpid()) + "." + STRATA_FUZZ_FORMAT;
    }();
    return path;
}

struct RemoveAtExit {
    ~RemoveAtExit() { std::remove(inputPath().c_str()); }
} removeAtExit;

void checkMesh(const mesh::Mesh& mesh) {
    for (const glm::dvec3& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) broken("non-finite vertex");
    }
    for (const auto& t : mesh.triangles) {
        for (const std::uint32_t i : t) {
            if (i >= mesh.positions.size()) broken("triangle index out of range");
        }
    }
}

void checkOutlines(const flat::Outlines& outlines) {
    for (const flat::Outline& outline : outlines.outlines) {
        for (const glm::dvec2& p : outline.points) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) broken("non-finite outline point");
        }
    }
}

void read(const std::string& format, const std::string& path) {
    if (format == "dxf" || format == "svg") {
        scene::FlatImport import;
        import.path = path;
        checkOutlines(flat::importFlat(import));
    } else if (format == "dat" || format == "png") {
        scene::Surface surface;
        surface.path = path;
        checkMesh(mesh::tessellate(surface));
    } else {
        checkMesh(mesh::importMesh(path));
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    {
        std::ofstream out(inputPath(), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) {
            std::fprintf(stderr, "strata_fuzz_%s: cannot write %s\n", STRATA_FUZZ_FORMAT, inputPath().c_str());
            std::abort();
        }
    }
    try {
        read(STRATA_FUZZ_FORMAT, inputPath());
    } catch (const Error&) {
        // Bad input, reported the way it should be.
    }
    return 0;
}
