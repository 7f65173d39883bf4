#pragma once
// Numbers in text as OpenSCAD 2021.01 reads them with boost::lexical_cast
// (Boost 1.74): the DXF reader and surface()'s .dat reader share this.

#include <string_view>

namespace strata {

// lexical_cast<double>(token): "inf", "infinity", "nan", "nan(...)" with an
// optional sign (any case), else what std::istream >> double reads in the C
// locale, the whole token, not ending in e, E, + or -. Overflow fails.
bool lexicalCastDouble(std::string_view token, double& out);

// ASCII case-insensitive equality with a lower-case word.
bool equalsLowerCase(std::string_view text, std::string_view lower);

}  // namespace strata
