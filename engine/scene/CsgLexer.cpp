#include "CsgLexer.h"

#include <charconv>
#include <utility>

namespace strata::scene {

namespace {
constexpr std::size_t kChunk = std::size_t(1) << 20;  // 1 MiB read-ahead
constexpr std::size_t kMaxToken = std::size_t(1) << 20;  // longest identifier/string/number

bool isIdentStart(int c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$'; }
bool isDigit(int c) { return c >= '0' && c <= '9'; }
bool isIdentChar(int c) { return isIdentStart(c) || isDigit(c); }
}  // namespace

CsgLexer::CsgLexer(std::istream& in, std::string file, Locate locate)
    : in_(in), buffer_(kChunk), file_(std::move(file)), locate_(std::move(locate)) {
    where_.file = file_;
}

bool CsgLexer::refill() {
    if (!in_) return false;
    in_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    end_ = static_cast<std::size_t>(in_.gcount());
    pos_ = 0;
    return end_ > 0;
}

int CsgLexer::peek() {
    if (pos_ == end_ && !refill()) return -1;
    return static_cast<unsigned char>(buffer_[pos_]);
}

int CsgLexer::get() {
    int c = peek();
    if (c < 0) return c;
    ++pos_;
    ++consumed_;
    if (c == '\n') {
        ++line_;
        column_ = 1;
    } else {
        ++column_;
    }
    return c;
}

void CsgLexer::fail(const std::string& message) const { failAt(where_, message); }

void CsgLexer::failAt(const SourceLocation& where, const std::string& message) const {
    throw Error(where, message);
}

void CsgLexer::skipSpaceAndComments() {
    for (;;) {
        int c = peek();
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
            get();
        } else if (c == '/') {
            SourceLocation start{file_, line_, column_};
            get();
            int d = peek();
            if (d == '/') {
                while ((c = peek()) >= 0 && c != '\n') get();
            } else if (d == '*') {
                get();
                int prev = 0;
                for (;;) {
                    c = get();
                    if (c < 0) failAt(start, "unterminated comment");
                    if (prev == '*' && c == '/') break;
                    prev = c;
                }
            } else {
                failAt(start, "unexpected character '/'");
            }
        } else {
            return;
        }
    }
}

Token CsgLexer::next() {
    skipSpaceAndComments();
    where_.line = line_;
    where_.column = column_;
    if (locate_) {
        if (line_ != locatedLine_) {
            locatedLine_ = line_;
            located_ = locate_(line_);
        }
        if (located_) {
            where_ = *located_;
        } else if (where_.file != file_) {
            where_.file = file_;
        }
    }
    int c = peek();
    if (c < 0) return token_ = Token::End;
    if (isDigit(c) || c == '.') {
        lexNumber();
        return token_ = Token::Number;
    }
    if (isIdentStart(c)) {
        lexIdentifier();
        return token_ = Token::Identifier;
    }
    if (c == '"') {
        lexString();
        return token_ = Token::String;
    }
    switch (c) {
        case '(': case ')': case '[': case ']': case '{': case '}': case ',': case ';':
        case '=': case '%': case '#': case '!': case '*': case '-': case '+':
            punct_ = static_cast<char>(get());
            return token_ = Token::Punct;
        default: break;
    }
    if (c < 0x20 || c >= 0x7f) fail("unexpected byte 0x" + [c] {
        const char* hex = "0123456789abcdef";
        return std::string{hex[(c >> 4) & 15], hex[c & 15]};
    }());
    fail(std::string("unexpected character '") + static_cast<char>(c) + "'");
}

void CsgLexer::lexNumber() {
    char digits[128];
    std::size_t n = 0;
    auto take = [&] {
        int c = get();
        if (n >= sizeof(digits) - 1) fail("number too long");
        digits[n++] = static_cast<char>(c);
    };
    while (isDigit(peek())) take();
    if (peek() == '.') {
        take();
        while (isDigit(peek())) take();
    }
    if (peek() == 'e' || peek() == 'E') {
        take();
        if (peek() == '+' || peek() == '-') take();
        if (!isDigit(peek())) fail("malformed number: exponent has no digits");
        while (isDigit(peek())) take();
    }
    if (isIdentChar(peek()) || peek() == '.') fail("malformed number");
    const char* first = digits;
    // from_chars takes no leading '.', so give it "0" in front.
    std::string withZero;
    if (digits[0] == '.') {
        withZero.reserve(n + 1);
        withZero.push_back('0');
        withZero.append(digits, n);
        first = withZero.data();
        n = withZero.size();
    }
    auto [ptr, ec] = std::from_chars(first, first + n, number_);
    if (ec == std::errc::result_out_of_range) {
        fail("number out of range");
    }
    if (ec != std::errc() || ptr != first + n) fail("malformed number");
}

void CsgLexer::lexIdentifier() {
    text_.clear();
    while (isIdentChar(peek())) {
        if (text_.size() >= kMaxToken) fail("identifier too long");
        text_.push_back(static_cast<char>(get()));
    }
}

void CsgLexer::lexString() {
    text_.clear();
    get();  // opening quote
    for (;;) {
        int c = get();
        if (c < 0 || c == '\n') fail("unterminated string");
        if (c == '"') return;
        if (c == '\\') {
            int e = get();
            switch (e) {
                case 'n': c = '\n'; break;
                case 't': c = '\t'; break;
                case 'r': c = '\r'; break;
                case '"': c = '"'; break;
                case '\\': c = '\\'; break;
                case -1: fail("unterminated string");
                default: c = e; break;  // keep unknown escapes' character
            }
        }
        if (text_.size() >= kMaxToken) fail("string too long");
        text_.push_back(static_cast<char>(c));
    }
}

}  // namespace strata::scene
