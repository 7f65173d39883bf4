#include "strata/core/Error.h"

namespace strata {

std::string SourceLocation::str() const {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (column > 0) s += ':' + std::to_string(column);
    }
    return s;
}

Error::Error(const SourceLocation& where, const std::string& message)
    : std::runtime_error(where.str() + ": " + message) {}

void rethrowAt(const SourceLocation& where, const Error& e) {
    if (where.file.empty() || std::string(e.what()).rfind(where.str() + ":", 0) == 0) throw e;
    throw Error(where, e.what());
}

}  // namespace strata
