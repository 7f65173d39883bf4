#pragma once
// The figures that `strata-render --stats` prints: one JSON object on stdout.
//
// Layout (times in milliseconds, memory in bytes):
//   {
//     "scene": "examples/cheese.csg", "width": 512, "height": 512,
//     "renderer": "llvmpipe (LLVM 15.0.6, 256 bits)",
//     "time_ms": {"parse": .., "geometry": .., "context": .., "upload": .., "peel": ..,
//                 "evaluate": .., "shade": .., "readback": .., "frame": .., "write": ..,
//                 "export": .. (with --export only), "total": ..},
//     "operands": 12, "leaves": 13, "triangles": 9000,
//     "dimensions": 3,                         // 2: a flat model, shown as a slab one unit thick
//     "layers_per_operand": [1, 3, ...],      // per tree leaf; 0 for leaves not drawn
//     "layers_max": 3, "layers_total": 14,
//     "texture_bytes": 12582912,
//     "covered_pixels": 91234,
//     "tiles": 1,
//     "notes": ["..."],                        // what the renderer decided
//     "warnings": ["file:line:col: warning: ..."],
//     "unsupported": {"linear_extrude": 2}
//   }

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "strata/render/Frame.h"

namespace strata::io {

struct RunStats {
    std::string scene;              // the SCENE argument as given
    int width = 0, height = 0;
    std::string renderer;           // GL_RENDERER (or "reference")
    double parseMs = 0, geometryMs = 0, contextMs = 0, uploadMs = 0, writeMs = 0, totalMs = 0;
    double exportMs = -1;  // --export: evaluating and encoding the mesh; < 0: no export (not printed)
    // The image-space export's parts: sampling the result (GL context
    // included) and contouring; < 0: not that export (not printed).
    double exportSampleMs = -1, exportContourMs = -1;
    int leaves = 0;                 // all tree leaves, background ones too
    int dimensions = 3;             // 2 when every leaf of the result is flat (scene::Tree::isFlat)
    std::size_t triangles = 0;      // over all leaf meshes
    render::FrameStats frame;
    std::vector<std::string> warnings;
    std::map<std::string, int> unsupported;
};

// The JSON object above; `indent` as JsonWriter (0: one line).
std::string statsJson(const RunStats& stats, int indent = 2);

}  // namespace strata::io
