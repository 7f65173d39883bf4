#include "strata/scene/ScadTrace.h"

#include <string_view>
#include <utility>

namespace strata::scene {
namespace {

bool identStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$'; }
bool identChar(char c) { return identStart(c) || (c >= '0' && c <= '9'); }

// Words followed by '(' that are not calls of a module.
bool isKeyword(std::string_view word) {
    return word == "if" || word == "for" || word == "let" || word == "each" || word == "assert" || word == "echo" ||
           word == "function" || word == "module" || word == "else";
}

// A string literal's text as OpenSCAD reads it (the common escapes).
std::string unescape(std::string_view raw) {
    std::string out;
    out.reserve(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] != '\\' || i + 1 == raw.size()) {
            out += raw[i];
            continue;
        }
        const char e = raw[++i];
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
    }
    return out;
}

// The end of the string literal whose opening quote is at `open`.
std::size_t stringEnd(std::string_view text, std::size_t open) {
    std::size_t i = open + 1;
    while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
    return std::min(i, text.size());
}

}  // namespace

ScadTrace::ScadTrace(std::string csg, const std::vector<Source>& sources) : csg_(std::move(csg)) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < csg_.size(); ++i)
        if (csg_[i] == '\n') lineStarts_.push_back(i + 1);

    for (const Source& source : sources) {
        const std::string_view text = source.text;
        int line = 1, column = 1;
        std::size_t i = 0;
        auto advanceTo = [&](std::size_t end) {
            for (; i < end && i < text.size(); ++i) {
                if (text[i] == '\n') {
                    ++line;
                    column = 1;
                } else {
                    ++column;
                }
            }
        };
        // The word just before, if the last token was one: a '(' after it is a call.
        std::string word;
        SourceLocation wordAt;
        bool wordIsName = false;      // a word, and not the name of a definition
        bool afterDefinition = false;  // the word before was `module` or `function`
        std::vector<std::pair<std::vector<Call>*, std::size_t>> open;  // the '(' now open: whose call, or none
        while (i < text.size()) {
            const char c = text[i];
            if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
                const std::size_t end = text.find('\n', i);
                advanceTo(end == std::string_view::npos ? text.size() : end);
            } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
                const std::size_t end = text.find("*/", i + 2);
                advanceTo(end == std::string_view::npos ? text.size() : end + 2);
            } else if (c == '"') {
                const std::size_t end = stringEnd(text, i);
                if (!open.empty() && open.back().first)
                    (*open.back().first)[open.back().second].strings.push_back(unescape(text.substr(i + 1, end - i - 1)));
                advanceTo(end + 1);
                wordIsName = false;
            } else if (identStart(c)) {
                std::size_t end = i;
                while (end < text.size() && identChar(text[end])) ++end;
                const bool definition = afterDefinition;
                word.assign(text.substr(i, end - i));
                afterDefinition = word == "module" || word == "function";
                wordIsName = !definition && !isKeyword(word);
                wordAt = SourceLocation{source.name, line, column};
                advanceTo(end);
            } else if (c == '(') {
                if (wordIsName) {
                    std::vector<Call>& calls = calls_[word];
                    calls.push_back(Call{wordAt, {}});
                    open.emplace_back(&calls, calls.size() - 1);
                } else {
                    open.emplace_back(nullptr, 0);
                }
                wordIsName = afterDefinition = false;
                advanceTo(i + 1);
            } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
                advanceTo(i + 1);  // a call's name and its '(' may stand apart
            } else {
                if (c == ')' && !open.empty()) open.pop_back();
                // A number's letters (1e5) are no word; a '#' or '%' before a call is no matter.
                std::size_t end = i + 1;
                if (c >= '0' && c <= '9')
                    while (end < text.size() && (identChar(text[end]) || text[end] == '.')) ++end;
                wordIsName = afterDefinition = false;
                advanceTo(end);
            }
        }
    }
}

std::optional<SourceLocation> ScadTrace::locate(int line) const {
    if (line < 1 || static_cast<std::size_t>(line) > lineStarts_.size()) return std::nullopt;
    const std::size_t start = lineStarts_[static_cast<std::size_t>(line) - 1];
    const std::size_t newline = csg_.find('\n', start);
    const std::string_view text =
        std::string_view(csg_).substr(start, (newline == std::string::npos ? csg_.size() : newline) - start);
    std::size_t i = 0;
    while (i < text.size() && (text[i] == '\t' || text[i] == ' ' || text[i] == '%' || text[i] == '#' || text[i] == '!' ||
                               text[i] == '*'))
        ++i;
    std::size_t end = i;
    while (end < text.size() && identChar(text[end])) ++end;
    if (end == i || end == text.size() || text[end] != '(') return std::nullopt;
    const auto found = calls_.find(std::string(text.substr(i, end - i)));
    if (found == calls_.end()) return std::nullopt;
    const std::vector<Call>& calls = found->second;

    // import and surface name a file, text its text: the call whose own
    // string arguments hold it, where only one does.
    const std::string_view name = text.substr(i, end - i);
    const std::string_view key = name == "import" || name == "surface" ? "file = \"" : name == "text" ? "text = \"" : "";
    if (!key.empty()) {
        const std::size_t at = text.find(key, end);
        if (at != std::string_view::npos) {
            const std::size_t open = at + key.size() - 1;
            const std::string value = unescape(text.substr(open + 1, stringEnd(text, open) - open - 1));
            const Call* only = nullptr;
            int holding = 0;
            for (const Call& call : calls) {
                for (const std::string& s : call.strings) {
                    if (s != value) continue;
                    only = &call;
                    ++holding;
                    break;
                }
            }
            if (holding == 1) return only->where;
            if (holding > 1) return std::nullopt;
        }
    }
    if (calls.size() == 1) return calls.front().where;
    return std::nullopt;
}

int ScadTrace::tracedLines() const {
    int traced = 0;
    for (std::size_t line = 1; line <= lineStarts_.size(); ++line)
        if (locate(static_cast<int>(line))) ++traced;
    return traced;
}

}  // namespace strata::scene
