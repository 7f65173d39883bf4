// SVG import as OpenSCAD 2021.01 does it: its libsvg (src/libsvg/*.cc) over
// libxml2's text reader, then src/import_svg.cc.
//
// - Elements are read in document order, those inside <defs> skipped. svg, g,
//   text and tspan are containers; path, rect, circle, ellipse, polygon,
//   polyline and line make outlines; everything else (use, image, text's
//   glyphs, ...) makes none. fill and stroke colours are not looked at:
//   closed shapes are filled, and open ones (line, polyline, and the open
//   subpaths of a path unless the path has a 'z' somewhere) become their
//   stroke: Clipper's offset of the centre line by half of stroke-width
//   (attribute, else style; 1 when missing, unreadable or below 0.01), with
//   stroke-linecap and stroke-linejoin (default square and miter).
// - Curves are flattened as libsvg does: 20 points per Bezier segment, arcs
//   in |sweep| * 10 / 180 + 4 steps, circles and ellipses as 40 points, rounded
//   rect corners through a path printed with 6 significant digits.
// - Each shape is transformed by its own and its ancestors' transform
//   attributes (the root svg's is ignored), in 3x3 matrices applied one by
//   one, as Eigen evaluates them.
// - Units: the page's width/height in mm (px at 96 dpi, pt, pc, in, cm, mm;
//   unitless numbers at `dpi`), the viewBox mapped onto them (uniformly unless
//   preserveAspectRatio is none), y flipped about the page height; no viewBox
//   means user units are mm. With center, the bounding box is centred instead.
// - Each shape's outlines get an even-odd union (points scaled by 2^16 and
//   truncated), then all shapes one non-zero union, cleaned: the result is
//   what OpenSCAD's import() returns, already sanitized.
// - Numbers are read as Boost.Spirit's qi::double_ reads them (Boost 1.74),
//   digit accumulation and scaling included; text that is not entirely a
//   number reads as 0, as in libsvg.
//
// Where 2021.01 logs an error and imports nothing (unparsable XML), strata
// throws; so it does for a file without outlines and for coordinates that are
// not finite. Unlike 2021.01, external entities are not loaded (see
// refuseExternalEntity) and the file is read into memory first (at most
// 256 MiB; a gzip-compressed .svg is not unpacked).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <locale.h>
#include <stdlib.h>

#include <libxml/xmlreader.h>
#include <polyclipping/clipper.hpp>

#include "strata/core/DegreeTrig.h"
#include "FlatImportDetail.h"
#include "strata/core/Error.h"
#include "strata/core/Progress.h"

