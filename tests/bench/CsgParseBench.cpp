// Parser throughput benchmark (not a test): writes a synthetic export of the
// given size in MB (default 200) to a temporary file, parses it with
// strata::scene::parseCsgFile and prints MB/s and the peak resident memory.
//
//   strata_parse_bench [MB] [--keep]
//
// The text mixes what real exports are made of: deep multmatrix/color groups
// around spheres and cylinders, and large polyhedra (imported meshes turned
// into polyhedron() by OpenSCAD).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <sys/resource.h>

#include "strata/scene/CsgParser.h"

namespace {

void writeScene(const std::string& path, double megabytes) {
    std::ofstream out(path, std::ios::binary);
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-100.0, 100.0);
    const auto target = static_cast<std::size_t>(megabytes * 1e6);
    std::size_t written = 0;
    char line[512];
    out << "difference() {\n";
    int block = 0;
    while (written < target) {
        if (block % 2 == 0) {
            int n = std::snprintf(line, sizeof line,
                                  "\tmultmatrix([[1, 0, 0, %.6g], [0, 1, 0, %.6g], [0, 0, 1, %.6g], [0, 0, 0, 1]]) {\n"
                                  "\t\tcolor([0.2, 0.4, 0.6, 1]) {\n"
                                  "\t\t\tsphere($fn = 0, $fa = 12, $fs = 2, r = %.6g);\n"
                                  "\t\t\tcylinder($fn = 0, $fa = 12, $fs = 2, h = %.6g, r1 = 1, r2 = 0.5, center = false);\n"
                                  "\t\t}\n\t}\n",
                                  u(rng), u(rng), u(rng), std::abs(u(rng)) + 1, std::abs(u(rng)) + 1);
            out.write(line, n);
            written += static_cast<std::size_t>(n);
        } else {
            std::string poly = "\tpolyhedron(points = [";
            for (int i = 0; i < 2000; ++i) {
                int n = std::snprintf(line, sizeof line, "%s[%.9g, %.9g, %.9g]", i ? ", " : "", u(rng), u(rng), u(rng));
                poly.append(line, static_cast<std::size_t>(n));
            }
            poly += "], faces = [";
            for (int i = 0; i < 1000; ++i) {
                int n = std::snprintf(line, sizeof line, "%s[%d, %d, %d]", i ? ", " : "", i, i + 1, i + 2);
                poly.append(line, static_cast<std::size_t>(n));
            }
            poly += "], convexity = 1);\n";
            out << poly;
            written += poly.size();
        }
        ++block;
    }
    out << "}\n";
}

}  // namespace

int main(int argc, char** argv) {
    double mb = argc > 1 ? std::atof(argv[1]) : 200.0;
    bool keep = argc > 2 && std::string(argv[2]) == "--keep";
    std::string path = (std::filesystem::temp_directory_path() / "strata_parse_bench.csg").string();
    writeScene(path, mb);
    const double bytes = static_cast<double>(std::filesystem::file_size(path));
    auto t0 = std::chrono::steady_clock::now();
    strata::scene::Tree tree = strata::scene::parseCsgFile(path);
    auto t1 = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(t1 - t0).count();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("parsed %.1f MB in %.3f s: %.1f MB/s; %zu leaves, %zu nodes; peak RSS %.1f MB\n", bytes / 1e6,
                seconds, bytes / 1e6 / seconds, tree.leaves.size(), tree.nodes.size(),
                static_cast<double>(usage.ru_maxrss) / 1024.0);
    if (!keep) std::filesystem::remove(path);
    return 0;
}
