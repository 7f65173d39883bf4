#include "strata/mesh/Surface.h"

#include <png.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <locale.h>

#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/core/LexicalCast.h"
#include "strata/mesh/VertexBudget.h"

// surface() as OpenSCAD 2021.01 builds it (src/surface.cc, SurfaceNode):
//
// - The file is a PNG image when it starts with the PNG signature, else .dat
//   text. A PNG pixel (decoded to 8-bit RGBA as lodepng does: 16-bit samples
//   keep their high byte, low-depth grey is scaled to 0..255, palettes are
//   looked up) at column x, row y becomes the height
//   100/255 * (invert ? 1 - lum : lum), lum = 0.2126 R + 0.7152 G + 0.0722 B,
//   at grid row height-1-y, column x. `invert` only affects images.
// - .dat text: lines of numbers separated by spaces or tabs; empty lines and
//   lines starting with '#' (after trimming) are skipped; row i, token j is the
//   height at grid row i, column j. Short rows leave zeros.
// - Each grid cell becomes 4 triangles fanning to its centre at the mean of its
//   4 corner heights; the sides and the base sit at min(0, lowest - 1). The
//   polygons are split into triangles as OpenSCAD's preview renderer splits
//   them (src/renderer.cc): a quad (0,1,2,3) into (0,1,3) and (2,3,1), a larger
//   polygon (the base) into a fan around the average of its vertices. OpenSCAD
//   lists these polygons counter-clockwise seen from outside already.
//
// Where 2021.01 only warns, strata throws: an unreadable file, an undecodable
// PNG, an illegal .dat value (OpenSCAD stops reading there), non-finite
// heights. A grid with fewer than 2 rows or columns (OpenSCAD's flat,
// zero-volume sheet) gives an empty mesh, as does an empty .dat file.

namespace strata::mesh {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
    throw Error("surface: cannot read '" + path + "': " + why);
}

// The heights, row-major: lines x columns, missing entries 0.
struct HeightMap {
    int lines = 0;
    int columns = 0;
    std::vector<double> z;  // lines * columns
    double minVal = 0;      // min(0, lowest value read - 1): missing entries do not count
    double at(int i, int j) const {
        return z[static_cast<std::size_t>(i) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(j)];
    }
};

void checkGridSize(const std::string& path, std::uint64_t lines, std::uint64_t columns) {
    // Vertices of the mesh: the grid, the cell centres, the base ring and its centre.
    if (lines > kMaxVertices || columns > kMaxVertices ||
        2 * lines * columns + 2 * (lines + columns) + 1 > kMaxVertices) {
        throw Error("surface: '" + path + "' is too large (" + std::to_string(columns) + " x " + std::to_string(lines) +
                    " values, at most about " + std::to_string(kMaxVertices / 2) + ")");
    }
}

// ---------------------------------------------------------------------------
// .dat text

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