namespace strata::flat::detail {
namespace {

constexpr double kClipperScale = 65536.0;                // OpenSCAD's CLIPPER_SCALE
constexpr double kClipperRange = 4611686018427387903.0;  // Clipper's hiRange
constexpr std::size_t kMaxPoints = std::size_t(1) << 23;
constexpr double kInchToMm = 25.4;

// ---------------------------------------------------------------------------
// Boost.Spirit Qi's real_parser<double, real_policies<double>> (Boost 1.74).

double pow10(int k) {
    static const std::array<double, 309> table = [] {
        std::array<double, 309> t{};
        const locale_t c = newlocale(LC_ALL_MASK, "C", locale_t(0));
        for (int i = 0; i <= 308; ++i) t[std::size_t(i)] = strtod_l(("1e" + std::to_string(i)).c_str(), nullptr, c);
        freelocale(c);
        return t;
    }();
    return table[std::size_t(k)];
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// traits::scale(exp, n, acc_n)
bool spiritScale(long long exp, double& n, std::uint64_t acc) {
    if (exp >= 0) {
        if (exp > 308) return false;
        n = static_cast<double>(acc) * pow10(static_cast<int>(exp));
    } else if (exp < -307) {
        n = static_cast<double>((acc / 10) * 10);
        n += static_cast<double>(acc % 10);
        n /= pow10(307);
        exp += 307;
        if (exp < -307) return false;
        n /= pow10(static_cast<int>(-exp));
    } else {
        n = static_cast<double>(acc) / pow10(static_cast<int>(-exp));
    }
    return true;
}

// Case-insensitive literal (Spirit's string_parse with both cases).
bool literal(const char*& first, const char* last, const char* lower) {
    const char* i = first;
    for (; *lower; ++lower, ++i) {
        if (i == last) return false;
        const char c = *i;
        if (c != *lower && c != *lower - 'a' + 'A') return false;
    }
    first = i;
    return true;
}

// extract_uint<unused, 10, 1, -1>: consumes digits, returns how many.
std::size_t skipDigits(const char*& first, const char* last) {
    const char* save = first;
    while (first != last && isDigit(*first)) ++first;
    return static_cast<std::size_t>(first - save);
}

// What Boost.Spirit's real parser has read so far of one number, handed from
// each step of spiritReal to the next.
struct SpiritNumber {
    bool neg = false;
    std::uint64_t acc = 0;
    bool gotNumber = false;
    long long excess = 0;
    int fracDigits = 0;
    bool eHit = false;
    const char* ePos = nullptr;
};

// parse_n: at most 17 digits, leading zeros included.
bool spiritInteger(const char*& first, const char* last, std::uint64_t& acc) {
    const char* it = first;
    std::size_t leadingZeros = 0, count = 0;
    while (it != last && *it == '0' && leadingZeros < 17) ++it, ++leadingZeros;
    std::uint64_t val = 0;
    while (count + leadingZeros < 17 && it != last && isDigit(*it)) {
        val = val * 10 + static_cast<std::uint64_t>(*it - '0');
        ++it, ++count;
    }
    if (count + leadingZeros >= 1) {
        acc = val;
        first = it;
        return true;
    }
    return false;
}

// Where no digits came: "nan", "nan(...)", "inf" or "infinity", any case; false when none of them.
bool spiritNanInf(const char*& first, const char* last, bool neg, double& attr) {
    const char* it = first;
    if (it != last && (*it == 'n' || *it == 'N')) {
        if (literal(it, last, "nan")) {
            bool ok = true;
            if (it != last && *it == '(') {
                const char* i = it;
                while (++i != last && *i != ')') {
                }
                if (i == last)
                    ok = false;
                else
                    it = i + 1;
            }
            if (ok) {
                first = it;
                attr = neg ? -std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::quiet_NaN();
                return true;
            }
        }
    } else if (it != last && (*it == 'i' || *it == 'I')) {
        if (literal(it, last, "inf")) {
            literal(it, last, "inity");
            first = it;
            attr = neg ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
            return true;
        }
    }
    return false;
}

// The '.' and fraction digits, if any, then whether an 'e' follows; false,
// with first back at save, when neither integer nor fraction digits came.
bool spiritFraction(const char*& first, const char* last, const char* save, SpiritNumber& num) {
    if (first != last && *first == '.') {
        ++first;
        if (num.excess != 0) {
            skipDigits(first, last);
        } else {
            // parse_frac_n: accumulate while the 64-bit accumulator does not overflow.
            const char* it = first;
            std::size_t count = 0;
            bool overflow = false;
            while (it != last && isDigit(*it)) {
                const std::uint64_t digit = static_cast<std::uint64_t>(*it - '0');
                const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
                if (num.acc > max / 10 || num.acc * 10 > max - digit) {
                    overflow = true;
                    break;
                }
                num.acc = num.acc * 10 + digit;
                ++it, ++count;
            }
            if (overflow || count >= 1) {
                first = it;
                num.fracDigits = static_cast<int>(count);
                skipDigits(first, last);
            } else if (!num.gotNumber) {
                first = save;
                return false;
            }
        }
        num.ePos = first;
        if (first != last && (*first == 'e' || *first == 'E')) ++first, num.eHit = true;
    } else {
        if (!num.gotNumber) {
            first = save;
            return false;
        }
        num.ePos = first;
        if (first != last && (*first == 'e' || *first == 'E')) ++first, num.eHit = true;
    }
    return true;
}

// After an 'e': the exponent and the number scaled by it into n, or, when
// the exponent is unusable, the 'e' left unread; false when out of range.
bool spiritExponent(const char*& first, const char* last, const SpiritNumber& num, double& n) {
    // parse_exp_n: a signed int, at least one digit, no overflow.
    const char* it = first;
    bool expNeg = false;
    if (it != last && (*it == '-' || *it == '+')) expNeg = *it++ == '-';
    long long exp = 0;
    std::size_t digits = 0;
    bool overflow = false;
    while (it != last && isDigit(*it)) {
        // Past int's range the digits are only counted: the value is
        // refused anyway, and more of them would overflow `exp` itself.
        if (!overflow) exp = exp * 10 + (*it - '0');
        if (exp > 2147483648LL) overflow = true;
        ++it, ++digits;
    }
    if (digits > 0 && !overflow && (expNeg || exp <= 2147483647LL)) {
        first = it;
        if (!spiritScale((expNeg ? -exp : exp) + num.excess - num.fracDigits, n, num.acc)) return false;
    } else {
        first = num.ePos;
        spiritScale(-num.fracDigits, n, num.acc);
    }
    return true;
}

// Boost.Spirit's real parser step by step (sign, integer digits, fraction,
// exponent, nan and inf), the parser OpenSCAD's SVG reader uses, so that
// every number reads to the same double; the steps above share its running
// state in a SpiritNumber.
bool spiritReal(const char*& first, const char* last, double& attr) {
    if (first == last) return false;
    const char* save = first;
    SpiritNumber num;
    if (*first == '-' || *first == '+') {
        num.neg = *first == '-';
        ++first;
    }
    num.gotNumber = spiritInteger(first, last, num.acc);
    if (!num.gotNumber) {
        if (spiritNanInf(first, last, num.neg, attr)) return true;
    } else {
        num.excess = static_cast<long long>(skipDigits(first, last));
    }

    if (!spiritFraction(first, last, save, num)) return false;

    double n = 0;
    if (num.eHit) {
        if (!spiritExponent(first, last, num, n)) return false;
    } else if (num.fracDigits) {
        spiritScale(-num.fracDigits, n, num.acc);
    } else if (num.excess) {
        if (!spiritScale(num.excess, n, num.acc)) return false;
    } else {
        n = static_cast<double>(num.acc);
    }
    attr = num.neg ? -n : n;
    return true;
}

// libsvg's parse_double: the whole text as a number, else 0.
double parseDouble(std::string_view s) {
    const char* it = s.data();
    const char* end = s.data() + s.size();
    double d = 0.0;
    const bool ok = spiritReal(it, end, d);
    return ok && it == end ? d : 0;
}

bool isQiSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }
void skipSpace(const char*& it, const char* end) {
    while (it != end && isQiSpace(*it)) ++it;
}

enum class Unit { Undefined, None, Percent, Em, Ex, Px, In, Cm, Mm, Pt, Pc };
struct Length {
    double number = 0.0;
    Unit unit = Unit::Undefined;
};

// libsvg's parse_length: number >> -unit with spaces skipped, all of it.
Length parseLength(std::string_view s) {
    const char* it = s.data();
    const char* end = s.data() + s.size();
    skipSpace(it, end);
    double number = 0;
    if (!spiritReal(it, end, number)) return {};
    skipSpace(it, end);
    Unit unit = Unit::None;
    static const std::pair<const char*, Unit> kUnits[] = {{"em", Unit::Em}, {"ex", Unit::Ex}, {"px", Unit::Px},
                                                          {"in", Unit::In}, {"cm", Unit::Cm}, {"mm", Unit::Mm},
                                                          {"pt", Unit::Pt}, {"pc", Unit::Pc}, {"%", Unit::Percent}};
    for (const auto& [text, u] : kUnits) {
        const std::size_t n = std::strlen(text);
        if (static_cast<std::size_t>(end - it) >= n && std::memcmp(it, text, n) == 0) {
            it += n;
            unit = u;
            break;
        }
    }
    skipSpace(it, end);
    if (it != end) return {};
    return {number, unit};
}

struct Viewbox {
    double x = 0, y = 0, width = 0, height = 0;
    bool valid = false;
};

// libsvg's parse_viewbox: four numbers, each pair optionally comma-separated.
Viewbox parseViewbox(std::string_view s) {
    const char* it = s.data();
    const char* end = s.data() + s.size();
    double v[4];
    for (int i = 0; i < 4; ++i) {
        skipSpace(it, end);
        if (i > 0 && it != end && *it == ',') {
            ++it;
            skipSpace(it, end);
        }
        if (!spiritReal(it, end, v[i])) return {};
    }
    skipSpace(it, end);
    if (it != end || !(v[2] >= 0.0) || !(v[3] >= 0.0)) return {};
    return {v[0], v[1], v[2], v[3], true};
}

enum class Align { None, Min, Mid, Max };
struct Alignment {
    Align x = Align::Mid, y = Align::Mid;
    bool meet = true;
};

// libsvg's parse_alignment: [defer] <align> [meet|slice]; default xMidYMid meet.
Alignment parseAlignment(std::string_view s) {
    const char* it = s.data();
    const char* end = s.data() + s.size();
    auto word = [&](const char* w) {
        const std::size_t n = std::strlen(w);
        if (static_cast<std::size_t>(end - it) >= n && std::memcmp(it, w, n) == 0) {
            it += n;
            return true;
        }
        return false;
    };
    Alignment result;
    skipSpace(it, end);
    word("defer");
    skipSpace(it, end);
    static const struct {
        const char* text;
        Align x, y;
    } kAligns[] = {{"none", Align::None, Align::None},   {"xMinYMin", Align::Min, Align::Min},
                   {"xMidYMin", Align::Mid, Align::Min}, {"xMaxYMin", Align::Max, Align::Min},
                   {"xMinYMid", Align::Min, Align::Mid}, {"xMidYMid", Align::Mid, Align::Mid},
                   {"xMaxYMid", Align::Max, Align::Mid}, {"xMinYMax", Align::Min, Align::Max},
                   {"xMidYMax", Align::Mid, Align::Max}, {"xMaxYMax", Align::Max, Align::Max}};
    const Align* ax = nullptr;
    const Align* ay = nullptr;
    for (const auto& a : kAligns) {
        if (word(a.text)) {
            ax = &a.x;
            ay = &a.y;
            break;
        }
    }
    if (!ax) return result;
    skipSpace(it, end);
    bool meet = true, hasMeet = false;
    if (word("meet"))
        hasMeet = true;
    else if (word("slice"))
        hasMeet = true, meet = false;
    skipSpace(it, end);
    if (it != end) return result;
    result.x = *ax;
    result.y = *ay;
    if (hasMeet) result.meet = meet;
    return result;
}

// boost::char_separator<char>(dropped, kept) with empty tokens dropped.
std::vector<std::string> tokenize(std::string_view s, std::string_view dropped, std::string_view kept) {
    std::vector<std::string> tokens;
    std::string current;
    for (char c : s) {
        if (dropped.find(c) != std::string_view::npos) {
            if (!current.empty()) tokens.push_back(std::move(current)), current.clear();
        } else if (kept.find(c) != std::string_view::npos) {
            if (!current.empty()) tokens.push_back(std::move(current)), current.clear();
            tokens.emplace_back(1, c);
        } else {
            current += c;
        }
    }
    if (!current.empty()) tokens.push_back(std::move(current));
    return tokens;
}

// libsvg's tan_degrees / atan2_degrees (src/degree_trig.cc).
double tanDegrees(double x) {
    const double huge = double(1L << 26) * 360.0 * double(1L << 26);
    const int cycles = toIntX86(std::floor(x / 180.0));  // 2021.01's int conversion
    if (x < 180.0 && x >= 0.0) {
    } else if (x < huge && x > -huge) {
        x -= 180.0 * cycles;
    } else {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const bool oppose = x > 90.0;
    if (oppose) x = 180.0 - x;
    if (x == 0.0) {
        x = (cycles % 2) == 0 ? 0.0 : -0.0;
    } else if (x == 30.0) {
        x = 0.57735026918962573106;  // M_SQRT1_3
    } else if (x == 45.0) {
        x = 1.0;
    } else if (x == 60.0) {
        x = 1.73205080756887719318;  // M_SQRT3
    } else if (x == 90.0) {
        x = (cycles % 2) == 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    } else {
        x = std::tan(x * kDegToRad);
    }
    return oppose ? -x : x;
}

double atan2Degrees(double y, double x) {
    const double degs = std::atan2(y, x) * 57.2957795130823208767;  // M_RAD2DEG
    const double whole = std::round(degs);
    if (std::fabs(degs - whole) < 3.0E-14) return whole;
    return degs;
}

// ---------------------------------------------------------------------------
// Shapes

using Mat3 = std::array<std::array<double, 3>, 3>;
using Point = std::array<double, 3>;  // x, y and libsvg's third coordinate
using PathPoints = std::vector<Point>;
using PathList = std::vector<PathPoints>;

Mat3 mat(double a, double b, double c, double d, double e, double f, double g, double h, double i) {
    return {{{a, b, c}, {d, e, f}, {g, h, i}}};
}

// Eigen's Matrix3d * Vector3d: each row summed left to right.
Point transformPoint(const Mat3& m, const Point& v) {
    Point r;
    for (int i = 0; i < 3; ++i)
        r[std::size_t(i)] = (m[std::size_t(i)][0] * v[0] + m[std::size_t(i)][1] * v[1]) + m[std::size_t(i)][2] * v[2];
    return r;
}

enum class Kind { Page, Group, Text, Tspan, Data, Circle, Ellipse, Line, Polygon, Polyline, Rect, Path };

struct Shape {
    Kind kind = Kind::Data;
    Shape* parent = nullptr;
    std::string transform, strokeWidth, strokeLinecap, strokeLinejoin, style;
    PathList paths;
    // svg pages
    Length width, height;
    Viewbox viewbox;
    Alignment alignment;

    bool container() const {
        return kind == Kind::Page || kind == Kind::Group || kind == Kind::Text || kind == Kind::Tspan;
    }
};

using Attributes = std::map<std::string, std::string>;

class ShapeBuilder {
public:
    explicit ShapeBuilder(std::size_t& pointCount) : pointCount_(pointCount) {}

    void setAttrs(Shape& s, Attributes& attrs) {
        if (s.kind == Kind::Page) {
            s.width = parseLength(attrs["width"]);
            s.height = parseLength(attrs["height"]);
            s.viewbox = parseViewbox(attrs["viewBox"]);
            s.alignment = parseAlignment(attrs["preserveAspectRatio"]);
            return;
        }
        s.transform = attrs["transform"];
        s.strokeWidth = attrs["stroke-width"];
        s.strokeLinecap = attrs["stroke-linecap"];
        s.strokeLinejoin = attrs["stroke-linejoin"];
        s.style = attrs["style"];
        switch (s.kind) {
            case Kind::Circle: {
                const double x = parseDouble(attrs["cx"]), y = parseDouble(attrs["cy"]), r = parseDouble(attrs["r"]);
                PathPoints path;
                drawEllipse(path, x, y, r, r);
                s.paths.push_back(std::move(path));
                break;
            }
            case Kind::Ellipse: {
                const double x = parseDouble(attrs["cx"]), y = parseDouble(attrs["cy"]);
                const double rx = parseDouble(attrs["rx"]), ry = parseDouble(attrs["ry"]);
                PathPoints path;
                drawEllipse(path, x, y, rx, ry);
                s.paths.push_back(std::move(path));
                break;
            }
            case Kind::Line: {
                PathPoints path{{parseDouble(attrs["x1"]), parseDouble(attrs["y1"]), 0},
                                {parseDouble(attrs["x2"]), parseDouble(attrs["y2"]), 0}};
                offsetPath(s, s.paths, path);
                break;
            }
            case Kind::Polygon:
            case Kind::Polyline: {
                PathPoints path;
                double x = 0.0;
                bool first = true;
                for (const std::string& v : tokenize(attrs["points"], " ,", "")) {
                    const double p = parseDouble(v);
                    if (first)
                        x = p;
                    else
                        push(path, {x, p, 0});
                    first = !first;
                }
                if (s.kind == Kind::Polygon) {
                    if (!path.empty()) path.push_back(path[0]);
                    s.paths.push_back(std::move(path));
                } else {
                    offsetPath(s, s.paths, path);
                }
                break;
            }
            case Kind::Rect: rect(s, attrs); break;
            case Kind::Path: pathData(s, attrs["d"]); break;
            default: break;
        }
    }

    // apply_transform: the shape's and its ancestors' transforms, the
    // outermost first in the list, applied from the last.
    void applyTransform(Shape& s) {
        std::vector<Mat3> matrices;
        for (Shape* t = &s; t->parent != nullptr; t = t->parent) collectTransforms(matrices, *t);
        if (matrices.empty()) return;
        for (PathPoints& p : s.paths) {
            for (Point& v : p) {
                Point r{v[0], v[1], 1};
                for (auto it = matrices.rbegin(); it != matrices.rend(); ++it) r = transformPoint(*it, r);
                v = r;
            }
        }
    }

private:
    void push(PathPoints& path, const Point& p) {
        if (++pointCount_ > kMaxPoints) {
            throw Error("import: the SVG file has more than " + std::to_string(kMaxPoints) + " points");
        }
        path.push_back(p);
    }

    static std::string style(const Shape& s, const std::string& name) {
        for (const std::string& entry : split(s.style, ';')) {
            const std::vector<std::string> values = split(entry, ':');
            if (values.size() != 2) continue;
            if (values[0] == name) return values[1];
        }
        return {};
    }

    // boost::split with is_any_of: empty pieces kept.
    static std::vector<std::string> split(const std::string& s, char sep) {
        std::vector<std::string> out;
        std::size_t start = 0;
        while (true) {
            const std::size_t at = s.find(sep, start);
            if (at == std::string::npos) {
                out.push_back(s.substr(start));
                return out;
            }
            out.push_back(s.substr(start, at - start));
            start = at + 1;
        }
    }

    static double strokeWidth(const Shape& s) {
        const double w = parseDouble(s.strokeWidth.empty() ? style(s, "stroke-width") : s.strokeWidth);
        return w < 0.01 ? 1 : w;
    }

    static ClipperLib::EndType linecap(const Shape& s) {
        const std::string cap = s.strokeLinecap.empty() ? style(s, "stroke-linecap") : s.strokeLinecap;
        if (cap == "butt") return ClipperLib::etOpenButt;
        if (cap == "round") return ClipperLib::etOpenRound;
        return ClipperLib::etOpenSquare;
    }

    static ClipperLib::JoinType linejoin(const Shape& s) {
        const std::string join = s.strokeLinejoin.empty() ? style(s, "stroke-linejoin") : s.strokeLinejoin;
        if (join == "bevel") return ClipperLib::jtSquare;
        if (join == "round") return ClipperLib::jtRound;
        return ClipperLib::jtMiter;  // also for "square"
    }

    static ClipperLib::cInt strokeGrid(double v) {
        const double scaled = v * 10000;
        if (!(std::fabs(scaled) < kClipperRange)) throw Error("import: an SVG coordinate is not finite or too large");
        return static_cast<ClipperLib::cInt>(scaled);
    }

    // offset_path: the stroke of an open line, in units of 1/10000.
    void offsetPath(const Shape& s, PathList& out, const PathPoints& path) {
        const double width = strokeWidth(s);
        if (!std::isfinite(width) || width > 1e12) throw Error("import: an SVG stroke-width is not usable");
        const std::string step = "import: stroking an SVG path of " + std::to_string(path.size()) + " points";
        reportProgress(step.c_str(), 0, 0);
        ClipperLib::Path line;
        for (const Point& v : path) line.emplace_back(strokeGrid(v[0]), strokeGrid(v[1]));
        ClipperLib::Paths result;
        ClipperLib::ClipperOffset co;
        co.AddPath(line, linejoin(s), linecap(s));
        co.Execute(result, width * 5000.0);
        for (const ClipperLib::Path& p : result) {
            out.emplace_back();
            for (const ClipperLib::IntPoint& point : p) {
                push(out.back(), {static_cast<double>(point.X) / 10000.0, static_cast<double>(point.Y) / 10000.0, 0});
            }
            push(out.back(), {static_cast<double>(p[0].X) / 10000.0, static_cast<double>(p[0].Y) / 10000.0, 0});
        }
    }

    void drawEllipse(PathPoints& path, double x, double y, double rx, double ry) {
        const unsigned long fn = 40;
        for (unsigned long idx = 1; idx <= fn; ++idx) {
            const double a = idx * 360.0 / fn;
            const double xx = rx * sinDegrees(a) + x;
            const double yy = ry * cosDegrees(a) + y;
            push(path, {xx, yy, 0});
        }
    }

    static std::string format(double v) {
        std::ostringstream os;
        os.imbue(std::locale::classic());
        os << v;
        return os.str();
    }

    void rect(Shape& s, Attributes& attrs) {
        const double x = parseDouble(attrs["x"]), y = parseDouble(attrs["y"]);
        const double width = parseDouble(attrs["width"]), height = parseDouble(attrs["height"]);
        double rx = parseDouble(attrs["rx"]), ry = parseDouble(attrs["ry"]);
        const bool hasRx = !(std::fabs(rx) < 1e-8);
        const bool hasRy = !(std::fabs(ry) < 1e-8);
        if (hasRx || hasRy) {
            if (!hasRx)
                rx = ry;
            else if (!hasRy)
                ry = rx;
            if (rx > (width / 2)) rx = width / 2;
            if (ry > (height / 2)) ry = height / 2;
            // The path libsvg prints (boost::format, 6 significant digits) and reads back.
            std::string d = "M " + format(x + rx) + "," + format(y) + " H " + format(x + width - rx) + " A " +
                            format(rx) + "," + format(ry) + " 0 0,1 " + format(x + width) + "," + format(y + ry) +
                            " V " + format(y + height - ry) + " A " + format(rx) + "," + format(ry) + " 0 0,1 " +
                            format(x + width - rx) + "," + format(y + height) + " H " + format(x + rx) + " A " +
                            format(rx) + "," + format(ry) + " 0 0,1 " + format(x) + "," + format(y + height - ry) +
                            " V " + format(y + ry) + " A " + format(rx) + "," + format(ry) + " 0 0,1 " +
                            format(x + rx) + "," + format(y) + " z";
            pathData(s, d);
        } else {
            PathPoints path;
            push(path, {x, y, 0});
            push(path, {x + width, y, 0});
            push(path, {x + width, y + height, 0});
            push(path, {x, y + height, 0});
            push(path, {x, y, 0});
            s.paths.push_back(std::move(path));
        }
    }

    static bool isOpenPath(const PathPoints& path) {
        const Point& p1 = path[0];
        const Point& p2 = path.back();
        const double distance =
            std::pow(std::pow(p1[0] - p2[0], 2) + std::pow(p1[1] - p2[1], 2) + std::pow(p1[2] - p2[2], 2), 0.5);
        return distance > 0.1;
    }

    static double vectorAngle(double ux, double uy, double vx, double vy) {
        double angle = atan2Degrees(vy, vx) - atan2Degrees(uy, ux);
        if (angle < 0) angle += 360;
        return angle;
    }

    void arcTo(PathPoints& path, double x1, double y1, double rx, double ry, double x2, double y2, double angle,
               bool large, bool sweep) {
        const double cosRad = cosDegrees(angle);
        const double sinRad = sinDegrees(angle);
        const double dx = (x1 - x2) / 2;
        const double dy = (y1 - y2) / 2;
        const double x1_ = cosRad * dx + sinRad * dy;
        const double y1_ = -sinRad * dx + cosRad * dy;

        const double d = (x1_ * x1_) / (rx * rx) + (y1_ * y1_) / (ry * ry);
        if (d > 1) {
            rx = std::fabs(std::sqrt(d) * rx);
            ry = std::fabs(std::sqrt(d) * ry);
        }
        double t1 = rx * rx * ry * ry - rx * rx * y1_ * y1_ - ry * ry * x1_ * x1_;
        const double t2 = rx * rx * y1_ * y1_ + ry * ry * x1_ * x1_;
        if (t1 < 0) t1 = 0;
        double t3 = std::sqrt(t1 / t2);
        if (large == sweep) t3 = -t3;

        const double cx_ = t3 * rx * y1_ / ry;
        const double cy_ = t3 * -ry * x1_ / rx;
        const double cx = cosRad * cx_ - sinRad * cy_ + (x1 + x2) / 2.0;
        const double cy = sinRad * cx_ + cosRad * cy_ + (y1 + y2) / 2.0;

        const double ux = (x1_ - cx_) / rx;
        const double uy = (y1_ - cy_) / ry;
        const double vx = (-x1_ - cx_) / rx;
        const double vy = (-y1_ - cy_) / ry;
        const double theta = vectorAngle(1, 0, ux, uy);
        double delta = vectorAngle(ux, uy, vx, vy);
        if (!sweep) delta -= 360;

        // int steps = fabs(delta) * 10.0 / 180 + 4, as an x86-64 build converts it.
        const double stepsReal = std::fabs(delta) * 10.0 / 180 + 4;
        const int steps =
            (stepsReal > -2147483649.0 && stepsReal < 2147483648.0) ? static_cast<int>(stepsReal) : INT32_MIN;
        for (int a = 0; a <= steps; ++a) {
            const double phi = theta + delta * a / steps;
            const double xx = cosRad * cosDegrees(phi) * rx - sinRad * sinDegrees(phi) * ry;
            const double yy = sinRad * cosDegrees(phi) * rx + cosRad * sinDegrees(phi) * ry;
            push(path, {xx + cx, yy + cy, 0});
        }
    }

    static double t(double t, int exp) { return std::pow(1.0 - t, exp); }

    void curveTo(PathPoints& path, double x, double y, double cx1, double cy1, double x2, double y2) {
        const unsigned long fn = 20;
        for (unsigned long idx = 1; idx <= fn; ++idx) {
            const double a = idx * (1.0 / (double)fn);
            const double xx = x * t(a, 2) + cx1 * 2 * t(a, 1) * a + x2 * a * a;
            const double yy = y * t(a, 2) + cy1 * 2 * t(a, 1) * a + y2 * a * a;
            push(path, {xx, yy, 0});
        }
    }

    void curveTo(PathPoints& path, double x, double y, double cx1, double cy1, double cx2, double cy2, double x2,
                 double y2) {
        const unsigned long fn = 20;
        for (unsigned long idx = 1; idx <= fn; ++idx) {
            const double a = idx * (1.0 / (double)fn);
            const double xx = x * t(a, 3) + cx1 * 3 * t(a, 2) * a + cx2 * 3 * t(a, 1) * a * a + x2 * a * a * a;
            const double yy = y * t(a, 3) + cy1 * 3 * t(a, 2) * a + cy2 * 3 * t(a, 1) * a * a + y2 * a * a * a;
            push(path, {xx, yy, 0});
        }
    }

    // libsvg's split_dots: "1.5.5" is "1.5" and ".5".
    static std::vector<std::string> splitDots(const std::string& str) {
        if (std::count(str.begin(), str.end(), '.') < 2) return {str};
        std::vector<std::string> result;
        std::string text;
        bool dotSeen = false;
        for (const std::string& token : tokenize(str, "", ".")) {
            text += token;
            if (token == ".") {
                dotSeen = true;
                continue;
            } else if (dotSeen) {
                result.push_back(text);
                text.clear();
            }
        }
        return result;
    }

    // The state of libsvg's path-data parser between tokens: the pen, the
    // command being read and its arguments so far, and a '-' or a number
    // ending in 'e' waiting for the next token.
    struct PathPen {
        double x = 0, y = 0, xx = 0, yy = 0, rx = 0, ry = 0, cx1 = 0, cy1 = 0, cx2 = 0, cy2 = 0, angle = 0;
        bool large = false, sweep = false, lastCubic = false, lastQuadratic = false;
        char cmd = ' ';
        int point = 0;
        bool negate = false, closed = false;
        std::string exp;
        // A segment drawn: the pen moves to its end, the next argument starts
        // a new group, and the segment's kind is kept for a smooth curve after it.
        void endSegment(bool cubic, bool quadratic) {
            x = xx;
            y = yy;
            point = -1;
            lastCubic = cubic;
            lastQuadratic = quadratic;
        }
    };

    void pathData(Shape& s, const std::string& data) {
        const std::string commands = "-zmlcqahvstZMLCQAHVST";
        std::vector<std::string> tokens;
        for (const std::string& token : tokenize(data, " ,", commands)) {
            for (std::string& part : splitDots(token)) tokens.push_back(std::move(part));
        }

        PathList& list = s.paths;
        PathPen pen;
        list.emplace_back();
        for (const std::string& v : tokens) {
            double p = 0;
            if (!pathToken(pen, commands, v, p)) continue;
            pathStep(s, pen, p);
        }

        while (!list.empty() && list.back().empty()) list.pop_back();
        if (!pen.closed && !list.empty() && isOpenPath(list.back())) {
            const PathPoints open = list.back();
            list.pop_back();
            offsetPath(s, list, open);
        }
    }

    // A token: a command starts its arguments, a number becomes the next one
    // in p; false for a '-' or a number ending in 'e', kept for the next token.
    static bool pathToken(PathPen& pen, const std::string& commands, const std::string& v, double& p) {
        if (v.length() == 1 && commands.find(v) != std::string::npos) {
            if (v[0] == '-') {
                pen.negate = true;
                return false;
            }
            pen.point = -1;
            pen.cmd = v[0];
        } else {
            if (v.back() == 'e') {
                pen.exp = pen.negate ? std::string("-") + v : v;
                pen.negate = false;
                return false;
            }
            if (pen.exp.empty()) {
                p = parseDouble(v);
                p = pen.negate ? -p : p;
            } else {
                p = parseDouble(pen.exp + (pen.negate ? "-" : "") + v);
                pen.exp = "";
            }
            pen.negate = false;
        }
        return true;
    }

    // Hands the argument p (0 for the command itself) to the current command.
    void pathStep(Shape& s, PathPen& pen, double p) {
        PathList& list = s.paths;
        switch (pen.cmd) {
            case 'a':
            case 'A': pathArc(list, pen, p); break;
            case 'l':
            case 'L': pathLine(list, pen, p); break;
            case 'c':
            case 'C': pathCubic(list, pen, p); break;
            case 's':
            case 'S': pathSmoothCubic(list, pen, p); break;
            case 'q':
            case 'Q': pathQuadratic(list, pen, p); break;
            case 't':
            case 'T': pathSmoothQuadratic(list, pen, p); break;
            case 'm':
            case 'M': pathMove(s, pen, p); break;
            case 'v':
            case 'V': pathVertical(list, pen, p); break;
            case 'h':
            case 'H': pathHorizontal(list, pen, p); break;
            case 'z':
            case 'Z': pathClose(list, pen); break;
        }
        pen.point++;
    }

    // a/A: radii, rotation, large-arc and sweep flags, then the end point.
    void pathArc(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0: pen.rx = std::fabs(p); break;
            case 1: pen.ry = std::fabs(p); break;
            case 2: pen.angle = p; break;
            case 3: pen.large = p > 0.5; break;
            case 4: pen.sweep = p > 0.5; break;
            case 5: pen.xx = pen.cmd == 'a' ? pen.x + p : p; break;
            case 6:
                pen.yy = pen.cmd == 'a' ? pen.y + p : p;
                arcTo(list.back(), pen.x, pen.y, pen.rx, pen.ry, pen.xx, pen.yy, pen.angle, pen.large, pen.sweep);
                pen.endSegment(false, false);
                break;
        }
    }

    // l/L: a straight line to the end point.
    void pathLine(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0: pen.xx = pen.cmd == 'l' ? pen.x + p : p; break;
            case 1:
                pen.yy = pen.cmd == 'l' ? pen.y + p : p;
                push(list.back(), {pen.xx, pen.yy, 0});
                pen.endSegment(false, false);
                break;
        }
    }

