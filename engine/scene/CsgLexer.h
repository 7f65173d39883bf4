#pragma once
// Tokens of OpenSCAD's CSG export, read from a stream in fixed-size chunks so
// the text is never held whole (real exports reach hundreds of MB).

#include <cstddef>
#include <functional>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "strata/core/Error.h"

namespace strata::scene {

enum class Token {
    End,
    Identifier,  // also $fn, true, false, undef, inf, nan
    Number,
    String,
    Punct,       // one of ( ) [ ] { } , ; = % # ! * -  +
};

class CsgLexer {
public:
    // `locate`, when given, says where messages about a line of the input
    // should point instead (the .scad a CSG export was made of), or nothing
    // to keep the input's own line and column.
    using Locate = std::function<std::optional<SourceLocation>(int line)>;
    CsgLexer(std::istream& in, std::string file, Locate locate = {});

    // Reads the next token; text()/number()/punct() describe it.
    Token next();

    Token token() const { return token_; }
    const std::string& text() const { return text_; }  // identifier or string contents
    double number() const { return number_; }
    char punct() const { return punct_; }
    // Where the current token starts, and where the lexer is now.
    const SourceLocation& where() const { return where_; }
    int column() const { return column_; }  // column of the next unread character

    [[noreturn]] void fail(const std::string& message) const;
    [[noreturn]] void failAt(const SourceLocation& where, const std::string& message) const;

    std::size_t bytesRead() const { return consumed_; }

private:
    int peek();
    int get();
    bool refill();
    void skipSpaceAndComments();
    void lexNumber();
    void lexIdentifier();
    void lexString();

    std::istream& in_;
    std::vector<char> buffer_;
    std::size_t pos_ = 0;
    std::size_t end_ = 0;
    std::size_t consumed_ = 0;
    int line_ = 1;
    int column_ = 1;

    Token token_ = Token::End;
    std::string text_;
    double number_ = 0.0;
    char punct_ = 0;
    SourceLocation where_;
    std::string file_;
    Locate locate_;
    int locatedLine_ = 0;
    std::optional<SourceLocation> located_;
};

}  // namespace strata::scene
