#pragma once
// Times OpenCSG on one bench case with every setting (OpenCsgComparator.h),
// and checks each setting's coverage against strata's frame.

#include <map>
#include <string>
#include <vector>

#include "Coverage.h"
#include "OpenCsgComparator.h"
#include "strata/camera/Camera.h"
#include "strata/gpu/Context.h"
#include "strata/model/Model.h"
#include "strata/scene/Tree.h"

namespace strata::bench {

struct OpenCsgSettingResult {
    std::string name;
    double ms = 0, minMs = 0;       // median and fastest of the timed frames
    int frames = 0;                 // frames timed
    bool overCap = false;           // a frame took longer than the cap: frames stopped there
    std::string skipped;            // non-empty: not run, and why
    Agreement agreement;            // coverage against strata's
};

struct OpenCsgResult {
    std::string unavailable;        // non-empty: no OpenCSG figures for this case, and why
    // The scene's sum of products (SumOfProducts.h); filled also when the
    // normalization gave up (gaveUp, with the element count it reached).
    std::size_t products = 0, primitives = 0, elements = 0;
    bool gaveUp = false;
    ConvexityMode convexity = ConvexityMode::OpenScad;
    std::vector<OpenCsgSettingResult> settings;
    int best = -1;                  // index of the fastest setting run
    unsigned maxConvexity = 1;
    std::size_t bufferBytes = 0;
};

struct OpenCsgRunOptions {
    int frames = 10, warmup = 2;
    double capMs = 2000;            // one frame over this stops the setting, and skips it for larger K
    ConvexityMode convexity = ConvexityMode::OpenScad;
    std::size_t renderingLimit = kOpenScadRenderingLimit;  // OpenSCAD's "Turn off rendering at"
};

// Settings that went over the cap, by "scene size setting", with the K they did it at.
using OpenCsgCaps = std::map<std::string, int>;

// Makes the comparator's context current for the run and strata's again
// after. `strataCoverage`: W*H, rows top first, non-zero where strata's frame
// has a surface. The tree is normalized as OpenSCAD does (CsgProduct.h).
// SCS is skipped for non-convex operands (it is only correct
// for convex ones); settings are skipped above the K where they went over the cap.
OpenCsgResult runOpenCsg(OpenCsgComparator& comparator, gpu::Context& strata, const scene::Tree& tree,
                         const model::Model& model, const camera::Camera& camera,
                         const std::vector<std::uint8_t>& strataCoverage, const OpenCsgRunOptions& options,
                         const std::string& caseKey, int k, OpenCsgCaps& caps);

}  // namespace strata::bench
