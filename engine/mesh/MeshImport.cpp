#include "strata/mesh/MeshImport.h"

// OpenMesh wants its IO header before any mesh kernel.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <mutex>
#include <vector>

#include "PlyCheck.h"
#include "PolygonTriangulation.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/scene/ImportFormats.h"

namespace strata::mesh {
namespace {

// Double-precision points. Note OpenMesh 9's readers parse coordinates as
// float (STL is float anyway; OFF, OBJ and PLY lose digits past ~7).
struct DoubleTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
};
// A polygon mesh, not a triangle mesh: OpenMesh's TriMesh would split n-gons
// into fans, which is wrong for non-convex faces; we ear-clip them instead.
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

// OpenMesh reports problems ("complex vertex", reader errors) on its global
// log streams omlog/omout/omerr. They are silenced while a file is read: we
// give our own reasons, and complex faces are judged by checkMesh anyway.
// Disabling, not redirecting: OpenMesh 9's mostream::disconnect() leaks its
// target, which LeakSanitizer reports. The streams are global, hence the lock.
class SilencedOpenMeshLog {
public:
    SilencedOpenMeshLog() : lock_(mutex()) {
        for (auto* s : streams()) {
            s->flush();  // let earlier messages out as they would have gone
            wasEnabled_.push_back(s->is_enabled());
            s->disable();
        }
    }
    ~SilencedOpenMeshLog() {
        const auto ss = streams();
        for (std::size_t i = 0; i < ss.size(); ++i) {
            ss[i]->flush();  // while disabled, flushing drops what was written
            if (wasEnabled_[i]) ss[i]->enable();
        }
    }
    SilencedOpenMeshLog(const SilencedOpenMeshLog&) = delete;
    SilencedOpenMeshLog& operator=(const SilencedOpenMeshLog&) = delete;

private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    static std::vector<OpenMesh::mostream*> streams() { return {&omlog(), &omout(), &omerr()}; }

    std::lock_guard<std::mutex> lock_;
    std::vector<bool> wasEnabled_;
};

// Whether an OFF file is Geomview's binary OFF: the keyword, then BINARY.
bool binaryOff(const std::string& head) {
    std::istringstream words(head.substr(0, std::min(head.find('\n'), head.size())));
    std::string keyword, next;
    words >> keyword >> next;
    return keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0 && next == "BINARY";
}

// The line of the first word of `text` that spells a non-finite number
// ("nan", "inf", "-inf", "infinity", any case), or 0. A reader would take
// such a coordinate, or stop at it and report a short file. Lines that carry
// names or comments (OBJ's o, g, usemtl, mtllib; STL's solid; PLY's comment;
// '#') are not looked at.
std::size_t lineOfNonFiniteWord(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string word;
        if (!(words >> word) || word[0] == '#' || word == "comment" || word == "obj_info" || word == "solid" ||
            word == "endsolid" || word == "o" || word == "g" || word == "usemtl" || word == "mtllib") {
            continue;
        }
        do {
            for (char& ch : word) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            if (word[0] == '-' || word[0] == '+') word.erase(0, 1);
            if (word == "nan" || word == "inf" || word == "infinity") return number;
        } while (words >> word);
    }
    return 0;
}

// Whether the start of a file reads as text (a binary STL or PLY does not).
bool looksLikeText(const std::string& head) {
    for (unsigned char c : head.substr(0, 512))
        if (c == 0 || (c < 32 && !std::isspace(c))) return false;
    return true;
}

// A word of a file as a message quotes it: printable ASCII as it is, other
// bytes as \xNN (a terminal never sees a control byte from the file), and
// at most 32 characters of it.
std::string quotedWord(std::string_view word) {
    std::string out = "'";
    for (std::size_t i = 0; i < word.size() && i < 32; ++i) {
        const auto c = static_cast<unsigned char>(word[i]);
        if (c >= 0x20 && c < 0x7f) {
            out.push_back(static_cast<char>(c));
        } else {
            static const char kHex[] = "0123456789abcdef";
            out += "\\x";
            out.push_back(kHex[c >> 4]);
            out.push_back(kHex[c & 15]);
        }
    }
    if (word.size() > 32) out += "...";
    return out + "'";
}

