#include "PlyCheck.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "strata/core/Error.h"

namespace strata::mesh::detail {
namespace {

// A word of the file as a message shows it: quoted, at most 32 bytes, bytes
// that are not printable ASCII written as \xNN.
std::string shownWord(std::string_view word) {
    std::string out = "'";
    for (std::size_t i = 0; i < word.size() && i < 32; ++i) {
        const auto c = static_cast<unsigned char>(word[i]);
        if (c >= 32 && c < 127) {
            out += static_cast<char>(c);
        } else {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
            out += escaped;
        }
    }
    if (word.size() > 32) out += "...";
    return out + "'";
}

struct Type {
    std::size_t size = 0;  // bytes in a binary body; 0: not a PLY type
    bool integer = false;
    bool isSigned = false;
};

Type typeNamed(const std::string& name) {
    if (name == "char" || name == "int8") return {1, true, true};
    if (name == "uchar" || name == "uint8") return {1, true, false};
    if (name == "short" || name == "int16") return {2, true, true};
    if (name == "ushort" || name == "uint16") return {2, true, false};
    if (name == "int" || name == "int32") return {4, true, true};
    if (name == "uint" || name == "uint32") return {4, true, false};
    if (name == "float" || name == "float32") return {4, false, true};
    if (name == "double" || name == "float64") return {8, false, true};
    return {};
}

struct Property {
    std::string name;
    Type type;           // a list's item type
    bool list = false;
    Type countType;      // a list's length type
    std::string typeWord;       // as the header writes it (a list's: the length type)
    std::size_t line = 0;       // of the header
};

struct Element {
    std::string name;
    unsigned long long count = 0;
    std::size_t line = 0;
    std::vector<Property> properties;
};

enum class Format { Ascii, LittleEndian, BigEndian };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t bytes = 0;   // up to and with end_header's line
    std::size_t lines = 0;   // the header's lines
};

class Checker {
public:
    Checker(const std::string& path, std::uintmax_t size) : path_(path), size_(size) {}

    [[noreturn]] void fail(std::size_t line, const std::string& why) const {
        throw Error(path_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": cannot read mesh: " + why);
    }

    Header header(const std::string& head) const;
    void counts(const Header& h) const;
    void asciiBody(const Header& h, const std::string& text) const;
    void binaryBody(const Header& h) const;

private:
    void formatLine(const std::vector<std::string>& words, std::size_t line, bool& formatSeen, Header& h) const;
    void elementLine(const std::vector<std::string>& words, std::size_t line, Header& h) const;
    void propertyLine(const std::vector<std::string>& words, std::size_t line, Header& h) const;
    void requiredElements(const Header& h) const;

    std::string tooMany(unsigned long long count, const Element& e) const {
        return "header declares " + std::to_string(count) + " " + shownWord(e.name) +
               " elements, more than the file can hold";
    }
    static std::string notANumber(std::string_view word, bool integer) {
        return std::string(integer ? "a value that is not a whole number: " : "a value that is not a number: ") +
               shownWord(word);
    }
    std::string endsEarly(const Element& e) const {
        return "the file ends before the " + std::to_string(e.count) + " " + shownWord(e.name) +
               " elements its header declares";
    }

