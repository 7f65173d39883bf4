#pragma once
// strata::Error and SourceLocation: how strata reports a mistake to the outside world.
//
// Every error that reaches a user is one line that starts with where it happened:
//   scenes/gear.csg:12:5: unknown primitive 'cyl'
// Input mistakes name the input's file, line and column; GPU failures name the
// source position in strata. main() catches strata::Error once and prints what().

#include <stdexcept>
#include <string>
#include <string_view>

namespace strata {

// A position in a text input. line and column count from 1; 0 means unknown.
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;

    // "file:line:col", "file:line" or "file", depending on what is known;
    // the file name printable().
    std::string str() const;
};

// `text` with each control byte (below 0x20, and 0x7f) written as \xNN, so
// that a file name or a file's bytes quoted in a message can neither break
// its line nor send a terminal an escape sequence. Other bytes, UTF-8
// included, pass as they are; text without control bytes is returned as it
// is (escaping twice changes nothing).
std::string printable(std::string_view text);

// Its message is printable(): one line, whatever file names it quotes.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(printable(message)) {}
    // "where: message"
    Error(const SourceLocation& where, const std::string& message);
};

// Rethrows `e` naming `where` in front of its message, unless it already
// starts with `where` or `where` names no file (a nested node's error is
// named once, by the innermost node that knows its position).
[[noreturn]] void rethrowAt(const SourceLocation& where, const Error& e);

// A non-fatal diagnostic, already formatted as "file:line:col: warning: ...".
struct Warning {
    std::string message;
};

}  // namespace strata
