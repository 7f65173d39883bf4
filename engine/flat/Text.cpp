#include "strata/flat/Text.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <sys/stat.h>
#include <utility>
#include <vector>

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_GLYPH_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_IDS_H
#include <hb-ft.h>
#include <hb.h>

#include "strata/core/Error.h"
#include "strata/mesh/Primitives.h"
#include "strata/mesh/VertexBudget.h"

// text() follows OpenSCAD 2021.01 step for step: src/text.cc (the segment
// count), src/FreetypeRenderer.cc (shaping, metrics, alignment),
// src/DrawingCallback.cc (outline flattening) and src/FontCache.cc (font
// lookup). The arithmetic is written in the same order as there, so that the
// points come out bit-identical with the same FreeType and HarfBuzz.

namespace strata::flat {

using mesh::fragmentsFromR;
using mesh::kMaxVertices;

namespace {

// FreetypeRenderer::scale and ::unscale. The 1000/1024 ratio between them is
// OpenSCAD's (kept there for compatibility).
constexpr double kScale = 1e5;
constexpr double kUnscale = 1.0 / 1.024e5;

const char* const kDefaultFont = "Liberation Sans:style=Regular";  // FontCache::DEFAULT_FONT
constexpr std::size_t kMaxCachedFaces = 8;

bool isDirectory(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string trimmed(const std::string& s) {
    const char* ws = " \t\n\v\f\r";
    const std::size_t first = s.find_first_not_of(ws);
    if (first == std::string::npos) return {};
    const std::size_t last = s.find_last_not_of(ws);
    return s.substr(first, last - first + 1);
}

// The font libraries, set up once as OpenSCAD's FontCache is, and the faces
// opened so far. Every use holds the mutex: FreeType faces and the library are
// not safe to share between threads.
class FontLibrary {
public:
    static FontLibrary& instance() {
        static FontLibrary library;
        return library;
    }

    std::mutex& mutex() { return mutex_; }

    // Under the mutex. Throws strata::Error where the libraries could not start.
    FT_Face face(const std::string& font) {
        init();
        auto it = faces_.find(font);
        if (it != faces_.end()) return it->second;
        FT_Face face = openFace(font);
        if (faces_.size() >= kMaxCachedFaces) {
            FT_Done_Face(faces_.begin()->second);
            faces_.erase(faces_.begin());
        }
        faces_.emplace(font, face);
        return face;
    }

    FontLibrary(const FontLibrary&) = delete;
    FontLibrary& operator=(const FontLibrary&) = delete;

private:
    FontLibrary() = default;
    ~FontLibrary() {
        for (auto& entry : faces_) FT_Done_Face(entry.second);
        if (library_) FT_Done_FreeType(library_);
        if (config_) FcConfigDestroy(config_);
    }

    void init() {
        if (library_) return;
        // FontCache::FontCache: the system configuration, plus ~/.fonts and
        // $OPENSCAD_FONT_PATH (':'-separated), then the font list is built.
        if (!config_) {
            config_ = FcInitLoadConfig();
            if (!config_) throw Error("text(): cannot initialize the fontconfig library");
            if (const char* home = std::getenv("HOME")) addFontDir(std::string(home) + "/.fonts");
            if (const char* paths = std::getenv("OPENSCAD_FONT_PATH")) {
                std::string all(paths);
                std::size_t start = 0;
                while (true) {
                    const std::size_t end = all.find(':', start);
                    addFontDir(all.substr(start, end == std::string::npos ? std::string::npos : end - start));
                    if (end == std::string::npos) break;
                    start = end + 1;
                }
            }
            FcConfigBuildFonts(config_);
        }
        FT_Library library = nullptr;
        if (FT_Init_FreeType(&library) != 0) throw Error("text(): cannot initialize the FreeType library");
        library_ = library;
    }

    void addFontDir(const std::string& path) {
        if (path.empty() || !isDirectory(path)) return;
        char* absolute = ::realpath(path.c_str(), nullptr);
        const std::string dir = absolute ? absolute : path;
        std::free(absolute);
        FcConfigAppFontAddDir(config_, reinterpret_cast<const FcChar8*>(dir.c_str()));
    }

    // FontCache::find_face_fontconfig. fontconfig always answers with its best
    // match, so an unknown family silently becomes another font, as in OpenSCAD.
    FT_Face openFace(const std::string& font) {
        const std::string trimmedFont = trimmed(font);
        const std::string lookup = trimmedFont.empty() ? kDefaultFont : trimmedFont;

        FcPattern* pattern = FcNameParse(reinterpret_cast<const FcChar8*>(lookup.c_str()));
        if (!pattern) throw Error("text(): fontconfig cannot parse the font name '" + lookup + "'");
        FcValue trueValue;
        trueValue.type = FcTypeBool;
        trueValue.u.b = FcTrue;
        FcPatternAdd(pattern, FC_OUTLINE, trueValue, FcTrue);
        FcPatternAdd(pattern, FC_SCALABLE, trueValue, FcTrue);
        FcConfigSubstitute(config_, pattern, FcMatchPattern);
        FcDefaultSubstitute(pattern);

        FcResult result = FcResultNoMatch;
        FcPattern* match = FcFontMatch(config_, pattern, &result);
        FcPatternDestroy(pattern);
        if (!match) throw Error("text(): fontconfig finds no font for '" + lookup + "'");

        std::string file;
        int index = 0;
        FcValue fileValue;
        FcValue indexValue;
        const bool found = FcPatternGet(match, FC_FILE, 0, &fileValue) == FcResultMatch &&
                           fileValue.type == FcTypeString &&
                           FcPatternGet(match, FC_INDEX, 0, &indexValue) == FcResultMatch &&
                           indexValue.type == FcTypeInteger;
        if (found) {
            file = reinterpret_cast<const char*>(fileValue.u.s);
            index = indexValue.u.i;
        }
        FcPatternDestroy(match);
        if (!found) throw Error("text(): fontconfig finds no font file for '" + lookup + "'");

        FT_Face face = nullptr;
        if (FT_New_Face(library_, file.c_str(), index, &face) != 0 || !face) {
            throw Error("text(): FreeType cannot open the font file '" + file + "' (for '" + lookup + "')");
        }
        if (FT_Select_Charmap(face, FT_ENCODING_UNICODE) != 0) {
            const bool set = tryCharmap(face, TT_PLATFORM_MICROSOFT, TT_MS_ID_UNICODE_CS) ||
                             tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_10646) ||
                             tryCharmap(face, TT_PLATFORM_APPLE_UNICODE, -1) ||
                             tryCharmap(face, TT_PLATFORM_MICROSOFT, TT_MS_ID_SYMBOL_CS) ||
                             tryCharmap(face, TT_PLATFORM_MACINTOSH, TT_MAC_ID_ROMAN) ||
                             tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_8859_1) ||
                             tryCharmap(face, TT_PLATFORM_ISO, TT_ISO_ID_7BIT_ASCII);
            (void)set;  // OpenSCAD only warns; the glyphs then come out as .notdef
        }
        return face;
    }