    const std::string& path_;
    std::uintmax_t size_;
};

// A format line: the body's encoding, and the version 1.0.
void Checker::formatLine(const std::vector<std::string>& words, std::size_t line, bool& formatSeen, Header& h) const {
    if (formatSeen) fail(line, "a second format line");
    if (words.size() != 3) fail(line, "expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian)");
    if (words[1] == "ascii") h.format = Format::Ascii;
    else if (words[1] == "binary_little_endian") h.format = Format::LittleEndian;
    else if (words[1] == "binary_big_endian") h.format = Format::BigEndian;
    else fail(line, "unknown format " + shownWord(words[1]) + " (expected ascii, binary_little_endian or binary_big_endian)");
    if (words[2] != "1.0" && words[2] != "1") fail(line, "unknown format version " + shownWord(words[2]) + " (expected 1.0)");
    formatSeen = true;
}

// An element line: a new element with its name and count.
void Checker::elementLine(const std::vector<std::string>& words, std::size_t line, Header& h) const {
    if (words.size() != 3) fail(line, "expected 'element NAME COUNT'");
    Element e;
    e.name = words[1];
    e.line = line;
    const std::string& count = words[2];
    const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
    if (ec == std::errc::result_out_of_range) {
        fail(line, "header declares " + shownWord(count) + " " + shownWord(e.name) + " elements, more than the file can hold");
    }
    if (ec != std::errc() || ptr != count.data() + count.size()) {
        fail(line, "the count of element " + shownWord(e.name) + " is not a whole number: " + shownWord(count));
    }
    h.elements.push_back(std::move(e));
}

// A property line: a scalar or list property of the last element.
void Checker::propertyLine(const std::vector<std::string>& words, std::size_t line, Header& h) const {
    if (h.elements.empty()) fail(line, "a property before any element");
    Property p;
    p.line = line;
    if (words.size() >= 2 && words[1] == "list") {
        if (words.size() != 5) fail(line, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        p.list = true;
        p.typeWord = words[2];
        p.countType = typeNamed(words[2]);
        if (!p.countType.integer) fail(line, "a list's length type must be an integer type, not " + shownWord(words[2]));
        p.type = typeNamed(words[3]);
        if (p.type.size == 0) fail(line, "unknown property type " + shownWord(words[3]));
        p.name = words[4];
    } else {
        if (words.size() != 3) fail(line, "expected 'property TYPE NAME'");
        p.type = typeNamed(words[1]);
        if (p.type.size == 0) fail(line, "unknown property type " + shownWord(words[1]));
        p.typeWord = words[1];
        p.name = words[2];
    }
    h.elements.back().properties.push_back(std::move(p));
}

// The header's lines one by one, up to end_header, then the elements a mesh needs.
Header Checker::header(const std::string& head) const {
    if (head.rfind("ply\n", 0) != 0 && head.rfind("ply\r\n", 0) != 0) fail(0, "not a PLY file (its first line is not 'ply')");
    Header h;
    bool formatSeen = false, ended = false;
    std::size_t pos = 0, line = 0;
    while (pos < head.size()) {
        std::size_t end = head.find('\n', pos);
        if (end == std::string::npos) {
            if (head.size() >= kPlyHeaderLimit) break;
            end = head.size();  // the last line of the file
        }
        if (end >= kPlyHeaderLimit) break;
        std::istringstream in(head.substr(pos, end - pos));
        pos = end + 1;
        ++line;
        std::vector<std::string> words;
        for (std::string w; in >> w;) words.push_back(w);
        if (line == 1 || words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
        const std::string& keyword = words[0];
        if (keyword == "format") {
            formatLine(words, line, formatSeen, h);
            continue;
        }
        if (!formatSeen) fail(line, "expected the format line, got " + shownWord(keyword));
        if (keyword == "end_header") {
            if (words.size() != 1) fail(line, "expected 'end_header' alone on its line");
            ended = true;
            break;
        }
        if (keyword == "element") {
            elementLine(words, line, h);
        } else if (keyword == "property") {
            propertyLine(words, line, h);
        } else {
            fail(line, "unknown header line starting with " + shownWord(keyword));
        }
    }
    if (!ended) {
        fail(0, head.size() >= kPlyHeaderLimit ? "no end_header in the first " + std::to_string(kPlyHeaderLimit) + " bytes"
                                               : "the header has no end_header line");
    }
    h.bytes = std::min(pos, head.size());
    h.lines = line;
    requiredElements(h);
    return h;
}

// The vertex and face elements with the properties OpenMesh reads, in that order.
void Checker::requiredElements(const Header& h) const {
    auto named = [&h](const char* name) {
        return std::find_if(h.elements.begin(), h.elements.end(), [name](const Element& e) { return e.name == name; });
    };
    auto has = [](const Element& e, const char* name, bool list) {
        return std::any_of(e.properties.begin(), e.properties.end(),
                           [&](const Property& p) { return p.name == name && p.list == list; });
    };
    const auto vertex = named("vertex");
    if (vertex == h.elements.end()) fail(0, "the header declares no vertex element");
    for (const char* axis : {"x", "y", "z"}) {
        if (!has(*vertex, axis, false)) fail(vertex->line, std::string("the vertex element has no property ") + axis);
    }
    const auto face = named("face");
    if (face == h.elements.end()) fail(0, "the header declares no face element");
    if (!has(*face, "vertex_indices", true) && !has(*face, "vertex_index", true)) {
        fail(face->line, "the face element has no list property vertex_indices");
    }
    if (face < vertex) fail(face->line, "the face element comes before the vertex element");
    // OpenMesh's binary reader takes coordinates only as floats (it prints a
    // line per value and reads 0 otherwise) and a face's corner count only
    // as an uchar or an int (others end the read).
    if (h.format != Format::Ascii) {
        for (const Property& p : vertex->properties) {
            if (!p.list && (p.name == "x" || p.name == "y" || p.name == "z") && p.type.integer) {
                fail(p.line, "binary coordinates of type " + shownWord(p.typeWord) + " are not read (float or double are)");
            }
        }
        for (const Property& p : face->properties) {
            const bool uchar = p.countType.size == 1 && !p.countType.isSigned, int32 = p.countType.size == 4 && p.countType.isSigned;
            if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index") && !uchar && !int32) {
                fail(p.line, "a binary face's corner count of type " + shownWord(p.typeWord) + " is not read (uchar or int is)");
            }
        }
    }
}

// What the body must hold at least: in text, every value one character and
// one separator (the last separator may be missing); in binary, every scalar
// and every list length its type's size. Each element at least one byte, so
// that no count is larger than the file.
void Checker::counts(const Header& h) const {
    const unsigned long long body = size_ > h.bytes ? size_ - h.bytes : 0;
    unsigned long long need = 0;
    for (const Element& e : h.elements) {
        unsigned long long each = 0;
        for (const Property& p : e.properties) {
            each += h.format == Format::Ascii ? 2 : (p.list ? p.countType.size : p.type.size);
        }
        each = std::max<unsigned long long>(each, 1);
        if (e.count > (body + 1) / each || need + e.count * each > body + 1) fail(e.line, tooMany(e.count, e));
        need += e.count * each;
    }
}

// Whether a word of a text body is one number of a property's type, whole:
// OpenMesh's reader takes numbers with >>, which stops inside a word such as
// '0+0' and reads the rest as the next value, so that the file it reads is
// no longer the one checked (a list length further on could then be any
// number at all). A sign is allowed, as >> allows it.
bool isNumberWord(std::string_view word, bool integer) {
    if (!word.empty() && word.front() == '+') word.remove_prefix(1);  // from_chars takes '-' only
    const char* end = word.data() + word.size();
    if (integer) {
        long long value = 0;
        const auto [ptr, ec] = std::from_chars(word.data(), end, value);
        return ec == std::errc() && ptr == end;
    }
    double value = 0;
    const auto [ptr, ec] = std::from_chars(word.data(), end, value);
    return ec == std::errc() && ptr == end;
}

// Walks the text after the header word by word: every element is there, and
// every list length is a whole number its values can follow.
void Checker::asciiBody(const Header& h, const std::string& text) const {
    std::size_t at = h.bytes;
    std::size_t line = h.lines + 1;
    auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; };
    // The next word, or an empty view at the end of the text.
    auto next = [&]() -> std::string_view {
        while (at < text.size() && isSpace(text[at])) {
            if (text[at] == '\n') ++line;
            ++at;
        }
        const std::size_t begin = at;
        while (at < text.size() && !isSpace(text[at])) ++at;
        return std::string_view(text).substr(begin, at - begin);
    };
    for (const Element& e : h.elements) {
        for (unsigned long long i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) {
                const std::string_view word = next();
                if (word.empty()) fail(0, endsEarly(e));
                if (!p.list) {
                    if (!isNumberWord(word, p.type.integer)) fail(line, notANumber(word, p.type.integer));
                    continue;
                }
                unsigned long long length = 0;
                const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), length);
                if (ec == std::errc::result_out_of_range) fail(line, "a list of " + shownWord(word) + " values, more than the file holds");
                if (ec != std::errc() || ptr != word.data() + word.size()) {
                    fail(line, "a list length that is not a whole number: " + shownWord(word));
                }
                // Each value takes a character and a separator.
                if (length > (text.size() - at) / 2 + 1) {
                    fail(line, "a list of " + std::to_string(length) + " values, more than the file holds");
                }
                for (unsigned long long k = 0; k < length; ++k) {
                    const std::string_view value = next();
                    if (value.empty()) fail(0, endsEarly(e));
                    if (!isNumberWord(value, p.type.integer)) fail(line, notANumber(value, p.type.integer));
                }
            }
        }
    }
}

