#include "strata/core/Error.h"

#include <cctype>

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
    std::string message = e.what();
    if (where.file.empty() || message.rfind(where.str() + ":", 0) == 0) throw e;
    // An error raised where no position was known takes this one instead.
    const std::string nowhere = SourceLocation{}.str() + ": ";
    if (message.rfind(nowhere, 0) == 0) throw Error(where, message.substr(nowhere.size()));
    // Already named by a node inside this one (a line of the same file):
    // shapes nested a thousand deep would otherwise put a thousand
    // positions in front of the message.
    const std::string file = where.file + ":";
    if (message.size() > file.size() && message.rfind(file, 0) == 0 && std::isdigit(static_cast<unsigned char>(message[file.size()])))
        throw e;
    throw Error(where, message);
}

}  // namespace strata
