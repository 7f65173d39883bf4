// Built instead of OpenCsgComparator.cpp when CMake found no OpenCSG or GLEW
// (or was told not to look); STRATA_BENCH_OPENCSG_WHY says which.
#include "OpenCsgComparator.h"
#include "strata/core/Error.h"

namespace strata::bench {

const char* openCsgVersion() {
    return "no OpenCSG";
}

std::unique_ptr<OpenCsgComparator> openOpenCsgComparator(CompatContext) {
    throw Error(std::string("built without OpenCSG: ") + STRATA_BENCH_OPENCSG_WHY);
}

}  // namespace strata::bench
