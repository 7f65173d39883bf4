#include "Console.h"

#include <utility>

namespace strata::view {

void Console::add(ConsoleLine::Kind kind, std::string text) {
    lines_.push_back(ConsoleLine{kind, std::move(text)});
    while (lines_.size() > kMaxLines) lines_.pop_front();
}

void Console::addOpenscad(const std::string& line) {
    ConsoleLine::Kind kind = ConsoleLine::Kind::Info;
    if (line.starts_with("ECHO:")) kind = ConsoleLine::Kind::Echo;
    else if (line.starts_with("WARNING:") || line.starts_with("DEPRECATED:")) kind = ConsoleLine::Kind::Warning;
    else if (line.starts_with("ERROR:")) kind = ConsoleLine::Kind::Error;
    add(kind, line);
}

std::string Console::text() const {
    std::string out;
    for (const ConsoleLine& l : lines_) out += l.text + '\n';
    return out;
}

}  // namespace strata::view
