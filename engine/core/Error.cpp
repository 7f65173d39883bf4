#include "strata/core/Error.h"

#include <cctype>

namespace strata {

std::string printable(std::string_view text) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte != 0x7f) {
            out += c;
            continue;
        }
        out += "\\x";
        out += kHex[byte >> 4];
        out += kHex[byte & 15];
    }
    return out;
}

std::string SourceLocation::str() const {
    std::string s = file.empty() ? std::string("<input>") : printable(file);
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (column > 0) s += ':' + std::to_string(column);
    }
    return s;
}

Error::Error(const SourceLocation& where, const std::string& message)
    : std::runtime_error(where.str() + ": " + printable(message)) {}

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
