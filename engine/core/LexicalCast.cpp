#include "strata/core/LexicalCast.h"

#include <clocale>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <locale.h>
#include <string>

namespace strata {

bool equalsLowerCase(std::string_view a, std::string_view lower) {
    if (a.size() != lower.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const char c = (a[i] >= 'A' && a[i] <= 'Z') ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
        if (c != lower[i]) return false;
    }
    return true;
}

bool lexicalCastDouble(std::string_view s, double& out) {
    if (s.empty()) return false;
    {
        std::string_view t = s;
        const bool minus = t.front() == '-';
        if (minus || t.front() == '+') t.remove_prefix(1);
        if (t.size() >= 3 && equalsLowerCase(t.substr(0, 3), "nan")) {
            std::string_view rest = t.substr(3);
            if (rest.empty() || (rest.size() >= 2 && rest.front() == '(' && rest.back() == ')')) {
                out = minus ? -std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::quiet_NaN();
                return true;
            }
            return false;
        }
        if (equalsLowerCase(t, "inf") || equalsLowerCase(t, "infinity")) {
            out = minus ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
            return true;
        }
    }
    // [+-]? digits* (. digits*)? ([eE] [+-]? digits+)?, at least one mantissa digit.
    std::size_t i = 0;
    if (s[i] == '+' || s[i] == '-') ++i;
    std::size_t digits = 0;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
    if (i < s.size() && s[i] == '.') {
        ++i;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
    }
    if (digits == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        std::size_t expDigits = 0;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++expDigits;
        if (expDigits == 0) return false;
    }
    if (i != s.size()) return false;
    static const locale_t cLocale = newlocale(LC_ALL_MASK, "C", locale_t(0));
    const std::string text(s);
    char* end = nullptr;
    const double v = strtod_l(text.c_str(), &end, cLocale);
    if (end != text.c_str() + text.size()) return false;
    if (std::isinf(v)) return false;  // libstdc++ reports overflow as a failure
    out = v;
    return true;
}

}  // namespace strata
