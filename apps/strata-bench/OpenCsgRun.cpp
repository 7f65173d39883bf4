#include "OpenCsgRun.h"

#include <algorithm>

#include "ViewMatrices.h"

namespace strata::bench {
namespace {

// The comparator's context current for one scope, strata's again after it
// (also when the run throws).
class CompatScope {
public:
    CompatScope(OpenCsgComparator& comparator, gpu::Context& strata) : comparator_(comparator), strata_(strata) {
        comparator_.makeCurrent();
    }
    ~CompatScope() {
        comparator_.release();
        strata_.makeCurrent();
    }
    CompatScope(const CompatScope&) = delete;
    CompatScope& operator=(const CompatScope&) = delete;

private:
    OpenCsgComparator& comparator_;
    gpu::Context& strata_;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

OpenCsgSettingResult skipped(const OpenCsgSetting& setting, std::string why) {
    OpenCsgSettingResult out;
    out.name = setting.name();
    out.skipped = std::move(why);
    return out;
}

OpenCsgSettingResult timeSetting(OpenCsgComparator& comparator, const OpenCsgSetting& setting,
                                 const OpenCsgRunOptions& options) {
    OpenCsgSettingResult out;
    out.name = setting.name();
    std::vector<double> timed;
    double overCapMs = 0;
    for (int i = 0; i < options.warmup + options.frames; ++i) {
        const double ms = comparator.drawFrame(setting);
        if (i >= options.warmup) timed.push_back(ms);
        if (ms > options.capMs) {
            out.overCap = true;
            overCapMs = ms;
            break;
        }
    }
    // Over the cap during warm-up: that frame is the only figure there is.
    if (timed.empty()) timed.push_back(overCapMs);
    out.frames = int(timed.size());
    out.ms = median(timed);
    out.minMs = *std::min_element(timed.begin(), timed.end());
    return out;
}

}  // namespace

OpenCsgResult runOpenCsg(OpenCsgComparator& comparator, gpu::Context& strata, const scene::Tree& tree,
                         const model::Model& model, const camera::Camera& camera,
                         const std::vector<std::uint8_t>& strataCoverage, const OpenCsgRunOptions& options,
                         const std::string& caseKey, int k, OpenCsgCaps& caps) {
    OpenCsgResult out;
    const CsgProducts products = csgProducts(tree, model, options.renderingLimit);
    out.products = products.sum.products.size();
    out.primitives = products.sum.primitives();
    out.elements = products.sum.elements;
    out.gaveUp = products.sum.gaveUp;
    out.convexity = options.convexity;
    if (!products.unavailable.empty()) {
        out.unavailable = products.unavailable;
        return out;
    }
    const bool allConvex = std::all_of(products.leaves.begin(), products.leaves.end(),
                                       [](const ProductLeaf& l) { return l.positions.empty() || l.convex; });

    CompatScope scope(comparator, strata);
    comparator.setScene(products, camera.width, camera.height, fittedView(camera, products.bounds),
                        options.convexity);
    out.maxConvexity = comparator.maxConvexity();
    out.bufferBytes = comparator.bufferBytes();
    for (const OpenCsgSetting& setting : openCsgSettings()) {
        const std::string key = caseKey + " " + setting.name();
        if (setting.algorithm == CsgAlgorithm::Scs && !allConvex) {
            out.settings.push_back(skipped(setting, "SCS needs convex operands"));
            continue;
        }
        if (auto cap = caps.find(key); cap != caps.end() && k > cap->second) {
            out.settings.push_back(skipped(setting, "over " + std::to_string(int(options.capMs)) +
                                                        " ms a frame at K = " + std::to_string(cap->second)));
            continue;
        }
        OpenCsgSettingResult result = timeSetting(comparator, setting, options);
        if (result.overCap) caps.emplace(key, k);
        result.agreement = compareCoverage(strataCoverage, comparator.coverage(), camera.width, camera.height);
        out.settings.push_back(std::move(result));
    }
    for (std::size_t i = 0; i < out.settings.size(); ++i) {
        const OpenCsgSettingResult& s = out.settings[i];
        if (s.skipped.empty() && (out.best < 0 || s.ms < out.settings[std::size_t(out.best)].ms)) out.best = int(i);
    }
    return out;
}

}  // namespace strata::bench
