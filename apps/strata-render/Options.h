#pragma once
// strata-render's command line, exactly docs/contract.md's table.
// Parsing only checks the words; files are opened later.

#include <optional>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "strata/camera/Camera.h"

namespace strata::apps {

struct RenderOptions {
    std::string scene;                      // SCENE: .csg, .scad, .stl, .obj, .off or .ply (the first of scenes)
    // SCENE...: every scene, rendered in turn by one process; with more than
    // one, each output name holds %s, which forScene replaces by the scene's
    // file name without its folder and extension.
    std::vector<std::string> scenes;
    std::vector<std::string> defines;       // -D NAME=VALUE, for a .scad, in order
    std::string png;                        // -o FILE.png; empty: none
    std::string depth;                      // --depth FILE.exr
    std::string normal;                     // --normal FILE.exr
    int width = 512, height = 512;          // --imgsize W,H (OpenSCAD's default)
    std::optional<std::vector<double>> camera;  // --camera: 6 or 7 numbers; absent: fitted default view
    camera::Projection projection = camera::Projection::Perspective;
    double fovDegrees = 22.5;
    int layers = 0;                         // 0: auto
    bool stats = false;
    bool quiet = false;                     // -q: errors only on stderr
    bool reference = false;                 // --reference: the CPU ray caster instead of the GPU passes
    std::string colorScheme = "Cornfield";
    LookOptions look;                       // --light, --no-outline
    render::Lighting lighting = render::Lighting::Strata;  // look.light, checked
    std::string exportPath;                 // --export FILE.stl|.off|.obj|.3mf; empty: none
    bool exportExact = false;               // --export-exact: the default, said aloud
    bool exportSampled = false;             // --export-sampled: contoured from the image-space result, not CGAL's exact one
    int exportResolution = 512;             // --export-resolution N: cells along the result's longest side
};

// The options for one of the scenes: `scene` set, %s in the output names
// replaced by its name (its file name without folder and extension).
RenderOptions forScene(const RenderOptions& options, const std::string& scene);

// What parsing decided: run with the options, or stop (CliOutcome).
struct ParseResult : CliOutcome {
    RenderOptions options;
};

// argv[0] is ignored. Never throws.
ParseResult parseOptions(int argc, char** argv);

}  // namespace strata::apps