    // c/C: a cubic Bezier curve, two control points then the end point.
    void pathCubic(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0: pen.cx1 = p; break;
            case 1: pen.cy1 = p; break;
            case 2: pen.cx2 = p; break;
            case 3: pen.cy2 = p; break;
            case 4: pen.xx = pen.cmd == 'c' ? pen.x + p : p; break;
            case 5:
                pen.yy = pen.cmd == 'c' ? pen.y + p : p;
                pen.cx1 = pen.cmd == 'c' ? pen.x + pen.cx1 : pen.cx1;
                pen.cy1 = pen.cmd == 'c' ? pen.y + pen.cy1 : pen.cy1;
                pen.cx2 = pen.cmd == 'c' ? pen.x + pen.cx2 : pen.cx2;
                pen.cy2 = pen.cmd == 'c' ? pen.y + pen.cy2 : pen.cy2;
                curveTo(list.back(), pen.x, pen.y, pen.cx1, pen.cy1, pen.cx2, pen.cy2, pen.xx, pen.yy);
                pen.endSegment(true, false);
                break;
        }
    }

    // s/S: a cubic Bezier curve whose first control point mirrors the last one.
    void pathSmoothCubic(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0:
                if (pen.lastCubic) {
                    // current + (current - old control point)
                    pen.cx1 = pen.x + (pen.x - pen.cx2);
                    pen.cy1 = pen.y + (pen.y - pen.cy2);
                } else {
                    pen.cx1 = pen.x;
                    pen.cy1 = pen.y;
                }
                pen.cx2 = p;
                break;
            case 1: pen.cy2 = p; break;
            case 2: pen.xx = pen.cmd == 's' ? pen.x + p : p; break;
            case 3:
                pen.yy = pen.cmd == 's' ? pen.y + p : p;
                pen.cx2 = pen.cmd == 's' ? pen.x + pen.cx2 : pen.cx2;
                pen.cy2 = pen.cmd == 's' ? pen.y + pen.cy2 : pen.cy2;
                curveTo(list.back(), pen.x, pen.y, pen.cx1, pen.cy1, pen.cx2, pen.cy2, pen.xx, pen.yy);
                pen.endSegment(true, false);
                break;
        }
    }

    // q/Q: a quadratic Bezier curve, a control point then the end point.
    void pathQuadratic(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0: pen.cx1 = p; break;
            case 1: pen.cy1 = p; break;
            case 2: pen.xx = pen.cmd == 'q' ? pen.x + p : p; break;
            case 3:
                pen.yy = pen.cmd == 'q' ? pen.y + p : p;
                pen.cx1 = pen.cmd == 'q' ? pen.x + pen.cx1 : pen.cx1;
                pen.cy1 = pen.cmd == 'q' ? pen.y + pen.cy1 : pen.cy1;
                curveTo(list.back(), pen.x, pen.y, pen.cx1, pen.cy1, pen.xx, pen.yy);
                pen.endSegment(false, true);
                break;
        }
    }

    // t/T: a quadratic Bezier curve whose control point mirrors the last one.
    void pathSmoothQuadratic(PathList& list, PathPen& pen, double p) {
        switch (pen.point) {
            case 0:
                if (pen.lastQuadratic) {
                    pen.cx1 = pen.x + (pen.x - pen.cx1);
                    pen.cy1 = pen.y + (pen.y - pen.cy1);
                } else {
                    pen.cx1 = pen.x;
                    pen.cy1 = pen.y;
                }
                pen.xx = pen.cmd == 't' ? pen.x + p : p;
                break;
            case 1:
                pen.yy = pen.cmd == 't' ? pen.y + p : p;
                curveTo(list.back(), pen.x, pen.y, pen.cx1, pen.cy1, pen.xx, pen.yy);
                pen.endSegment(false, true);
                break;
        }
    }

    // m/M: starts a new subpath (stroking the previous one if open); later
    // pairs are lines, as the command turns into l/L.
    void pathMove(Shape& s, PathPen& pen, double p) {
        PathList& list = s.paths;
        switch (pen.point) {
            case 0: pen.xx = pen.cmd == 'm' ? pen.x + p : p; break;
            case 1: {
                pen.yy = pen.cmd == 'm' ? pen.y + p : p;
                pen.cmd = pen.cmd == 'm' ? 'l' : 'L';
                if (!list.back().empty()) {
                    if (isOpenPath(list.back())) {
                        const PathPoints open = list.back();
                        list.pop_back();
                        offsetPath(s, list, open);
                    }
                    list.emplace_back();
                }
                push(list.back(), {pen.xx, pen.yy, 0});
                pen.endSegment(false, false);
                break;
            }
        }
    }

    // v/V: a vertical line.
    void pathVertical(PathList& list, PathPen& pen, double p) {
        if (pen.point == 0) {
            pen.y = pen.cmd == 'v' ? pen.y + p : p;
            push(list.back(), {pen.x, pen.y, 0});
            pen.point = -1;
            pen.lastCubic = pen.lastQuadratic = false;
        }
    }

    // h/H: a horizontal line.
    void pathHorizontal(PathList& list, PathPen& pen, double p) {
        if (pen.point == 0) {
            pen.x = pen.cmd == 'h' ? pen.x + p : p;
            push(list.back(), {pen.x, pen.y, 0});
            pen.point = -1;
            pen.lastCubic = pen.lastQuadratic = false;
        }
    }

    // z/Z (on the command and on every number after it): closes the subpath
    // back to its first point and starts another; the argument count runs on.
    void pathClose(PathList& list, PathPen& pen) {
        if (!list.back().empty()) {
            const Point first = list.back()[0];
            push(list.back(), first);
            pen.x = first[0];
            pen.y = first[1];
        }
        list.emplace_back();
        pen.closed = true;
        pen.lastCubic = pen.lastQuadratic = false;
    }

    // collect_transform_matrices: this shape's transform attribute, its
    // operations' matrices put in front of those already collected.
    static void collectTransforms(std::vector<Mat3>& matrices, const Shape& s) {
        std::string arg = s.transform;
        auto replaceAll = [&](const std::string& from, const std::string& to) {
            std::size_t at = 0;
            while ((at = arg.find(from, at)) != std::string::npos) {
                arg.replace(at, from.size(), to);
                at += to.size();
            }
        };
        replaceAll("matrix", "m");
        replaceAll("translate", "t");
        replaceAll("scale", "s");
        replaceAll("rotate", "r");
        replaceAll("skewX", "x");
        replaceAll("skewY", "y");
        const std::string commands = "mtsrxy";

        struct Op {
            char op;
            std::vector<double> args;
        };
        std::vector<Op> ops;
        for (const std::string& v : tokenize(arg, " ,()", commands)) {
            if (v.length() == 1 && commands.find(v) != std::string::npos) {
                ops.push_back({v[0], {}});
            } else if (!ops.empty()) {
                ops.back().args.push_back(parseDouble(v));
            }
        }
        std::vector<Mat3> own;
        for (const Op& t : ops) {
            std::vector<Mat3> m;
            const std::vector<double>& a = t.args;
            switch (t.op) {
                case 'm':
                    if (a.size() == 6) m.push_back(mat(a[0], a[2], a[4], a[1], a[3], a[5], 0, 0, 1));
                    break;
                case 't':
                    if (a.size() >= 1 && a.size() <= 2)
                        m.push_back(mat(1, 0, a[0], 0, 1, a.size() > 1 ? a[1] : 0, 0, 0, 1));
                    break;
                case 's':
                    if (a.size() >= 1 && a.size() <= 2) {
                        const double sy = a.size() > 1 ? a[1] : a[0];
                        m.push_back(mat(a[0], 0, 0, 0, sy, 0, 0, 0, 1));
                    }
                    break;
                case 'r':
                    if (a.size() == 1 || a.size() == 3) {
                        const bool center = a.size() == 3;
                        const double cx = center ? a[1] : 0, cy = center ? a[2] : 0;
                        if (center) m.push_back(mat(1, 0, -cx, 0, 1, -cy, 0, 0, 1));
                        const double sn = sinDegrees(a[0]), cs = cosDegrees(a[0]);
                        m.push_back(mat(cs, -sn, 0, sn, cs, 0, 0, 0, 1));
                        if (center) m.push_back(mat(1, 0, cx, 0, 1, cy, 0, 0, 1));
                    }
                    break;
                case 'x':
                    if (a.size() == 1) m.push_back(mat(1, tanDegrees(a[0]), 0, 0, 1, 0, 0, 0, 1));
                    break;
                case 'y':
                    if (a.size() == 1) m.push_back(mat(1, 0, 0, tanDegrees(a[0]), 1, 0, 0, 0, 1));
                    break;
            }
            own.insert(own.end(), m.rbegin(), m.rend());
        }
        matrices.insert(matrices.begin(), own.begin(), own.end());
    }

    std::size_t& pointCount_;
};

