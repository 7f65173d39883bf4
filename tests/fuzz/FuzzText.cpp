// libFuzzer target for text() (flat::textGlyphs): fontconfig, HarfBuzz
// and FreeType under strata's calls.
//
// The input's first bytes choose the node's other arguments (size, spacing,
// font, direction, alignment, script, language, $fn) from values a .csg can
// give, odd ones included; the rest, at most 512 bytes, is the text (any
// bytes: invalid UTF-8, controls, combining marks). Any input must either
// give glyph outlines with finite points or throw strata::Error; anything
// else (another exception, a crash, a leak, a sanitizer report, a hang) is
// a finding. scripts/fuzz.sh builds and runs it.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "strata/core/Error.h"
#include "strata/flat/Text.h"

namespace {

using namespace strata;

template <typename T, std::size_t N>
const T& pick(const std::array<T, N>& values, std::uint8_t byte) {
    return values[byte % N];
}

// The parser refuses a size or spacing that is not finite, and the 2D grid
// a glyph too large for it.
const std::array<double, 9> kSizes{10.0, 1.0, 0.25, 100.0, 3.7, 0.0, -5.0, 1e6, 1e-9};
const std::array<double, 6> kSpacings{1.0, 0.5, 2.0, 0.0, -1.0, 1e9};
const std::array<const char*, 8> kFonts{"",
                                        "Liberation Sans",
                                        "Liberation Serif:style=Bold",
                                        "Liberation Mono:style=Italic",
                                        "No Such Font",
                                        ":",
                                        "Liberation Sans:size=abc:weight=",
                                        "\\:="};
const std::array<const char*, 6> kDirections{"ltr", "rtl", "ttb", "btt", "", "sideways"};
const std::array<const char*, 5> kHalign{"left", "center", "right", "default", "middle"};
const std::array<const char*, 6> kValign{"baseline", "top", "center", "bottom", "default", "x"};
const std::array<const char*, 6> kScripts{"Latn", "Arab", "Hebr", "Zyyy", "", "Qaaa"};
const std::array<const char*, 5> kLanguages{"en", "ar", "he", "", "zz-ZZ"};
const std::array<double, 5> kFn{0.0, 3.0, 12.0, 100.0, 1024.0};
constexpr std::size_t kChoices = 9;
constexpr std::size_t kMaxText = 512;

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "strata_fuzz_text: textGlyphs returned a broken result: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < kChoices) return 0;
    scene::Text text;
    text.size = pick(kSizes, data[0]);
    text.spacing = pick(kSpacings, data[1]);
    text.font = pick(kFonts, data[2]);
    text.direction = pick(kDirections, data[3]);
    text.halign = pick(kHalign, data[4]);
    text.valign = pick(kValign, data[5]);
    text.script = pick(kScripts, data[6]);
    text.language = pick(kLanguages, data[7]);
    text.fragments.fn = pick(kFn, data[8]);
    const std::size_t length = std::min(size - kChoices, kMaxText);
    text.text.assign(reinterpret_cast<const char*>(data + kChoices), length);
    try {
        for (const flat::Outlines& glyph : flat::textGlyphs(text)) {
            for (const flat::Outline& outline : glyph.outlines) {
                for (const glm::dvec2& p : outline.points) {
                    if (!std::isfinite(p.x) || !std::isfinite(p.y)) broken("non-finite outline point");
                }
            }
        }
    } catch (const Error&) {
        // A refusal in one line is the contract's answer.
    }
    return 0;
}
