#pragma once
// The viewer's console: what strata and OpenSCAD said about the files shown,
// newest last: loads and their time, OpenSCAD's ECHO, WARNING and ERROR
// lines for a .scad, strata's warnings, errors, exports. Kept to the last
// few thousand lines.

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

namespace strata::view {

struct ConsoleLine {
    enum class Kind { Info, Echo, Warning, Error };
    Kind kind;
    std::string text;
};

class Console {
public:
    void add(ConsoleLine::Kind kind, std::string text);
    // A line OpenSCAD printed, its kind read from its prefix (ECHO:, WARNING:, ERROR:).
    void addOpenscad(const std::string& line);
    const std::deque<ConsoleLine>& lines() const { return lines_; }
    // Every line as text, one per line, as `print console` writes it.
    std::string text() const;

    static constexpr std::size_t kMaxLines = 5000;

private:
    std::deque<ConsoleLine> lines_;
};

}  // namespace strata::view