    static bool tryCharmap(FT_Face face, int platform, int encoding) {
        for (int i = 0; i < face->num_charmaps; ++i) {
            FT_CharMap charmap = face->charmaps[i];
            if (charmap->platform_id == platform && (encoding < 0 || charmap->encoding_id == encoding)) {
                if (FT_Set_Charmap(face, charmap) == 0) return true;
            }
        }
        return false;
    }

    std::mutex mutex_;
    FcConfig* config_ = nullptr;
    FT_Library library_ = nullptr;
    std::map<std::string, FT_Face> faces_;
};

// FontCache::is_windows_symbol_font.
bool isWindowsSymbolFont(FT_Face face) {
    if (!face->charmap) return false;
    if (face->charmap->platform_id != TT_PLATFORM_MICROSOFT) return false;
    if (face->charmap->encoding_id != TT_MS_ID_SYMBOL_CS) return false;
    FT_UInt gindex = 0;
    const FT_ULong charcode = FT_Get_First_Char(face, &gindex);
    return gindex != 0 && charcode >= 0xf000;
}

// Strict UTF-8 decoding as glib's g_utf8_validate accepts it (no surrogates,
// no overlongs, at most U+10FFFF). Returns false on invalid input.
bool decodeUtf8(const char* s, std::vector<uint32_t>& out) {
    const auto* p = reinterpret_cast<const unsigned char*>(s);
    while (*p) {
        uint32_t c = *p;
        int extra = 0;
        uint32_t min = 0;
        if (c < 0x80) {
            extra = 0;
        } else if ((c & 0xe0) == 0xc0) {
            extra = 1, c &= 0x1f, min = 0x80;
        } else if ((c & 0xf0) == 0xe0) {
            extra = 2, c &= 0x0f, min = 0x800;
        } else if ((c & 0xf8) == 0xf0) {
            extra = 3, c &= 0x07, min = 0x10000;
        } else {
            return false;
        }
        ++p;
        for (int i = 0; i < extra; ++i, ++p) {
            if ((*p & 0xc0) != 0x80) return false;
            c = (c << 6) | (*p & 0x3f);
        }
        if (c < min || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff)) return false;
        out.push_back(c);
    }
    return true;
}

