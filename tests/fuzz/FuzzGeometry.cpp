// libFuzzer target for the geometry evaluation of small trees: the input's
// bytes choose a .csg of at most a dozen nodes, curves of at most a dozen
// fragments (an exact Minkowski sum of larger ones takes minutes under the
// sanitizers) (solids, 2D shapes and their
// booleans, offsets, linear and rotate extrusions, hulls, Minkowski sums,
// projections, resizes, transforms), which is parsed and built into meshes
// as strata-render builds a scene (model::buildModel), and of a solid
// tree its exact result, as the exact export evaluates it.
//
// Any input must either give closed meshes with finite points or throw
// strata::Error; anything else (another exception, a crash, a leak, a
// sanitizer report, a hang past the time bound, memory past the bound) is a
// finding. It links strata_geometry, CGAL and all, so it is not part of the
// build CI fuzzes: scripts/fuzz.sh --geometry SECONDS runs it by hand.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "strata/core/Error.h"
#include "strata/exact/Exact.h"
#include "strata/mesh/MeshCheck.h"
#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

namespace {

using namespace strata;

// The input read as a stream of choices; past its end every choice is 0.
class Choices {
public:
    Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    int below(int n) { return byte() % n; }
    // A number from a small set that holds the awkward ones (0, negative, tiny).
    std::string number(double scale) {
        static const double values[] = {1, 2, 0.5, 3, 5, 0, -1, 1e-4, 7.25, 10, 0.1, 4};
        return fmt(values[below(12)] * scale);
    }
    std::string vec(int n, double scale) {
        std::string out = "[";
        for (int k = 0; k < n; ++k) out += (k ? ", " : "") + number(scale);
        return out + "]";
    }
    static std::string fmt(double v) {
        std::ostringstream out;
        out << v;
        return out.str();
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

class Writer {
public:
    explicit Writer(Choices& c) : c_(c) {}

    std::string solid(int depth) {
        if (budget_-- <= 0 || depth > 3) return leaf3();
        switch (c_.below(10)) {
        case 0: return leaf3();
        case 1: return op("union", depth, false);
        case 2: return op("difference", depth, false);
        case 3: return op("intersection", depth, false);
        case 4: return "linear_extrude(height = " + c_.number(3) + ", center = " + boolean() + ", twist = " +
                       c_.number(30) + ", slices = " + std::to_string(c_.below(5)) + ", scale = " + c_.number(1) +
                       ") {\n" + flat(depth + 1) + "}\n";
        case 5: return "rotate_extrude(angle = " + c_.number(90) + ", $fn = " + std::to_string(3 + c_.below(10)) +
                       ") {\n" + transformed("multmatrix([[1, 0, 0, " + c_.number(3) +
                                                 "], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])",
                                             flat(depth + 1)) +
                       "}\n";
        case 6: return op("hull", depth, false);
        case 7: return op("minkowski", depth, false);
        case 8: return "resize(newsize = " + c_.vec(3, 4) + ", auto = " + boolean() + ") {\n" + solid(depth + 1) + "}\n";
        default: return transformed(matrix(), solid(depth + 1));
        }
    }

    std::string flat(int depth) {
        if (budget_-- <= 0 || depth > 4) return leaf2();
        switch (c_.below(9)) {
        case 0:
        case 1: return leaf2();
        case 2: return op("union", depth, true);
        case 3: return op("difference", depth, true);
        case 4: return op("intersection", depth, true);
        case 5: return "offset(" + std::string(c_.below(2) ? "r = " : "delta = ") + c_.number(1) +
                       ", chamfer = " + boolean() + ", $fn = " + std::to_string(c_.below(16)) + ") {\n" +
                       flat(depth + 1) + "}\n";
        case 6: return "projection(cut = " + boolean() + ") {\n" + solid(depth + 1) + "}\n";
        case 7: return op("hull", depth, true);
        default: return transformed(matrix(), flat(depth + 1));
        }
    }

private:
    std::string boolean() { return c_.below(2) ? "true" : "false"; }

    std::string leaf3() {
        switch (c_.below(5)) {
        case 0: return "cube(size = " + c_.vec(3, 2) + ", center = " + boolean() + ");\n";
        case 1: return "sphere($fn = " + std::to_string(c_.below(12)) + ", $fa = 12, $fs = 2, r = " + c_.number(2) + ");\n";
        case 2: return "cylinder($fn = " + std::to_string(c_.below(12)) + ", $fa = 12, $fs = 2, h = " + c_.number(3) +
                       ", r1 = " + c_.number(1) + ", r2 = " + c_.number(1) + ", center = " + boolean() + ");\n";
        case 3: return "polyhedron(points = [[0, 0, 0], [" + c_.number(3) + ", 0, 0], [0, " + c_.number(3) +
                       ", 0], [0, 0, " + c_.number(3) + "]], faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]], convexity = 1);\n";
        default: return "cube(size = [1, 1, 1], center = true);\n";
        }
    }

    std::string leaf2() {
        switch (c_.below(4)) {
        case 0: return "square(size = " + c_.vec(2, 2) + ", center = " + boolean() + ");\n";
        case 1: return "circle($fn = " + std::to_string(c_.below(12)) + ", $fa = 12, $fs = 2, r = " + c_.number(1) + ");\n";
        case 2: {
            std::string points = "[";
            const int n = 3 + c_.below(6);
            for (int k = 0; k < n; ++k) points += (k ? ", " : "") + c_.vec(2, 2);
            return "polygon(points = " + points + "], paths = undef, convexity = 1);\n";
        }
        default: return "square(size = [2, 1], center = true);\n";
        }
    }

    std::string matrix() {
        const double a = c_.below(8) * 0.7853981633974483;
        const std::string s = Choices::fmt(c_.below(3) == 0 ? 0.0 : std::sin(a)), co = Choices::fmt(std::cos(a));
        const std::string k = c_.number(1);
        return "multmatrix([[" + co + ", -" + s + ", 0, " + c_.number(2) + "], [" + s + ", " + co + ", 0, " +
               c_.number(2) + "], [0, 0, " + (c_.below(4) ? std::string("1") : k) + ", " + c_.number(1) +
               "], [0, 0, 0, 1]])";
    }

    std::string transformed(const std::string& head, const std::string& body) { return head + " {\n" + body + "}\n"; }

    std::string op(const char* name, int depth, bool flatChildren) {
        std::string out = std::string(name) + "() {\n";
        const int n = 1 + c_.below(3);
        for (int k = 0; k < n; ++k) out += flatChildren ? flat(depth + 1) : solid(depth + 1);
        return out + "}\n";
    }

    Choices& c_;
    int budget_ = 12;
};

[[noreturn]] void broken(const char* what, const std::string& csg) {
    std::fprintf(stderr, "strata_fuzz_geometry: %s\n--- the scene:\n%s\n", what, csg.c_str());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Choices choices(data, size);
    Writer writer(choices);
    const std::string csg = choices.below(4) == 0 ? writer.flat(0) : writer.solid(0);
    // To see what a reproducer builds: STRATA_FUZZ_PRINT=1 strata_fuzz_geometry FILE
    static const bool print = std::getenv("STRATA_FUZZ_PRINT") != nullptr;
    if (print) std::fprintf(stderr, "%s", csg.c_str());
    try {
        std::istringstream in(csg);
        const scene::Tree tree = scene::parseCsg(in, "fuzz.csg", ".");
        const model::Model model = model::buildModel(tree);
        for (const mesh::Mesh& mesh : model.leafMeshes) {
            for (const glm::dvec3& p : mesh.positions) {
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) broken("a non-finite point", csg);
            }
            if (!mesh.triangles.empty() && !mesh::checkMesh(mesh).ok()) broken("a leaf mesh that is not closed", csg);
        }
        // The whole solid's exact result, as --export evaluates it: closed
        // too (its booleans in the frames their leaves share, its coplanar
        // triangles joined).
        if (tree.root >= 0 && !tree.isFlat()) {
            const mesh::Mesh result = exact::exactResult(tree, tree.root, model.leafMeshes, model::objectMesh);
            if (!result.triangles.empty() && !mesh::checkMesh(result).ok()) broken("an exact result that is not closed", csg);
        }
    } catch (const Error&) {
        // A refusal in one line is the contract's answer.
    }
    return 0;
}