// Walks a binary body: scalars are skipped by their sizes, list lengths are
// read and their values skipped, never past the end of the file.
void Checker::binaryBody(const Header& h) const {
    std::ifstream in(path_, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(h.bytes));
    std::uintmax_t at = h.bytes;
    const bool little = h.format == Format::LittleEndian;
    for (const Element& e : h.elements) {
        for (unsigned long long i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) {
                if (!p.list) {
                    if (size_ - at < p.type.size) fail(0, endsEarly(e));
                    in.ignore(static_cast<std::streamsize>(p.type.size));
                    at += p.type.size;
                    continue;
                }
                std::array<unsigned char, 4> bytes{};
                if (size_ - at < p.countType.size) fail(0, endsEarly(e));
                in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(p.countType.size));
                if (!in) fail(0, endsEarly(e));
                at += p.countType.size;
                const std::size_t n = p.countType.size;
                std::uint32_t raw = 0;
                for (std::size_t k = 0; k < n; ++k) raw |= std::uint32_t(bytes[little ? k : n - 1 - k]) << (8 * k);
                long long length = raw;
                if (p.countType.isSigned && (raw >> (8 * n - 1)) != 0) length -= (1ll << (8 * n));
                if (length < 0) fail(0, "a negative list length (" + std::to_string(length) + ") in element " + shownWord(e.name));
                const auto bytesOfValues = static_cast<std::uintmax_t>(length) * p.type.size;
                if (bytesOfValues > size_ - at) {
                    fail(0, "a list of " + std::to_string(length) + " values in element " + shownWord(e.name) +
                                ", more than the file holds");
                }
                in.ignore(static_cast<std::streamsize>(bytesOfValues));
                at += bytesOfValues;
            }
        }
    }
}

}  // namespace

std::string readHead(const std::string& path, std::size_t limit) {
    std::ifstream in(path, std::ios::binary);
    std::string text(limit, '\0');
    in.read(text.data(), static_cast<std::streamsize>(limit));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

void checkPly(const std::string& path, std::uintmax_t size) {
    const Checker check(path, size);
    const Header h = check.header(readHead(path, kPlyHeaderLimit));
    check.counts(h);
    if (h.format == Format::Ascii) {
        std::ifstream in(path, std::ios::binary);
        check.asciiBody(h, std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
    } else {
        check.binaryBody(h);
    }
}

}  // namespace strata::mesh::detail
