#pragma once
// Runs a program as the tests' user would, and captures what it says.
// POSIX only (fork/exec), like the rest of strata's CI.

#include <string>
#include <utility>
#include <vector>

namespace strata::testing {

struct ProcessResult {
    int exitCode = -1;   // the exit status, or 128 + signal number when killed
    std::string out;     // stdout
    std::string err;     // stderr
    long peakKiB = -1;   // its own peak resident memory, in KiB (see PeakRss.cpp)
};

// Runs `argv[0]` with `argv`, adding `env` (NAME, value) to the environment,
// under strata_peak_rss (PeakRss.cpp).
ProcessResult runProcess(const std::vector<std::string>& argv,
                         const std::vector<std::pair<std::string, std::string>>& env = {});

// Number of '\n'-terminated lines in `text` (a last line without '\n' counts too).
int lineCount(const std::string& text);

}  // namespace strata::testing
