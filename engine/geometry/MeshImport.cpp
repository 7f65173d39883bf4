#include "strata/geometry/MeshImport.h"

// OpenMesh wants its IO header before any mesh kernel.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <mutex>
#include <vector>

#include "PlyCheck.h"
#include "PolygonTriangulation.h"
#include "strata/core/Error.h"
#include "strata/core/InputFile.h"
#include "strata/geometry/MeshCheck.h"

namespace strata::geometry {
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

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// OpenSCAD writes OFF files with the counts on the keyword's line
// ("OFF 8 6 0"); OpenMesh's reader takes the whole first line as the keyword
// and then reads coordinates as counts. Moves such counts to a line of their
// own; returns false when the text needs no change.
bool splitOffHeader(std::string& text) {
    const std::size_t lineEnd = std::min(text.find('\n'), text.size());
    std::size_t i = text.find_first_not_of(" \t\r");
    const std::size_t keyword = i;
    while (i < lineEnd && std::isalpha(static_cast<unsigned char>(text[i]))) ++i;
    if (i == keyword || i - keyword < 3 || text.compare(i - 3, 3, "OFF") != 0) return false;
    const std::size_t rest = text.find_first_not_of(" \t\r", i);
    if (rest >= lineEnd || !std::isdigit(static_cast<unsigned char>(text[rest]))) return false;
    text[i] = '\n';  // the separator after the keyword
    return true;
}

// Element counts an OFF header declares (vertices, faces), so a corrupt
// header cannot make OpenMesh reserve gigabytes: every element takes at
// least one byte of the file. Empty when the header cannot be parsed
// (OpenMesh then reports the file itself) or has no counts.
std::vector<unsigned long long> declaredOffCounts(const std::string& head) {
    std::vector<unsigned long long> counts;
    std::istringstream in(head);
    std::string line;
    std::string keyword;
    if (!(in >> keyword) || keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) return {};
    std::getline(in, line);  // rest of the keyword line
    if (line.find("BINARY") != std::string::npos) return {};
    std::string numbers = line;
    while (std::getline(in, line)) {  // counts may follow comments and blank lines
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        numbers += " " + line;
        break;
    }
    std::istringstream words(numbers);
    unsigned long long dimension = 0, vertices = 0, faces = 0;
    if (keyword.find('n') != std::string::npos && !(words >> dimension)) return {};
    if (words >> vertices >> faces) counts = {vertices, faces};
    return counts;
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

// Turns each OBJ `mtllib` line into a comment (the same length, so that
// line numbers and columns stay where they were).
void withoutMaterialLibraries(std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::size_t word = text.find_first_not_of(" \t", start);
        if (word < end && text.compare(word, 6, "mtllib") == 0 &&
            (word + 6 == end || text[word + 6] == ' ' || text[word + 6] == '\t' || text[word + 6] == '\r')) {
            text[word] = '#';
        }
        start = end + 1;
    }
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

Mesh importMesh(const std::string& path) {
    auto fail = [&path](const std::string& why) { return Error(path + ": cannot read mesh: " + why); };
    const std::string ext = lowerExtension(path);
    if (ext != ".stl" && ext != ".off" && ext != ".obj" && ext != ".ply") {
        throw fail("unsupported format '" + ext + "' (expected .stl, .off, .obj or .ply)");
    }
    std::error_code ec;
    if (const std::string why = unreadableReason(path); !why.empty()) throw fail(why);
    if (!std::ifstream(path, std::ios::binary)) throw fail("cannot open file");
    const auto size = std::filesystem::file_size(path, ec);
    if (size == 0) throw fail("empty file");
    const std::string head = detail::readHead(path, 1 << 16);
    if (ext == ".ply") detail::checkPly(path, size);
    if (ext == ".off") {
        for (unsigned long long n : declaredOffCounts(head)) {
            if (n > size) throw fail("header declares " + std::to_string(n) + " elements, more than the file can hold");
        }
    }
    if (looksLikeText(head)) {
        if (const std::size_t line = lineOfNonFiniteWord(readAll(path)); line > 0) {
            throw Error(path + ":" + std::to_string(line) + ": cannot read mesh: a coordinate is not a finite number");
        }
    }

    PolyMesh om;
    bool ok = false;
    std::string exception;
    {
        SilencedOpenMeshLog silence;
        OpenMesh::IO::Options options;
        try {
            std::string text;
            if (ext == ".off" && splitOffHeader(text = readAll(path))) {
                std::istringstream in(text);
                ok = OpenMesh::IO::read_mesh(om, in, ext, options);
            } else if (ext == ".obj") {
                // OpenMesh opens the material files an OBJ names, a FIFO or
                // a device included; strata takes no colours from them, so
                // the reader never sees those lines.
                text = readAll(path);
                withoutMaterialLibraries(text);
                std::istringstream in(text);
                ok = OpenMesh::IO::read_mesh(om, in, ext, options);
            } else {
                ok = OpenMesh::IO::read_mesh(om, path, options);
            }
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

}  // namespace strata::geometry