// Long, and kept in one piece: it reproduces OpenSCAD's line reader for
// .dat files rule by rule (comments, blank lines, short rows, where reading
// stops), whose rules depend on the line before.
HeightMap readDat(const std::string& path, const std::string& bytes) {
    const std::string_view text(bytes);
    std::size_t pos = 0;
    bool eof = false;
    // std::getline on the file: eof is set when a read reaches the end of the data.
    auto getline = [&](std::string_view& line) {
        if (pos >= text.size()) {
            eof = true;
            line = {};
            return;
        }
        const std::size_t nl = text.find('\n', pos);
        if (nl == std::string_view::npos) {
            line = text.substr(pos);
            pos = text.size();
            eof = true;
        } else {
            line = text.substr(pos, nl - pos);
            pos = nl + 1;
        }
    };

    struct Entry {
        int row, col;
        double z;
    };
    std::vector<Entry> entries;
    int lines = 0, columns = 0;
    int row = 0;
    std::size_t lineNumber = 0;
    while (!eof) {
        std::string_view line;
        while (!eof && (line.empty() || line.front() == '#')) {
            getline(line);
            ++lineNumber;
            line = trim(line);
        }
        if (line.empty() && eof) break;
        int col = 0;
        bool stop = false;
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
            if (i >= line.size()) break;
            std::size_t j = i;
            while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
            const std::string_view token = line.substr(i, j - i);
            i = j;
            double v = 0.0;
            if (!lexicalCastDouble(token, v)) {
                // OpenSCAD stops reading here; it warns unless this is the last line.
                if (!eof) {
                    throw Error("surface: illegal value '" + std::string(token.substr(0, 40)) + "' in '" + path +
                                "' (line " + std::to_string(lineNumber) + ")");
                }
                stop = true;
                break;
            }
            if (!std::isfinite(v)) {
                throw Error("surface: non-finite value '" + std::string(token) + "' in '" + path + "' (line " +
                            std::to_string(lineNumber) + ")");
            }
            if (col >= std::numeric_limits<int>::max() - 1) throw Error("surface: '" + path + "' has too many columns");
            entries.push_back({row, col, v});
            ++col;
            if (col > columns || row + 1 > lines) {
                columns = std::max(columns, col);
                lines = std::max(lines, row + 1);
                checkGridSize(path, static_cast<std::uint64_t>(lines), static_cast<std::uint64_t>(columns));
            }
        }
        if (stop) break;
        ++row;
    }

    HeightMap map;
    if (entries.empty()) return map;
    map.lines = lines;
    map.columns = columns;
    map.z.assign(static_cast<std::size_t>(lines) * static_cast<std::size_t>(columns), 0.0);
    for (const Entry& e : entries) {
        map.z[static_cast<std::size_t>(e.row) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(e.col)] =
            e.z;
        map.minVal = std::min(e.z - 1, map.minVal);
    }
    return map;
}

// ---------------------------------------------------------------------------
// PNG

struct PngSource {
    const unsigned char* data;
    std::size_t size;
    std::size_t pos;
};

struct PngDecode {
    std::vector<unsigned char> rgb;  // width * height * 3
    std::vector<png_bytep> rows;
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    char message[200] = {0};
    bool tooLarge = false;
};

void pngError(png_structp png, png_const_charp message) {
    auto* d = static_cast<PngDecode*>(png_get_error_ptr(png));
    std::snprintf(d->message, sizeof d->message, "%s", message ? message : "error");
    png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}

void pngRead(png_structp png, png_bytep out, png_size_t length) {
    auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
    if (length > src->size - src->pos) png_error(png, "truncated file");
    std::memcpy(out, src->data + src->pos, length);
    src->pos += length;
}

// All of libpng's state lives in *d and in the libpng structures, so the
// longjmp of an error skips no C++ destructor. Returns false on error.
bool decodePngRows(png_structp png, png_infop info, PngDecode* d) {
    if (setjmp(png_jmpbuf(png))) return false;
    // lodepng refuses a chunk with a bad CRC, ancillary ones too.
    png_set_crc_action(png, PNG_CRC_DEFAULT, PNG_CRC_ERROR_QUIT);
    png_set_user_limits(png, 1u << 24, 1u << 24);
    png_set_chunk_malloc_max(png, 8u << 20);
    // Text, colour profiles and the other ancillary chunks are skipped
    // unread: a heightmap needs none, and libpng would otherwise allocate
    // what a chunk's length claims (a 44-byte file claiming 2 GiB of text:
    // the chunk limit above is only a warning to a reader).
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, nullptr, -1);
    png_read_info(png, info);
    d->width = png_get_image_width(png, info);
    d->height = png_get_image_height(png, info);
    if (std::uint64_t(d->width) * std::uint64_t(d->height) * 2 + 2 * (std::uint64_t(d->width) + d->height) + 1 >
        kMaxVertices) {
        d->tooLarge = true;
        return false;
    }
    const int colorType = png_get_color_type(png, info);
    const int bitDepth = png_get_bit_depth(png, info);
    // To 8-bit RGB as lodepng's conversion to RGBA gives it (alpha is not used).
    if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if ((colorType & PNG_COLOR_MASK_COLOR) == 0 && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (bitDepth == 16) png_set_strip_16(png);  // keeps the high byte, as lodepng does
    if ((colorType & PNG_COLOR_MASK_COLOR) == 0) png_set_gray_to_rgb(png);
    // A palette or grey image with a tRNS chunk expands to an alpha channel too.
    if ((colorType & PNG_COLOR_MASK_ALPHA) || png_get_valid(png, info, PNG_INFO_tRNS)) png_set_strip_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != std::size_t(d->width) * 3) png_error(png, "unexpected pixel format");
    d->rgb.resize(std::size_t(d->width) * std::size_t(d->height) * 3);
    d->rows.resize(d->height);
    for (png_uint_32 y = 0; y < d->height; ++y) d->rows[y] = d->rgb.data() + std::size_t(y) * std::size_t(d->width) * 3;
    png_read_image(png, d->rows.data());
    png_read_end(png, nullptr);
    return true;
}

