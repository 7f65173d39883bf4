// libFuzzer target for strata-view's --script language (view::parseScript).
//
// Any input must either parse into commands whose numbers are finite and
// whose words and positions agree, or throw strata::Error (one
// "file:line:col: message"); anything else (another exception, a crash, a
// leak, a sanitizer report, a hang) is a finding. Only the parser runs: no
// window, no file is opened. scripts/fuzz.sh builds and runs it.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "Script.h"
#include "strata/core/Error.h"

namespace {

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "strata_fuzz_script: the parser returned a broken command: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        for (const strata::view::Command& c : strata::view::parseScript(text, "fuzz.script")) {
            if (c.words.size() != c.wordsAt.size()) broken("a word without its position");
            if (c.where.line < 1 || c.where.column < 1) broken("a command without a position");
            for (double x : c.numbers) {
                if (!std::isfinite(x)) broken("a non-finite number");
            }
        }
    } catch (const strata::Error& e) {
        if (std::string(e.what()).find('\n') != std::string::npos) broken("a message of more than one line");
    }
    return 0;
}
