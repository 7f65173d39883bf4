#include "strata/io/Json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace strata::io {

std::string JsonWriter::quote(std::string_view text) {
    std::string out = "\"";
    for (char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            default:
                if (c < 0x20) {
                    char buffer[8];
                    std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
                    out += buffer;
                } else {
                    out += ch;  // UTF-8 passes through as it is
                }
        }
    }
    out += '"';
    return out;
}

bool JsonWriter::oneLine() const noexcept {
    for (const Level& level : stack_)
        if (level.oneLine) return true;
    return indent_ <= 0;
}

void JsonWriter::newline() {
    if (oneLine()) return;
    out_ += '\n';
    out_.append(stack_.size() * static_cast<std::size_t>(indent_), ' ');
}

void JsonWriter::beforeValue() {
    if (afterKey_) {
        afterKey_ = false;
        return;
    }
    if (!stack_.empty()) {
        if (!stack_.back().empty) out_ += oneLine() ? ", " : ",";
        stack_.back().empty = false;
        newline();
    }
}

JsonWriter& JsonWriter::key(std::string_view name) {
    if (!stack_.empty()) {
        if (!stack_.back().empty) out_ += oneLine() ? ", " : ",";
        stack_.back().empty = false;
        newline();
    }
    out_ += quote(name);
    out_ += ": ";
    afterKey_ = true;
    return *this;
}

JsonWriter& JsonWriter::beginObject() {
    beforeValue();
    out_ += '{';
    stack_.push_back({true, true});
    return *this;
}

JsonWriter& JsonWriter::endObject() {
    const bool empty = stack_.back().empty;
    const bool flat = oneLine();
    stack_.pop_back();
    if (!empty && !flat) newline();
    out_ += '}';
    return *this;
}

JsonWriter& JsonWriter::beginArray(bool oneLine) {
    beforeValue();
    out_ += '[';
    stack_.push_back({false, true, oneLine});
    return *this;
}

JsonWriter& JsonWriter::endArray() {
    const bool empty = stack_.back().empty;
    const bool flat = oneLine();
    stack_.pop_back();
    if (!empty && !flat) newline();
    out_ += ']';
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view s) {
    beforeValue();
    out_ += quote(s);
    return *this;
}

JsonWriter& JsonWriter::value(bool b) {
    beforeValue();
    out_ += b ? "true" : "false";
    return *this;
}

JsonWriter& JsonWriter::value(double d) {
    beforeValue();
    if (!std::isfinite(d)) {
        out_ += "null";
        return *this;
    }
    char buffer[32];
    // %.17g round-trips any double; most figures are short and print short.
    std::snprintf(buffer, sizeof buffer, "%.6g", d);
    if (std::strtod(buffer, nullptr) != d) std::snprintf(buffer, sizeof buffer, "%.17g", d);
    out_ += buffer;
    return *this;
}

JsonWriter& JsonWriter::value(long long i) {
    beforeValue();
    out_ += std::to_string(i);
    return *this;
}

JsonWriter& JsonWriter::value(unsigned long long u) {
    beforeValue();
    out_ += std::to_string(u);
    return *this;
}

JsonWriter& JsonWriter::null() {
    beforeValue();
    out_ += "null";
    return *this;
}

}  // namespace strata::io