// ---------------------------------------------------------------------------
// Reading the document (libsvg.cc's processNode)

struct XmlErrors {
    std::string first;
};

void xmlError(void* arg, xmlErrorPtr error) {
    auto* errors = static_cast<XmlErrors*>(arg);
    if (errors->first.empty() && error && error->message) {
        errors->first = error->message;
        while (!errors->first.empty() && (errors->first.back() == '\n' || errors->first.back() == ' ')) {
            errors->first.pop_back();
        }
        if (error->line > 0) errors->first += " (line " + std::to_string(error->line) + ")";
    }
}

// External entities (<!ENTITY x SYSTEM "...">) are not loaded: a hostile file
// could name a FIFO or a device and hang the import. libxml2's loader is
// process-wide; strata uses libxml2 for nothing else.
xmlParserInputPtr refuseExternalEntity(const char*, const char*, xmlParserCtxtPtr) { return nullptr; }

void initLibxml() {
    static const bool done = [] {
        xmlInitParser();
        xmlSetExternalEntityLoader(refuseExternalEntity);
        return true;
    }();
    (void)done;
}

Shape* createShape(std::string_view name, std::vector<std::unique_ptr<Shape>>& shapes) {
    static const std::pair<const char*, Kind> kNames[] = {
        {"circle", Kind::Circle}, {"ellipse", Kind::Ellipse}, {"line", Kind::Line},       {"text", Kind::Text},
        {"tspan", Kind::Tspan},   {"data", Kind::Data},       {"polygon", Kind::Polygon}, {"polyline", Kind::Polyline},
        {"rect", Kind::Rect},     {"svg", Kind::Page},        {"path", Kind::Path},       {"g", Kind::Group}};
    for (const auto& [n, kind] : kNames) {
        if (name == n) {
            shapes.push_back(std::make_unique<Shape>());
            shapes.back()->kind = kind;
            return shapes.back().get();
        }
    }
    return nullptr;
}

