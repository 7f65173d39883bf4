#pragma once
// OpenSCAD's colour schemes for the 3D view (color-schemes/render/*.json in
// OpenSCAD's sources, Cornfield built into its ColorMap.cc): the colours the
// shade pass uses where a leaf has no color() of its own.

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

namespace strata::render {

struct ColorScheme {
    std::string name;        // as OpenSCAD spells it: "Cornfield", "Tomorrow Night"
    glm::vec4 background;    // "background": the empty pixels, opaque
    glm::vec4 faceFront;     // "opencsg-face-front": a leaf's own surface
    glm::vec4 faceBack;      // "opencsg-face-back": a cut face (the leaf is subtracted there)
};

// OpenSCAD's modifier colours (its Renderer's HIGHLIGHT and BACKGROUND colour
// modes), RGBA in [0,1], alpha 128/255: '#' leaves and '%' leaves without a color().
inline constexpr glm::vec4 kHighlightColor{255.0f / 255.0f, 81.0f / 255.0f, 81.0f / 255.0f, 128.0f / 255.0f};
inline constexpr glm::vec4 kBackgroundModifierColor{180.0f / 255.0f, 180.0f / 255.0f, 180.0f / 255.0f,
                                                     128.0f / 255.0f};

inline constexpr std::string_view kDefaultColorScheme = "Cornfield";

// How the shade pass lights the visible surface (shaders/csg/light.glsl).
enum class Lighting {
    // Ambient 0.35 plus 0.65 times Lambert from a light a little above and
    // left of the eye, per pixel along its view ray.
    Strata,
    // OpenSCAD's preview: the colour times 0.2 + |n . l|, with l the unit
    // direction (-1, 1, 1) in view space (up, left and towards the viewer),
    // the same on every pixel and on both sides of a face.
    OpenScad,
};

// "strata" or "openscad", and back; lightingNamed throws
// strata::Error("unknown light 'x' (valid: strata, openscad)").
std::string_view lightingName(Lighting lighting);
Lighting lightingNamed(std::string_view name);

// The scheme called `name` (OpenSCAD's spelling; case and spaces are ignored,
// so "tomorrow-night" and "TomorrowNight" find "Tomorrow Night"). Throws
// strata::Error("unknown colour scheme 'x' (valid: Cornfield, Metallic, ...)").
const ColorScheme& colorScheme(std::string_view name);

// Every scheme's name, Cornfield first.
std::vector<std::string> colorSchemeNames();

}  // namespace strata::render