void appendUtf8(uint32_t c, std::string& out) {
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xc0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
        out += static_cast<char>(0xe0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
        out += static_cast<char>(0x80 | (c & 0x3f));
    } else {
        out += static_cast<char>(0xf0 | (c >> 18));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
        out += static_cast<char>(0x80 | (c & 0x3f));
    }
}

bool isIgnoredScript(hb_script_t script) {
    return script == HB_SCRIPT_COMMON || script == HB_SCRIPT_INHERITED || script == HB_SCRIPT_UNKNOWN ||
           script == HB_SCRIPT_INVALID;
}

struct Properties {
    hb_direction_t direction = HB_DIRECTION_LTR;
    hb_script_t script = HB_SCRIPT_INVALID;
};

// FreetypeRenderer::detect_properties followed by the conversions render()
// makes: a script or direction that HarfBuzz does not know is detected from
// the text, as when OpenSCAD instantiates the node.
Properties detectProperties(const scene::Text& text) {
    const char* s = text.text.c_str();
    const hb_script_t given = hb_script_from_string(text.script.c_str(), -1);
    hb_script_t detected = given;  // FreetypeRenderer::get_script
    hb_script_t script = given;    // what the buffer gets
    if (given == HB_SCRIPT_INVALID) {
        detected = HB_SCRIPT_INVALID;
        hb_buffer_t* buffer = hb_buffer_create();
        const int length = static_cast<int>(std::strlen(s));
        hb_buffer_add_utf8(buffer, s, length, 0, length);
        unsigned int count = 0;
        const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
        for (unsigned int i = 0; i < count; ++i) {
            const hb_script_t sc = hb_unicode_script(hb_unicode_funcs_get_default(), info[i].codepoint);
            if (!isIgnoredScript(sc)) {
                if (detected == HB_SCRIPT_INVALID) {
                    detected = sc;
                } else if (detected != sc && detected != HB_SCRIPT_UNKNOWN) {
                    detected = HB_SCRIPT_UNKNOWN;
                }
            }
        }
        hb_buffer_destroy(buffer);
        // OpenSCAD stores a detected script as its ISO 15924 tag and reads
        // that back; an ignored one leaves the (invalid) string as it was.
        if (!isIgnoredScript(detected)) {
            char tag[5] = {0, 0, 0, 0, 0};
            hb_tag_to_string(hb_script_to_iso15924_tag(detected), tag);
            script = hb_script_from_string(tag, -1);
        }
    }
    hb_direction_t direction = hb_direction_from_string(text.direction.c_str(), -1);
    if (direction == HB_DIRECTION_INVALID) direction = hb_script_get_horizontal_direction(detected);
    // OpenSCAD keeps the direction as a string and converts it back.
    direction = hb_direction_from_string(hb_direction_to_string(direction), -1);
    return {direction, script};
}