// Whether all of `word` is one number, read into `value` (from_chars: no
// locale, doubles in full precision; "inf" and "nan" read as numbers).
template <class T>
bool wholeNumber(const std::string& word, T& value) {
    const char* begin = word.data();
    const auto [rest, error] = std::from_chars(begin, begin + word.size(), value);
    return error == std::errc() && rest == begin + word.size();
}

// A Wavefront OBJ's polygons, read by strata itself: its vertices (`v x y z`,
// any further numbers ignored) and faces (`f` with one reference a corner,
// `v`, `v/vt`, `v//vn` or `v/vt/vn`, counted from 1, or back from the last
// vertex read when negative). Every other statement (texture coordinates,
// normals, groups, objects, smoothing, materials, lines, points) carries
// nothing strata draws and is skipped; a line ending in a backslash goes on
// on the next. OpenMesh's reader opens the material files an OBJ names (a
// FIFO or a device included) and asserts on a face whose corners it cannot
// find; this one opens nothing and names the line of any fault.
struct Polygons {
    std::vector<glm::dvec3> positions;
    std::vector<std::vector<uint32_t>> faces;
};

Polygons readObj(const std::string& text, const std::string& path) {
    Polygons obj;
    std::size_t lineNumber = 0, start = 0;
    std::string line;
    auto fail = [&](const std::string& why) {
        return Error(path + ":" + std::to_string(lineNumber) + ": cannot read mesh: " + why);
    };
    while (start < text.size()) {
        // One logical line, joined across backslash-newlines.
        ++lineNumber;
        const std::size_t first = lineNumber;
        line.clear();
        while (start < text.size()) {
            std::size_t end = text.find('\n', start);
            if (end == std::string::npos) end = text.size();
            std::string_view part(text.data() + start, end - start);
            start = end + 1;
            if (!part.empty() && part.back() == '\r') part.remove_suffix(1);
            if (!part.empty() && part.back() == '\\') {
                line.append(part.substr(0, part.size() - 1)).push_back(' ');
                ++lineNumber;
                continue;
            }
            line.append(part);
            break;
        }
        const std::size_t last = lineNumber;
        lineNumber = first;
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword) || keyword[0] == '#') {
            lineNumber = last;
            continue;
        }
        if (keyword == "v") {
            glm::dvec3 p;
            for (int i = 0; i < 3; ++i) {
                std::string word;
                if (!(words >> word)) throw fail("a vertex needs three coordinates");
                if (!wholeNumber(word, p[i])) throw fail(quotedWord(word) + " is not a number");
                if (!std::isfinite(p[i])) throw fail("a coordinate is not a finite number");
            }
            obj.positions.push_back(p);
        } else if (keyword == "f") {
            std::vector<uint32_t> face;
            for (std::string corner; words >> corner;) {
                long long index = 0;
                const char* begin = corner.data();
                const char* stop = begin + corner.size();
                const auto [rest, error] = std::from_chars(begin, stop, index);
                if (error != std::errc() || (rest != stop && *rest != '/') || index == 0) {
                    throw fail(quotedWord(corner) + " is not a vertex reference");
                }
                const auto count = static_cast<long long>(obj.positions.size());
                const long long at = index > 0 ? index - 1 : count + index;
                if (at < 0 || at >= count) {
                    throw fail("a face refers to vertex " + std::to_string(index) + ", but " + std::to_string(count) +
                               (count == 1 ? " vertex is" : " vertices are") + " defined before it");
                }
                face.push_back(static_cast<uint32_t>(at));
            }
            if (face.size() < 3) throw fail("a face needs at least three corners");
            obj.faces.push_back(std::move(face));
        }
        lineNumber = last;
    }
    return obj;
}