std::vector<std::unique_ptr<Shape>> readShapes(const scene::FlatImport& import, const std::string& text) {
    std::vector<std::unique_ptr<Shape>> shapes;
    std::vector<Shape*> stack;
    bool inDefs = false;
    std::size_t pointCount = 0;
    ShapeBuilder builder(pointCount);
    XmlErrors errors;

    if (text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw Error("import: " + quotedPath(import.path) + " is too large");
    }
    initLibxml();
    xmlTextReaderPtr reader = xmlReaderForMemory(text.data(), static_cast<int>(text.size()), import.path.c_str(),
                                                 nullptr, XML_PARSE_NOENT | XML_PARSE_NONET);
    if (!reader) throw Error("import: cannot read " + quotedPath(import.path) + " as XML");
    struct Closer {
        xmlTextReaderPtr r;
        ~Closer() { xmlFreeTextReader(r); }
    } closer{reader};
    xmlTextReaderSetStructuredErrorHandler(reader, xmlError, &errors);

    auto endElement = [&](std::string_view name) {
        if (name == "defs") inDefs = false;
        if (inDefs) return;
        if (name == "g" || name == "tspan" || name == "text") {
            if (!stack.empty()) stack.pop_back();
        }
    };

    int ret = xmlTextReaderRead(reader);
    while (ret == 1) {
        const xmlChar* rawName = xmlTextReaderConstName(reader);
        const std::string name = rawName ? reinterpret_cast<const char*>(rawName) : "--";
        const int type = xmlTextReaderNodeType(reader);
        if (type == XML_READER_TYPE_ELEMENT) {
            const bool isEmpty = xmlTextReaderIsEmptyElement(reader) == 1;
            if (name == "defs") inDefs = true;
            if (!inDefs) {
                if (Shape* s = createShape(name, shapes)) {
                    Attributes attrs;
                    const int count = xmlTextReaderAttributeCount(reader);
                    for (int i = 0; i < count; ++i) {
                        if (xmlTextReaderMoveToAttributeNo(reader, i) != 1) continue;
                        const xmlChar* an = xmlTextReaderConstName(reader);
                        const xmlChar* av = xmlTextReaderConstValue(reader);
                        attrs[an ? reinterpret_cast<const char*>(an) : ""] =
                            av ? reinterpret_cast<const char*>(av) : "";
                    }
                    xmlTextReaderMoveToElement(reader);
                    // The parent is known before the outlines are made (strokes need no parent).
                    if (!stack.empty()) s->parent = stack.back();
                    builder.setAttrs(*s, attrs);
                    if (s->container()) stack.push_back(s);
                    builder.applyTransform(*s);
                }
            }
            if (isEmpty) endElement(name);
        } else if (type == XML_READER_TYPE_END_ELEMENT) {
            endElement(name);
        } else if (type == XML_READER_TYPE_TEXT) {
            // A "data" shape: no outlines; it only keeps its place in the list.
            auto s = std::make_unique<Shape>();
            s->kind = Kind::Data;
            if (!stack.empty()) s->parent = stack.back();
            shapes.push_back(std::move(s));
        }
        ret = xmlTextReaderRead(reader);
    }
    if (ret != 0) {
        throw Error("import: cannot parse " + quotedPath(import.path) +
                    (errors.first.empty() ? "" : ": " + errors.first));
    }
    return shapes;
}