// FreetypeRenderer::calc_x_offset / calc_y_offset (an unknown value counts as left / baseline).
double xOffset(const std::string& halign, double width) {
    if (halign == "right") return -width;
    if (halign == "center") return -width / 2.0;
    return 0;
}

double yOffset(const std::string& valign, double ascend, double descend) {
    if (valign == "top") return -ascend;
    if (valign == "center") return descend / 2.0 - ascend / 2.0;
    if (valign == "bottom") return descend;
    return 0;
}

// DrawingCallback: flattens one glyph's outline into vertices.
class Drawing {
public:
    Drawing(unsigned long segments, double size) : segments_(segments), size_(size) {}

    void startGlyph(double offsetX, double offsetY) {
        glyph_ = Outlines{};
        // DrawingCallback::start_glyph marks the glyph's Polygon2d sanitized,
        // though its contours are raw: ClipperUtils::apply then takes them as
        // they are (orientation kept, no even-odd pass) into the non-zero
        // union. An even-odd pass would differ where a composite glyph's
        // parts overlap (Ç, Å, ø in Liberation Sans).
        glyph_.sanitized = true;
        outline_.clear();
        offset_ = {offsetX, offsetY};
    }

    // Returns false when the glyph has no outline (OpenSCAD drops it).
    bool finishGlyph(Outlines& out) {
        flush();
        if (glyph_.outlines.empty()) return false;
        out = std::move(glyph_);
        glyph_ = Outlines{};
        glyph_.sanitized = true;
        return true;
    }

    void addAdvance(double x, double y) {
        advance_.x += x;
        advance_.y += y;
    }

    void moveTo(glm::dvec2 to) {
        flush();
        addVertex(to);
        pen_ = to;
    }

    void lineTo(glm::dvec2 to) {
        addVertex(to);
        pen_ = to;
    }

    // OpenSCAD writes pow(1-a, 2) and pow(a, 2), which GCC at -O2 (its
    // release builds) turns into products; pow(x, 3) stays a libm call.
    // Each coordinate is summed left to right as Eigen does there.
    void conicTo(glm::dvec2 c1, glm::dvec2 to) {
        for (unsigned long idx = 1; idx <= segments_; ++idx) {
            const double a = static_cast<double>(idx) * (1.0 / static_cast<double>(segments_));
            const double b = 1 - a;
            const double b2 = b * b;
            const double a2 = a * a;
            // pen * (1-a)^2 + c1 * 2 * (1-a)^1 * a + to * a^2
            addVertex({pen_.x * b2 + c1.x * 2 * b * a + to.x * a2, pen_.y * b2 + c1.y * 2 * b * a + to.y * a2});
        }
        pen_ = to;
    }

    void cubicTo(glm::dvec2 c1, glm::dvec2 c2, glm::dvec2 to) {
        for (unsigned long idx = 1; idx <= segments_; ++idx) {
            const double a = static_cast<double>(idx) * (1.0 / static_cast<double>(segments_));
            const double b = 1 - a;
            const double b3 = std::pow(b, 3.0);
            const double b2 = b * b;
            const double a2 = a * a;
            const double a3 = std::pow(a, 3.0);
            // pen * (1-a)^3 + c1 * 3 * (1-a)^2 * a + c2 * 3 * (1-a)^1 * a^2 + to * a^3
            addVertex({pen_.x * b3 + c1.x * 3 * b2 * a + c2.x * 3 * b * a2 + to.x * a3,
                       pen_.y * b3 + c1.y * 3 * b2 * a + c2.y * 3 * b * a2 + to.y * a3});
        }
        pen_ = to;
    }

private:
    void addVertex(glm::dvec2 v) {
        outline_.push_back({size_ * ((v.x + offset_.x) + advance_.x), size_ * ((v.y + offset_.y) + advance_.y)});
    }

