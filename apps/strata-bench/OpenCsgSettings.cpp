#include "OpenCsgComparator.h"

namespace strata::bench {

std::string OpenCsgSetting::name() const {
    std::string out = algorithm == CsgAlgorithm::Goldfeather ? "goldfeather" : "scs";
    if (depthComplexity == DepthComplexity::OcclusionQuery) out += "-oq";
    if (depthComplexity == DepthComplexity::Sampling) out += "-dcs";
    return out;
}

const std::vector<OpenCsgSetting>& openCsgSettings() {
    static const std::vector<OpenCsgSetting> settings{
        {CsgAlgorithm::Goldfeather, DepthComplexity::None},
        {CsgAlgorithm::Goldfeather, DepthComplexity::OcclusionQuery},
        {CsgAlgorithm::Goldfeather, DepthComplexity::Sampling},
        {CsgAlgorithm::Scs, DepthComplexity::None},
        {CsgAlgorithm::Scs, DepthComplexity::OcclusionQuery},
        {CsgAlgorithm::Scs, DepthComplexity::Sampling},
    };
    return settings;
}

}  // namespace strata::bench
