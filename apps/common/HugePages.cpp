#include "HugePages.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace strata::apps {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb";

bool sanitized() {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
    return true;
#else
    return false;
#endif
#else
    return false;
#endif
}

std::string hugePageSetting() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace

std::optional<std::string> tunablesForHugePages(const char* current, const std::string& hugePageSetting) {
    const std::string tunables = current != nullptr ? current : "";
    // Only where huge pages are given on request: "[always]" gives them
    // without the tunable, "[never]" not at all.
    if (tunables.find(kTunable) != std::string::npos || hugePageSetting.find("[madvise]") == std::string::npos)
        return std::nullopt;
    return (tunables.empty() ? "" : tunables + ":") + kTunable + "=1";
}

bool startedWithHugePages() {
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    return tunables != nullptr && std::string(tunables).find(std::string(kTunable) + "=1") != std::string::npos;
}

void runWithHugePages(char** argv) {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
    if (sanitized()) return;
    const char* current = std::getenv("GLIBC_TUNABLES");
    const std::string before = current != nullptr ? current : "";
    const std::optional<std::string> tunables = tunablesForHugePages(current, hugePageSetting());
    if (!tunables || setenv("GLIBC_TUNABLES", tunables->c_str(), 1) != 0) return;
    execv("/proc/self/exe", argv);
    // Not run again (no /proc, say): go on as started, the variable as it
    // was, so that programs this one runs are not changed either.
    if (current != nullptr)
        setenv("GLIBC_TUNABLES", before.c_str(), 1);
    else
        unsetenv("GLIBC_TUNABLES");
#else
    (void)argv;
#endif
}

}  // namespace strata::apps