    void flush() {
        if (outline_.empty()) return;
        Outline o;
        o.points = std::move(outline_);
        o.positive = true;  // Outline2d's default: OpenSCAD does not set it for glyphs
        glyph_.outlines.push_back(std::move(o));
        outline_.clear();
    }

    unsigned long segments_;
    double size_;
    glm::dvec2 pen_{0, 0};
    glm::dvec2 offset_{0, 0};
    glm::dvec2 advance_{0, 0};
    std::vector<glm::dvec2> outline_;
    Outlines glyph_;

public:
    std::exception_ptr failure;  // what a callback caught
};

glm::dvec2 scaled(const FT_Vector* v) {
    return {static_cast<double>(v->x) / kScale, static_cast<double>(v->y) / kScale};
}

// FreeType is C: nothing may be thrown through it. A callback that fails
// keeps the exception and stops the decomposition.
template <typename F>
int guarded(void* user, F&& f) {
    Drawing* drawing = static_cast<Drawing*>(user);
    try {
        f(*drawing);
        return 0;
    } catch (...) {
        drawing->failure = std::current_exception();
        return 1;
    }
}

int moveToFunc(const FT_Vector* to, void* user) {
    return guarded(user, [&](Drawing& d) { d.moveTo(scaled(to)); });
}

int lineToFunc(const FT_Vector* to, void* user) {
    return guarded(user, [&](Drawing& d) { d.lineTo(scaled(to)); });
}

int conicToFunc(const FT_Vector* c1, const FT_Vector* to, void* user) {
    return guarded(user, [&](Drawing& d) { d.conicTo(scaled(c1), scaled(to)); });
}

int cubicToFunc(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
    return guarded(user, [&](Drawing& d) { d.cubicTo(scaled(c1), scaled(c2), scaled(to)); });
}

// The number of vertices a glyph will have, counted before any is made.
struct VertexCount {
    unsigned long long segments;
    unsigned long long total = 0;
};

int countPoint(const FT_Vector*, void* user) {
    static_cast<VertexCount*>(user)->total += 1;
    return 0;
}

int countConic(const FT_Vector*, const FT_Vector*, void* user) {
    auto* c = static_cast<VertexCount*>(user);
    c->total += c->segments;
    return 0;
}

int countCubic(const FT_Vector*, const FT_Vector*, const FT_Vector*, void* user) {
    auto* c = static_cast<VertexCount*>(user);
    c->total += c->segments;
    return 0;
}

// Owners for the per-call objects, so that an exception frees them.
struct HbFontDeleter {
    void operator()(hb_font_t* f) const { hb_font_destroy(f); }
};
struct HbBufferDeleter {
    void operator()(hb_buffer_t* b) const { hb_buffer_destroy(b); }
};
struct GlyphDeleter {
    void operator()(FT_GlyphRec_* g) const { FT_Done_Glyph(g); }
};
using GlyphPtr = std::unique_ptr<FT_GlyphRec_, GlyphDeleter>;

struct LoadedGlyph {
    GlyphPtr glyph;
    hb_glyph_position_t pos;
    double xOffset() const { return pos.x_offset * kUnscale; }
    double yOffset() const { return pos.y_offset * kUnscale; }
    double xAdvance() const { return pos.x_advance * kUnscale; }
    double yAdvance() const { return pos.y_advance * kUnscale; }
};

std::string fontName(const scene::Text& text) { return text.font.empty() ? std::string("(default)") : text.font; }