// ---------------------------------------------------------------------------
// import_svg.cc

double toMm(const Length& length, double viewbox, bool viewboxValid, double dpi) {
    switch (length.unit) {
        case Unit::None: return kInchToMm * length.number / dpi;
        case Unit::Px: return kInchToMm * length.number / 96.0;
        case Unit::Pt: return kInchToMm * length.number / 72.0;
        case Unit::Pc: return kInchToMm * length.number / 6.0;
        case Unit::In: return kInchToMm * length.number;
        case Unit::Cm: return 10 * length.number;
        case Unit::Mm: return length.number;
        case Unit::Undefined: return viewboxValid ? kInchToMm * viewbox / dpi : 0.0;
        default: return viewboxValid ? viewbox : 0.0;
    }
}

double calcAlignment(Align alignment, double pageMm, double scale, double viewbox) {
    switch (alignment) {
        case Align::Mid: return pageMm / 2.0 - scale * viewbox / 2.0;
        case Align::Max: return pageMm - scale * viewbox;
        default: return 0.0;
    }
}

ClipperLib::cInt toGrid(double v) {
    const double scaled = v * kClipperScale;
    if (!(std::fabs(scaled) < kClipperRange)) throw Error("import: an SVG coordinate is not finite or too large");
    return static_cast<ClipperLib::cInt>(scaled);
}

}  // namespace