HeightMap readPng(const std::string& path, const std::string& bytes, bool invert) {
    PngDecode d;
    PngSource src{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &d, pngError, pngWarning);
    if (!png) fail(path, "out of memory");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        fail(path, "out of memory");
    }
    png_set_read_fn(png, &src, pngRead);
    bool ok = false;
    try {
        ok = decodePngRows(png, info, &d);
    } catch (...) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw;
    }
    png_destroy_read_struct(&png, &info, nullptr);
    if (d.tooLarge) checkGridSize(path, d.height, d.width);
    if (!ok) fail(path, std::string("not a valid PNG image (") + d.message + ")");

    HeightMap map;
    map.lines = static_cast<int>(d.height);
    map.columns = static_cast<int>(d.width);
    map.z.resize(std::size_t(d.width) * std::size_t(d.height));
    for (png_uint_32 y = 0; y < d.height; ++y) {
        for (png_uint_32 x = 0; x < d.width; ++x) {
            const unsigned char* p = d.rgb.data() + (std::size_t(y) * d.width + x) * 3;
            const double pixel = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            const double z = 100.0 / 255 * (invert ? 1 - pixel : pixel);
            map.z[std::size_t(d.height - 1 - y) * d.width + x] = z;
            map.minVal = std::min(z - 1, map.minVal);
        }
    }
    return map;
}

// ---------------------------------------------------------------------------
// The solid

class SurfaceBuilder {
public:
    SurfaceBuilder(const HeightMap& map, bool center) : map_(map), l_(map.lines), c_(map.columns) {
        ox_ = center ? -(c_ - 1) / 2.0 : 0;
        oy_ = center ? -(l_ - 1) / 2.0 : 0;
        minVal_ = map.minVal;
    }

