#pragma once
// A small streaming JSON writer, enough for strata's --stats and --json
// figures (no parsing, no DOM). Keys keep the order they are written in.
//
//   io::JsonWriter json;
//   json.beginObject();
//   json.key("operands").value(12);
//   json.key("layers").beginArray().value(1).value(3).endArray();
//   json.endObject();
//   std::cout << json.str() << '\n';
//
// Non-finite doubles become null (JSON has no inf or NaN).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata::io {

class JsonWriter {
public:
    // indent > 0 puts each member on its own line, indented that many spaces per level.
    explicit JsonWriter(int indent = 0) : indent_(indent) {}

    JsonWriter& beginObject();
    JsonWriter& endObject();
    // oneLine keeps the array on one line even when indenting (long lists of numbers).
    JsonWriter& beginArray(bool oneLine = false);
    JsonWriter& endArray();
    JsonWriter& key(std::string_view name);

    JsonWriter& value(std::string_view s);
    JsonWriter& value(const char* s) { return value(std::string_view(s)); }
    JsonWriter& value(const std::string& s) { return value(std::string_view(s)); }
    JsonWriter& value(bool b);
    JsonWriter& value(double d);
    JsonWriter& value(float f) { return value(static_cast<double>(f)); }
    JsonWriter& value(long long i);
    JsonWriter& value(unsigned long long u);
    JsonWriter& value(int i) { return value(static_cast<long long>(i)); }
    JsonWriter& value(unsigned u) { return value(static_cast<unsigned long long>(u)); }
    JsonWriter& value(long i) { return value(static_cast<long long>(i)); }
    JsonWriter& value(unsigned long u) { return value(static_cast<unsigned long long>(u)); }
    JsonWriter& null();

    const std::string& str() const noexcept { return out_; }

    // "text" with JSON escapes, quotes included.
    static std::string quote(std::string_view text);

private:
    void beforeValue();
    void newline();
    struct Level {
        bool object = false;
        bool empty = true;
        bool oneLine = false;
    };
    bool oneLine() const noexcept;
    std::string out_;
    std::vector<Level> stack_;
    bool afterKey_ = false;
    int indent_ = 0;
};

}  // namespace strata::io