// Fills the buffer with the text's code points and shapes it with the font.
void shapeText(const scene::Text& text, const Properties& props, FT_Face face, hb_font_t* hbFont, hb_buffer_t* buffer) {
    hb_buffer_set_direction(buffer, props.direction);
    hb_buffer_set_script(buffer, props.script);
    hb_buffer_set_language(buffer, hb_language_from_string(text.language.c_str(), -1));

    const char* s = text.text.c_str();
    if (isWindowsSymbolFont(face)) {
        // Symbol fonts (Webdings): U+0000..U+00FF move to the 0xF000 page.
        std::vector<uint32_t> codepoints;
        if (decodeUtf8(s, codepoints)) {
            for (uint32_t c : codepoints) {
                std::string one;
                appendUtf8(c < 0x0100 ? 0xf000 + c : c, one);
                const int length = static_cast<int>(one.size());
                hb_buffer_add_utf8(buffer, one.c_str(), length, 0, length);
            }
        }
        // Invalid UTF-8: OpenSCAD warns and ignores the text.
    } else {
        const int length = static_cast<int>(std::strlen(s));
        hb_buffer_add_utf8(buffer, s, length, 0, length);
    }
    hb_shape(hbFont, buffer, nullptr, 0);
    if (!hb_buffer_allocation_successful(buffer)) throw Error("text(): HarfBuzz ran out of memory shaping the text");
}

// Loads the outline of every shaped glyph, with its position in the run.
std::vector<LoadedGlyph> loadGlyphs(const scene::Text& text, FT_Face face, hb_buffer_t* buffer) {
    unsigned int count = 0;
    const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
    const hb_glyph_position_t* positions = hb_buffer_get_glyph_positions(buffer, &count);

    std::vector<LoadedGlyph> glyphs;
    glyphs.reserve(count);
    for (unsigned int i = 0; i < count; ++i) {
        const FT_UInt index = info[i].codepoint;
        if (FT_Load_Glyph(face, index, FT_LOAD_DEFAULT) != 0) {
            throw Error("text(): FreeType cannot load glyph " + std::to_string(index) + " of font " + fontName(text));
        }
        FT_Glyph glyph = nullptr;
        if (FT_Get_Glyph(face->glyph, &glyph) != 0 || !glyph) {
            throw Error("text(): FreeType cannot copy glyph " + std::to_string(index) + " of font " + fontName(text));
        }
        GlyphPtr owned(glyph);
        if (glyph->format != FT_GLYPH_FORMAT_OUTLINE) {
            throw Error("text(): glyph " + std::to_string(index) + " of font " + fontName(text) +
                        " is not an outline (bitmap fonts cannot be used)");
        }
        glyphs.push_back({std::move(owned), positions[i]});
    }
    return glyphs;
}

// The extent of the text: its width, and how far it rises above and falls below the baseline.
struct Extent {
    double width;
    double ascend;
    double descend;
};

// The extent of the text for the alignment.
Extent extentOf(const scene::Text& text, hb_buffer_t* buffer, const std::vector<LoadedGlyph>& glyphs) {
    double width = 0, ascend = 0, descend = 0;
    const bool horizontal = HB_DIRECTION_IS_HORIZONTAL(hb_buffer_get_direction(buffer));
    for (const LoadedGlyph& g : glyphs) {
        FT_BBox bbox;
        FT_Glyph_Get_CBox(g.glyph.get(), FT_GLYPH_BBOX_GRIDFIT, &bbox);
        if (horizontal) {
            const double asc = std::max(0.0, bbox.yMax * kUnscale);
            const double desc = std::max(0.0, -bbox.yMin * kUnscale);
            width += g.xAdvance() * text.spacing;
            ascend = std::max(ascend, asc);
            descend = std::max(descend, desc);
        } else {
            const double wBox = (bbox.xMax - bbox.xMin) * kUnscale;
            width = std::max(width, wBox);
            ascend += g.yAdvance() * text.spacing;
        }
    }
    return {width, ascend, descend};
}