    Mesh build() {
        const std::size_t grid = std::size_t(l_) * std::size_t(c_);
        mesh_.positions.reserve(grid * 2 + 2 * std::size_t(l_ + c_) + 1);
        mesh_.triangles.reserve((std::size_t(l_) - 1) * (std::size_t(c_) - 1) * 4 + 4 * std::size_t(l_ + c_) +
                                2 * std::size_t(l_ + c_));
        // Grid vertices (row i, column j) at index i*c + j.
        for (int i = 0; i < l_; ++i)
            for (int j = 0; j < c_; ++j) mesh_.positions.push_back({ox_ + j, oy_ + i, map_.at(i, j)});
        // Base ring: -1 where a grid point has no base vertex (interior points).
        bottom_.assign(grid, UINT32_MAX);

        for (int i = 1; i < l_; ++i) {
            for (int j = 1; j < c_; ++j) {
                const double v1 = map_.at(i - 1, j - 1);
                const double v2 = map_.at(i - 1, j);
                const double v3 = map_.at(i, j - 1);
                const double v4 = map_.at(i, j);
                const double vx = (v1 + v2 + v3 + v4) / 4;
                const uint32_t centre = add({ox_ + j - 0.5, oy_ + i - 0.5, vx});
                const uint32_t a = top(i - 1, j - 1), b = top(i - 1, j), c = top(i, j - 1), d = top(i, j);
                tri(a, b, centre);
                tri(b, d, centre);
                tri(d, c, centre);
                tri(c, a, centre);
            }
        }
        for (int i = 1; i < l_; ++i) {
            // x = 0 side, appended as listed.
            quad({bottomAt(i - 1, 0), top(i - 1, 0), top(i, 0), bottomAt(i, 0)});
            // x = columns-1 side, listed by insert_vertex (reversed).
            quad({bottomAt(i, c_ - 1), top(i, c_ - 1), top(i - 1, c_ - 1), bottomAt(i - 1, c_ - 1)});
        }
        for (int i = 1; i < c_; ++i) {
            // y = 0 side, inserted (reversed).
            quad({bottomAt(0, i), top(0, i), top(0, i - 1), bottomAt(0, i - 1)});
            // y = lines-1 side, appended.
            quad({bottomAt(l_ - 1, i - 1), top(l_ - 1, i - 1), top(l_ - 1, i), bottomAt(l_ - 1, i)});
        }
        // The base, inserted vertex by vertex: the final order is the reverse.
        std::vector<uint32_t> inserted;
        for (int i = 0; i < c_ - 1; ++i) inserted.push_back(bottomAt(0, i));
        for (int i = 0; i < l_ - 1; ++i) inserted.push_back(bottomAt(i, c_ - 1));
        for (int i = c_ - 1; i > 0; i--) inserted.push_back(bottomAt(l_ - 1, i));
        for (int i = l_ - 1; i > 0; i--) inserted.push_back(bottomAt(i, 0));
        polygon(std::vector<uint32_t>(inserted.rbegin(), inserted.rend()));

        for (const glm::dvec3& p : mesh_.positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                throw Error("surface: the heights overflow (a vertex is not finite)");
            }
        }
        return std::move(mesh_);
    }

private:
    uint32_t add(const glm::dvec3& p) {
        mesh_.positions.push_back(p);
        return static_cast<uint32_t>(mesh_.positions.size() - 1);
    }
    uint32_t top(int i, int j) const {
        return static_cast<uint32_t>(std::size_t(i) * std::size_t(c_) + std::size_t(j));
    }
    // The base vertex below grid point (row i, column j).
    uint32_t bottomAt(int i, int j) {
        uint32_t& id = bottom_[std::size_t(i) * std::size_t(c_) + std::size_t(j)];
        if (id == UINT32_MAX) id = add({ox_ + j, oy_ + i, minVal_});
        return id;
    }
    void tri(uint32_t a, uint32_t b, uint32_t c) { mesh_.triangles.push_back({a, b, c}); }
    void quad(const std::array<uint32_t, 4>& q) {
        tri(q[0], q[1], q[3]);
        tri(q[2], q[3], q[1]);
    }
    void polygon(const std::vector<uint32_t>& loop) {
        const std::size_t n = loop.size();
        if (n == 3) {
            tri(loop[0], loop[1], loop[2]);
        } else if (n == 4) {
            quad({loop[0], loop[1], loop[2], loop[3]});
        } else if (n > 4) {
            double sx = 0, sy = 0, sz = 0;
            for (uint32_t id : loop) {
                const glm::dvec3& p = mesh_.positions[id];
                sx += p.x;
                sy += p.y;
                sz += p.z;
            }
            const double count = static_cast<double>(n);
            const uint32_t centre = add({sx / count, sy / count, sz / count});
            for (std::size_t j = 1; j <= n; ++j) tri(centre, loop[j - 1], loop[j % n]);
        }
    }

    const HeightMap& map_;
    int l_, c_;
    double ox_ = 0, oy_ = 0, minVal_ = 0;
    std::vector<uint32_t> bottom_;
    Mesh mesh_;
};

bool isPng(const std::string& bytes) {
    static const unsigned char kSignature[8] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a};
    return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

}  // namespace

Mesh tessellate(const scene::Surface& surface) {
    const std::string bytes = readInputFile(surface.path, "surface");
    const HeightMap map = isPng(bytes) ? readPng(surface.path, bytes, surface.invert) : readDat(surface.path, bytes);
    if (map.lines < 2 || map.columns < 2) return {};
    return SurfaceBuilder(map, surface.center).build();
}

}  // namespace strata::mesh