// A text OFF's polygons, read by strata itself: the keyword (OFF with
// Geomview's prefixes: ST, C, N, 4, n), the counts of vertices, faces and
// edges (on the keyword's line, as OpenSCAD writes them, or after it), each
// vertex on a line of its own (x y z, or x y z w for 4OFF; whatever follows,
// a normal or a colour, is skipped), then each face (its corner count and
// corners, counted from 0; a colour after them is skipped). '#' starts a
// comment. OpenMesh's reader reserved gigabytes for a header it could not
// read; this one checks every count against the file and names the line of
// any fault.
Polygons readOff(const std::string& text, const std::string& path) {
    Polygons off;
    std::size_t lineNumber = 0, start = 0;
    auto fail = [&](const std::string& why) {
        return Error(path + ":" + std::to_string(lineNumber) + ": cannot read mesh: " + why);
    };
    // The next line with something on it, its comment cut off; false at the end.
    std::string line;
    auto nextLine = [&]() {
        while (start < text.size()) {
            std::size_t end = text.find('\n', start);
            if (end == std::string::npos) end = text.size();
            line.assign(text, start, end - start);
            start = end + 1;
            ++lineNumber;
            if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
            if (line.find_first_not_of(" \t\r") != std::string::npos) return true;
        }
        return false;
    };
    auto number = [&](const std::string& word, auto& value) {
        if (!wholeNumber(word, value)) throw fail(quotedWord(word) + " is not a number");
    };
    if (!nextLine()) throw fail("no OFF keyword");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    std::size_t at = 0;
    if (keyword.compare(at, 2, "ST") == 0) at += 2;
    if (keyword.compare(at, 1, "C") == 0) at += 1;
    if (keyword.compare(at, 1, "N") == 0) at += 1;
    const bool homogeneous = keyword.compare(at, 1, "4") == 0;
    if (homogeneous) at += 1;
    const bool dimensioned = keyword.compare(at, 1, "n") == 0;
    if (dimensioned) at += 1;
    if (keyword.compare(at, std::string::npos, "OFF") != 0) throw fail(quotedWord(keyword) + " is not an OFF keyword");
    // The header's numbers: the dimension (nOFF), then the three counts.
    std::vector<unsigned long long> header;
    const std::size_t wanted = dimensioned ? 4 : 3;
    for (;;) {
        for (std::string word; header.size() < wanted && words >> word;) {
            unsigned long long value = 0;
            number(word, value);
            header.push_back(value);
        }
        if (header.size() == wanted) break;
        if (!nextLine()) throw fail("the header has no vertex, face and edge counts");
        words = std::istringstream(line);
    }
    if (dimensioned && header[0] != 3) throw fail("only three dimensions can be read, not " + std::to_string(header[0]));
    const unsigned long long vertices = header[wanted - 3], faces = header[wanted - 2];
    for (const unsigned long long n : {vertices, faces}) {
        if (n > text.size()) {
            throw fail("header declares " + std::to_string(n) + " elements, more than the file can hold");
        }
    }
    const int coordinates = homogeneous ? 4 : 3;
    off.positions.reserve(vertices);
    for (unsigned long long v = 0; v < vertices; ++v) {
        if (!nextLine()) throw fail("the file ends after " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
        words = std::istringstream(line);
        double c[4] = {0, 0, 0, 1};
        for (int i = 0; i < coordinates; ++i) {
            std::string word;
            if (!(words >> word)) throw fail("a vertex needs " + std::to_string(coordinates) + " coordinates");
            number(word, c[i]);
        }
        const glm::dvec3 p = glm::dvec3(c[0], c[1], c[2]) / c[3];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) throw fail("a coordinate is not a finite number");
        off.positions.push_back(p);
    }
    for (unsigned long long f = 0; f < faces; ++f) {
        if (!nextLine()) throw fail("the file ends after " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
        words = std::istringstream(line);
        std::string word;
        unsigned long long corners = 0;
        words >> word;
        number(word, corners);
        if (corners < 3) throw fail("a face needs at least three corners");
        if (corners > vertices) throw fail("a face of " + std::to_string(corners) + " corners, more than the vertices");
        std::vector<uint32_t> face;
        face.reserve(corners);
        for (unsigned long long k = 0; k < corners; ++k) {
            unsigned long long index = 0;
            if (!(words >> word)) throw fail("a face has fewer corners than it declares");
            number(word, index);
            if (index >= vertices) {
                throw fail("a face refers to vertex " + std::to_string(index) + ", past the " + std::to_string(vertices) +
                           " vertices");
            }
            face.push_back(static_cast<uint32_t>(index));
        }
        off.faces.push_back(std::move(face));
    }
    return off;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

Mesh importMesh(const std::string& path) {
    auto fail = [&path](const std::string& why) { return Error(path + ": cannot read mesh: " + why); };
    const std::string ext = lowerExtension(path);
    if (!scene::isImportPath(path, scene::ImportKind::Mesh)) {
        throw fail("unsupported format '" + ext + "' (expected " + scene::importExtensionList(scene::ImportKind::Mesh) + ")");
    }
    std::error_code ec;
    if (const std::string why = unreadableReason(path); !why.empty()) throw fail(why);
    if (!std::ifstream(path, std::ios::binary)) throw fail("cannot open file");
    const auto size = std::filesystem::file_size(path, ec);
    if (size == 0) throw fail("empty file");
    const std::string head = detail::readHead(path, 1 << 16);
    if (ext == ".ply") detail::checkPly(path, size);
    if (ext == ".off" && binaryOff(head)) throw fail("binary OFF is not read (write the mesh as text OFF, STL or PLY)");
    std::string text;  // the whole file, read once where it is read as text
    if (looksLikeText(head)) {
        text = readAll(path);
        if (const std::size_t line = lineOfNonFiniteWord(text); line > 0) {
            throw Error(path + ":" + std::to_string(line) + ": cannot read mesh: a coordinate is not a finite number");
        }
    }

    if (ext == ".obj" || ext == ".off") {
        if (text.empty()) text = readAll(path);  // one that does not look like text
        Polygons read = ext == ".obj" ? readObj(text, path) : readOff(text, path);
        if (read.faces.empty()) throw fail("no faces (not a valid " + ext.substr(1) + " file?)");
        Mesh mesh;
        mesh.positions = std::move(read.positions);
        for (const std::vector<uint32_t>& face : read.faces) detail::triangulatePolygon(mesh.positions, face, mesh.triangles);
        mergeCoincidentVertices(mesh);
        return mesh;
    }

    PolyMesh om;
    bool ok = false;
    std::string exception;
    {
        SilencedOpenMeshLog silence;
        OpenMesh::IO::Options options;
        try {
            ok = OpenMesh::IO::read_mesh(om, path, options);
        } catch (const std::exception& e) {
            ok = false;
            exception = e.what();
        }
    }
    if (!ok) {
        throw fail("not a valid " + ext.substr(1) + " file" + (exception.empty() ? "" : " (" + exception + ")"));
    }
    if (om.n_faces() == 0) throw fail("no faces (not a valid " + ext.substr(1) + " file?)");

    Mesh mesh;
    mesh.positions.reserve(om.n_vertices());
    for (const auto& vh : om.vertices()) {
        const auto& p = om.point(vh);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            throw fail("a vertex has a coordinate that is not a finite number");
        }
        mesh.positions.emplace_back(p[0], p[1], p[2]);
    }
    // Faces OpenMesh could not attach (complex edges) it adds again on copies
    // of their vertices; merging the copies below restores the real topology,
    // so checkMesh still sees the defect.
    std::vector<uint32_t> loop;
    for (const auto& fh : om.faces()) {
        loop.clear();
        for (const auto& vh : om.fv_range(fh)) loop.push_back(static_cast<uint32_t>(vh.idx()));
        detail::triangulatePolygon(mesh.positions, loop, mesh.triangles);
    }
    mergeCoincidentVertices(mesh);
    return mesh;
}

}  // namespace strata::mesh
