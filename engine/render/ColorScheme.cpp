#include "strata/render/ColorScheme.h"

#include <array>
#include <cctype>
#include <cstdint>

#include "strata/core/Error.h"

namespace strata::render {

namespace {

constexpr glm::vec4 rgb(std::uint32_t hex) {
    return {static_cast<float>((hex >> 16) & 0xffu) / 255.0f, static_cast<float>((hex >> 8) & 0xffu) / 255.0f,
            static_cast<float>(hex & 0xffu) / 255.0f, 1.0f};
}

// Values from OpenSCAD's sources: Cornfield from src/glview/ColorMap.cc, the
// others from color-schemes/render/<name>.json ("background",
// "opencsg-face-front", "opencsg-face-back").
const std::array<ColorScheme, 14>& schemes() {
    static const std::array<ColorScheme, 14> kSchemes{{
        {"Cornfield", rgb(0xffffe5), rgb(0xf9d72c), rgb(0x9dcb51)},
        {"Metallic", rgb(0xaaaaff), rgb(0xddddff), rgb(0xdd22dd)},
        {"Sunset", rgb(0xaa4444), rgb(0xffaaaa), rgb(0x882233)},
        {"Starnight", rgb(0x000000), rgb(0xffffe0), rgb(0x00ffff)},
        {"BeforeDawn", rgb(0x333333), rgb(0xcccccc), rgb(0x5563dd)},
        {"Nature", rgb(0xfafafa), rgb(0x16a085), rgb(0xdbf4da)},
        {"Daylight Gem", rgb(0xf0f0f0), rgb(0x02daf7), rgb(0x014da1)},
        {"Nocturnal Gem", rgb(0x0c0c0c), rgb(0x02daf7), rgb(0x014da1)},
        {"DeepOcean", rgb(0x333333), rgb(0xeeeeee), rgb(0x0babc8)},
        {"Solarized", rgb(0xfdf6e3), rgb(0xb58800), rgb(0x882233)},
        {"Tomorrow", rgb(0xf8f8f8), rgb(0x4271ae), rgb(0xf5871f)},
        {"Tomorrow Night", rgb(0x1d1f21), rgb(0x81a2be), rgb(0xde935f)},
        {"ClearSky", rgb(0x87ceeb), rgb(0xf9d72c), rgb(0x9dcb51)},
        {"Monotone", rgb(0xffffe5), rgb(0xf9d72c), rgb(0xf9d72c)},
    }};
    return kSchemes;
}

// Lower case, letters and digits only: "Tomorrow Night" -> "tomorrownight".
std::string key(std::string_view name) {
    std::string k;
    for (char c : name) {
        if (std::isalnum(static_cast<unsigned char>(c))) {
            k += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        }
    }
    return k;
}

}  // namespace

const ColorScheme& colorScheme(std::string_view name) {
    const std::string wanted = key(name);
    for (const ColorScheme& scheme : schemes()) {
        if (!wanted.empty() && key(scheme.name) == wanted) return scheme;
    }
    std::string valid;
    for (const ColorScheme& scheme : schemes()) {
        if (!valid.empty()) valid += ", ";
        valid += scheme.name;
    }
    throw Error("unknown colour scheme '" + std::string(name) + "' (valid: " + valid + ")");
}

std::vector<std::string> colorSchemeNames() {
    std::vector<std::string> names;
    for (const ColorScheme& scheme : schemes()) names.push_back(scheme.name);
    return names;
}

std::string_view lightingName(Lighting lighting) { return lighting == Lighting::OpenScad ? "openscad" : "strata"; }

Lighting lightingNamed(std::string_view name) {
    const std::string wanted = key(name);
    for (Lighting lighting : {Lighting::Strata, Lighting::OpenScad}) {
        if (key(lightingName(lighting)) == wanted) return lighting;
    }
    throw Error("unknown light '" + std::string(name) + "' (valid: strata, openscad)");
}

}  // namespace strata::render