// Throws where the glyphs' outlines would have more than kMaxVertices vertices.
void checkVertexCount(const std::vector<LoadedGlyph>& glyphs, unsigned long segments) {
    // A huge $fn makes every curve step millions of times: refuse before
    // allocating rather than exhaust memory.
    FT_Outline_Funcs counting{};
    counting.move_to = countPoint;
    counting.line_to = countPoint;
    counting.conic_to = countConic;
    counting.cubic_to = countCubic;
    VertexCount vertexCount{segments};
    for (const LoadedGlyph& g : glyphs) {
        FT_Outline outline = reinterpret_cast<FT_OutlineGlyph>(g.glyph.get())->outline;
        FT_Outline_Decompose(&outline, &counting, &vertexCount);
        if (vertexCount.total > kMaxVertices) {
            throw Error("text(): more than " + std::to_string(kMaxVertices) + " vertices (" +
                        std::to_string(segments) + " steps per curve from $fn, $fa, $fs)");
        }
    }
}

// Flattens each glyph's outline, placed at (x0, y0) plus the advances so far, into `result`.
void drawGlyphs(const scene::Text& text, const std::vector<LoadedGlyph>& glyphs, unsigned long segments, double x0,
                double y0, std::vector<Outlines>& result) {
    FT_Outline_Funcs funcs{};
    funcs.move_to = moveToFunc;
    funcs.line_to = lineToFunc;
    funcs.conic_to = conicToFunc;
    funcs.cubic_to = cubicToFunc;
    funcs.shift = 0;
    funcs.delta = 0;

    Drawing drawing(segments, text.size);
    for (const LoadedGlyph& g : glyphs) {
        drawing.startGlyph(x0 + g.xOffset(), y0 + g.yOffset());
        FT_Outline outline = reinterpret_cast<FT_OutlineGlyph>(g.glyph.get())->outline;
        if (FT_Outline_Decompose(&outline, &funcs, &drawing) != 0) {
            if (drawing.failure) std::rethrow_exception(drawing.failure);
            throw Error("text(): FreeType cannot decompose a glyph outline of font " + fontName(text));
        }
        drawing.addAdvance(g.xAdvance() * text.spacing, g.yAdvance() * text.spacing);
        Outlines shape;
        if (drawing.finishGlyph(shape)) result.push_back(std::move(shape));
    }
}

}  // namespace

// It follows OpenSCAD's text() in its order (fragments for the size, the
// font, the code points, shaping, the extent for the alignment, each glyph's
// outline); the font library's lock, the HarfBuzz font and buffer and the
// loaded glyphs are held here to the end.
std::vector<Outlines> textGlyphs(const scene::Text& text) {
    std::vector<Outlines> result;
    // TextModule::instantiate: a fraction of the circle's fragments for the text size.
    const int fragments = fragmentsFromR(text.size, text.fragments);
    const double segmentsD = std::max(std::floor(fragments / 8) + 1, 2.0);
    const auto segments = static_cast<unsigned long>(segmentsD);

    if (text.text.c_str()[0] == '\0') return result;  // no glyphs (the font is not even looked up)

    const Properties props = detectProperties(text);

    FontLibrary& library = FontLibrary::instance();
    std::lock_guard<std::mutex> lock(library.mutex());
    FT_Face face = library.face(text.font);

    if (FT_Set_Char_Size(face, 0, static_cast<FT_F26Dot6>(kScale), 100, 100) != 0) {
        throw Error("text(): FreeType cannot set the font size for font " + fontName(text));
    }

    std::unique_ptr<hb_font_t, HbFontDeleter> hbFont(hb_ft_font_create(face, nullptr));
    std::unique_ptr<hb_buffer_t, HbBufferDeleter> buffer(hb_buffer_create());
    if (!hbFont || !buffer || !hb_buffer_allocation_successful(buffer.get())) {
        throw Error("text(): HarfBuzz cannot allocate its font or buffer");
    }
    shapeText(text, props, face, hbFont.get(), buffer.get());

    std::vector<LoadedGlyph> glyphs = loadGlyphs(text, face, buffer.get());

    const Extent extent = extentOf(text, buffer.get(), glyphs);
    const double x0 = xOffset(text.halign, extent.width);
    const double y0 = yOffset(text.valign, extent.ascend, extent.descend);

    checkVertexCount(glyphs, segments);
    drawGlyphs(text, glyphs, segments, x0, y0, result);
    return result;
}

}  // namespace strata::flat