// Long, and kept in one piece: it is OpenSCAD's SVG import in its order
// (document units and viewBox to a scale, each shape's outline cleaned, the
// union, the placement), each step a few lines that read the steps before.
Outlines importSvg(const scene::FlatImport& import, const std::string& text) {
    const std::vector<std::unique_ptr<Shape>> shapes = readShapes(import, text);
    // ImportModule replaces a dpi below 0.001 by the default, 72.
    const double dpi = import.dpi < 0.001 ? 72.0 : import.dpi;

    double widthMm = 0.0, heightMm = 0.0;
    double minX = std::numeric_limits<double>::max(), minY = std::numeric_limits<double>::max();
    double maxX = std::numeric_limits<double>::lowest(), maxY = std::numeric_limits<double>::lowest();
    double scaleX = 1.0, scaleY = 1.0, alignX = 0.0, alignY = 0.0, viewboxX = 0.0, viewboxY = 0.0;
    for (const auto& shape : shapes) {
        if (shape->kind == Kind::Page) {
            const Viewbox& vb = shape->viewbox;
            widthMm = toMm(shape->width, vb.width, vb.valid, dpi);
            heightMm = toMm(shape->height, vb.height, vb.valid, dpi);
            if (vb.valid) {
                viewboxX = vb.x;
                viewboxY = vb.y;
                scaleX = widthMm / vb.width;
                scaleY = heightMm / vb.height;
                if (shape->alignment.x != Align::None) {
                    // meet: fit into the viewport (the smaller factor); slice: fill it.
                    const double scaling = shape->alignment.meet ? (scaleX < scaleY ? scaleX : scaleY)
                                                                 : (scaleX > scaleY ? scaleX : scaleY);
                    scaleX = scaleY = scaling;
                    alignX = calcAlignment(shape->alignment.x, widthMm, scaleX, vb.width);
                    alignY = calcAlignment(shape->alignment.y, heightMm, scaleY, vb.height);
                }
            }
        }
        for (const PathPoints& p : shape->paths) {
            for (const Point& v : p) {
                const double x = scaleX * v[0], y = scaleY * v[1];
                minX = std::min(minX, x);
                minY = std::min(minY, y);
                maxX = std::max(maxX, x);
                maxY = std::max(maxY, y);
            }
        }
    }
    const double cx = import.center ? (minX + maxX) / 2 : -alignX;
    const double cy = import.center ? (minY + maxY) / 2 : heightMm - alignY;

    // Each shape cleaned with an even-odd union, then all of them unioned.
    std::vector<ClipperLib::Paths> operands;
    operands.reserve(shapes.size());
    for (const auto& shape : shapes) {
        ClipperLib::Paths paths;
        for (const PathPoints& p : shape->paths) {
            ClipperLib::Path path;
            for (const Point& v : p) {
                const double x = scaleX * (-viewboxX + v[0]) - cx;
                const double y = scaleY * (-viewboxY - v[1]) + cy;
                path.emplace_back(toGrid(x), toGrid(y));
            }
            if (!ClipperLib::Orientation(path)) std::reverse(path.begin(), path.end());
            paths.push_back(std::move(path));
        }
        ClipperLib::PolyTree tree;
        ClipperLib::Clipper clipper;
        clipper.AddPaths(paths, ClipperLib::ptSubject, true);
        clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftEvenOdd);
        ClipperLib::PolyTreeToPaths(tree, paths);
        operands.push_back(std::move(paths));
    }
    ClipperLib::Clipper clipper;
    bool first = true;
    for (const ClipperLib::Paths& paths : operands) {
        clipper.AddPaths(paths, first ? ClipperLib::ptSubject : ClipperLib::ptClip, true);
        first = false;
    }
    ClipperLib::PolyTree sum;
    clipper.Execute(ClipperLib::ctUnion, sum, ClipperLib::pftNonZero, ClipperLib::pftNonZero);

    Outlines result;
    for (const ClipperLib::PolyNode* node = sum.GetFirst(); node != nullptr; node = node->GetNext()) {
        ClipperLib::Path cleaned;
        ClipperLib::CleanPolygon(node->Contour, cleaned);
        if (cleaned.size() < 3) continue;
        Outline outline;
        outline.positive = ClipperLib::Orientation(node->Contour);
        outline.points.reserve(cleaned.size());
        for (const ClipperLib::IntPoint& p : cleaned) {
            outline.points.push_back(
                {1.0 * static_cast<double>(p.X) / kClipperScale, 1.0 * static_cast<double>(p.Y) / kClipperScale});
        }
        result.outlines.push_back(std::move(outline));
    }
    result.sanitized = true;
    if (result.outlines.empty()) throw Error("import: " + quotedPath(import.path) + " has no outlines");
    return result;
}

}  // namespace strata::flat::detail
