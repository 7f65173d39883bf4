#include "Script.h"

#include "strata/render/Limits.h"
#include "strata/io/ExportFormats.h"
#include "strata/core/InputFile.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "Orbit.h"

namespace strata::view {
namespace {

struct Word {
    std::string text;
    int column = 0;
};

struct Syntax {
    std::string_view name;
    CommandKind kind;
    int minWords, maxWords;  // -1: any number (the rest of the line)
};

constexpr std::array<Syntax, 35> kSyntax{{
    {"open", CommandKind::Open, 1, 1},
    {"size", CommandKind::Size, 2, 2},
    {"layers", CommandKind::Layers, 1, 1},
    {"camera", CommandKind::Camera, 1, 1},
    {"projection", CommandKind::Projection, 1, 1},
    {"fov", CommandKind::Fov, 1, 1},
    {"orbit", CommandKind::Orbit, 2, 2},
    {"pan", CommandKind::Pan, 2, 2},
    {"middle-drag", CommandKind::MiddleDrag, 2, 2},
    {"zoom-drag", CommandKind::ZoomDrag, 1, 1},
    {"zoom", CommandKind::Zoom, 1, 3},
    {"preset", CommandKind::Preset, 1, 1},
    {"view-all", CommandKind::ViewAll, 0, 0},
    {"double-click", CommandKind::DoubleClick, 2, 2},
    {"toggle", CommandKind::Toggle, 1, 1},
    {"highlight", CommandKind::Highlight, 1, 1},
    {"colorscheme", CommandKind::ColorScheme, 1, -1},
    {"light", CommandKind::Light, 1, 1},
    {"debug", CommandKind::Debug, 1, 1},
    {"panel", CommandKind::Panel, 1, 1},
    {"show", CommandKind::Show, 2, 2},
    {"screenshot", CommandKind::Screenshot, 1, 1},
    {"screenshot-window", CommandKind::ScreenshotWindow, 1, 1},
    {"export", CommandKind::Export, 1, 1},
    {"export-exact", CommandKind::Export, 1, 1},
    {"export-sampled", CommandKind::ExportSampled, 1, 1},
    {"save-csg", CommandKind::SaveCsg, 1, 1},
    {"copy", CommandKind::Copy, 2, 2},
    {"remove", CommandKind::Remove, 1, 1},
    {"wait-reload", CommandKind::WaitReload, 0, 0},
    {"wait-loading", CommandKind::WaitLoading, 0, 0},
    {"print", CommandKind::Print, 1, 1},
    {"key", CommandKind::Key, 1, 1},
    {"sleep", CommandKind::Sleep, 1, 1},
    {"quit", CommandKind::Quit, 0, 0},
}};

std::string commandList() {
    std::string list;
    for (const Syntax& s : kSyntax) list += (list.empty() ? "" : ", ") + std::string(s.name);
    return list;
}

// Splits one line into words; throws on an unterminated quote.
std::vector<Word> splitWords(const std::string& line, const std::string& name, int lineNumber) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
            ++i;
            continue;
        }
        if (line[i] == '#') break;
        Word word;
        word.column = static_cast<int>(i) + 1;
        if (line[i] == '"') {
            const std::size_t close = line.find('"', i + 1);
            if (close == std::string::npos)
                throw Error(SourceLocation{name, lineNumber, word.column}, "unterminated quoted word");
            word.text = line.substr(i + 1, close - i - 1);
            i = close + 1;
        } else {
            while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') word.text += line[i++];
        }
        words.push_back(std::move(word));
    }
    return words;
}

bool readNumber(const std::string& text, double& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    out = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(out);
}

bool readWhole(const std::string& text, double& out) {
    return readNumber(text, out) && out == std::floor(out) && text.find_first_of(".eE") == std::string::npos;
}

// Checks the arguments of one command and fills Command::numbers; messages
// start with the command's name, so they say whose argument is wrong.
void checkArguments(Command& c, std::string_view name) {
    auto fail = [&](const std::string& message, int k) { return c.error(std::string(name) + ": " + message, k); };
    auto number = [&](int k, const char* what) {
        double v = 0;
        if (!readNumber(c.words[k], v)) throw fail(std::string("expected ") + what + ", got '" + c.words[k] + "'", k);
        c.numbers.push_back(v);
    };
    auto whole = [&](int k, double lo, double hi, const std::string& what) {
        double v = 0;
        if (!readWhole(c.words[k], v) || v < lo || v > hi)
            throw fail(std::string("expected ") + what + ", got '" + c.words[k] + "'", k);
        c.numbers.push_back(v);
    };
    auto oneOf = [&](std::initializer_list<std::string_view> valid) {
        std::string list;
        for (std::string_view v : valid) {
            if (c.words[0] == v) return;
            list += (list.empty() ? "" : ", ") + std::string(v);
        }
        throw fail("expected one of " + list + ", got '" + c.words[0] + "'", 0);
    };

    switch (c.kind) {
    case CommandKind::Size:
        whole(0, 1, render::kMaxImageSide, "a width from 1 to " + std::to_string(render::kMaxImageSide));
        whole(1, 1, render::kMaxImageSide, "a height from 1 to " + std::to_string(render::kMaxImageSide));
        break;
    case CommandKind::Layers:
        if (c.words[0] != "auto") whole(0, 1, render::kMaxLayers, "'auto' or a whole number from 1 to " + std::to_string(render::kMaxLayers));
        break;
    case CommandKind::Camera: {
        std::stringstream parts(c.words[0]);
        std::string part;
        while (std::getline(parts, part, ',')) {
            double v = 0;
            if (!readNumber(part, v)) throw fail("'" + part + "' is not a finite number", 0);
            c.numbers.push_back(v);
        }
        if (c.numbers.size() != 6 && c.numbers.size() != 7)
            throw fail("expected 6 numbers (eye, center) or 7 (translate, rotate, distance), got " +
                              std::to_string(c.numbers.size()),
                          0);
        break;
    }
    case CommandKind::Projection: oneOf({"p", "o"}); break;
    case CommandKind::Fov:
        number(0, "degrees between 0 and 180");
        if (!(c.numbers[0] > 0.0 && c.numbers[0] < 180.0))
            throw fail("expected degrees between 0 and 180, got '" + c.words[0] + "'", 0);
        break;
    case CommandKind::Orbit:
    case CommandKind::Pan:
    case CommandKind::MiddleDrag:
        number(0, "pixels");
        number(1, "pixels");
        break;
    case CommandKind::ZoomDrag: number(0, "pixels"); break;
    case CommandKind::Zoom:
        number(0, "wheel notches");
        if (c.words.size() == 2) throw fail("expected the cursor's X and Y after the notches, or neither", 1);
        if (c.words.size() == 3) {
            number(1, "pixels");
            number(2, "pixels");
        }
        break;
    case CommandKind::Preset:
        try {
            presetFromName(c.words[0]);
        } catch (const Error& e) {
            throw fail(e.what(), 0);
        }
        break;
    case CommandKind::DoubleClick:
        whole(0, 0, render::kMaxImageSide, "a pixel column");
        whole(1, 0, render::kMaxImageSide, "a pixel row");
        break;
    case CommandKind::Toggle:
    case CommandKind::Highlight:
        // NODE: a node number as the panel shows it, or line:N for the
        // outermost node written on line N; resolved against the open tree.
        if (c.words[0].starts_with("line:")) {
            double v = 0;
            if (!readWhole(c.words[0].substr(5), v) || v < 1 || v > 1e9)
                throw fail("expected line:N with N from 1 to 1000000000", 0);
        } else {
            whole(0, 0, 1e9, "a node number or line:N");
        }
        break;
    case CommandKind::Debug: oneOf({"shaded", "depth", "normal", "peel", "forms"}); break;
    case CommandKind::Panel: {
        const std::string& w = c.words[0];
        if (w == "on" || w == "off" || w == "open" || w == "export") break;
        double width = 0;
        if (!readWhole(w, width) || width < 220 || width > render::kMaxImageSide)
            throw fail("expected on, off, open, export or a width from 220 to " + std::to_string(render::kMaxImageSide) + ", got '" + w + "'", 0);
        c.numbers.push_back(width);
        break;
    }
    case CommandKind::Light: oneOf({"strata", "openscad"}); break;
    case CommandKind::Key: {
        std::string_view name = c.words[0];
        if (name.starts_with("ctrl+")) name.remove_prefix(5);
        const bool letterOrDigit = name.size() == 1 && ((name[0] >= 'a' && name[0] <= 'z') || (name[0] >= '0' && name[0] <= '9'));
        if (!letterOrDigit && name != "escape" && name != "f5" && name != "f12")
            throw fail("expected [ctrl+] and a lower-case letter, a digit, escape, f5 or f12, got '" + c.words[0] + "'", 0);
        break;
    }
    case CommandKind::Show:
        oneOf({"axes", "scale", "edges", "outline"});
        if (c.words[1] != "on" && c.words[1] != "off") throw fail("expected on or off, got '" + c.words[1] + "'", 1);
        break;
    case CommandKind::Print: oneOf({"camera", "console", "error", "load", "panel", "recent", "stats", "title", "tree"}); break;
    case CommandKind::Sleep: whole(0, 0, 600000, "milliseconds from 0 to 600000"); break;
    case CommandKind::Screenshot:
    case CommandKind::ScreenshotWindow:
        if (!c.words[0].ends_with(".png")) throw fail("expected a .png file name, got '" + c.words[0] + "'", 0);
        break;
    case CommandKind::Export:
        if (const io::ExportFormat* format = io::exportFormatOf(c.words[0]); format && format->kind == io::ExportKind::Drawing)
            break;  // a 2D model's drawing
        [[fallthrough]];
    case CommandKind::ExportSampled:
        if (const io::ExportFormat* format = io::exportFormatOf(c.words[0]); !format || format->kind != io::ExportKind::Mesh) {
            const std::string drawings =
                c.kind == CommandKind::Export ? " (or, for a 2D model, " + io::extensionList(io::ExportKind::Drawing) + ")" : "";
            throw fail("expected a " + io::extensionList(io::ExportKind::Mesh) + drawings + " file name, got '" + c.words[0] + "'", 0);
        }
        break;
    case CommandKind::SaveCsg:
        if (!c.words[0].ends_with(".csg")) throw fail("expected a .csg file name, got '" + c.words[0] + "'", 0);
        break;
    default: break;
    }
}

}  // namespace

Error Command::error(const std::string& message, int index) const {
    const SourceLocation& at = index >= 0 && index < static_cast<int>(wordsAt.size()) ? wordsAt[index] : where;
    return Error(at, message);
}

std::vector<Command> parseScript(const std::string& text, const std::string& name) {
    std::vector<Command> commands;
    std::istringstream in(text);
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::vector<Word> words = splitWords(line, name, lineNumber);
        if (words.empty()) continue;
        const SourceLocation at{name, lineNumber, words[0].column};
        const Syntax* syntax = nullptr;
        for (const Syntax& s : kSyntax)
            if (words[0].text == s.name) syntax = &s;
        if (syntax == nullptr)
            throw Error(at, "unknown command '" + words[0].text + "' (valid: " + commandList() + ")");
        Command c{syntax->kind, at, {}, {}, {}};
        if (syntax->maxWords < 0 && words.size() > 2) {
            // colorscheme Tomorrow Night: the rest of the line is one name.
            std::string rest;
            for (std::size_t k = 1; k < words.size(); ++k) rest += (k > 1 ? " " : "") + words[k].text;
            words.resize(2);
            words[1].text = rest;
        }
        const int given = static_cast<int>(words.size()) - 1;
        if (given < syntax->minWords || (syntax->maxWords >= 0 && given > syntax->maxWords)) {
            const std::string expected = syntax->minWords == syntax->maxWords
                                             ? std::to_string(syntax->minWords)
                                             : "at least " + std::to_string(syntax->minWords);
            const SourceLocation extra = given > syntax->minWords
                                             ? SourceLocation{name, lineNumber, words[syntax->maxWords + 1].column}
                                             : at;
            throw Error(extra, std::string(syntax->name) + ": expected " + expected + " argument" +
                                   (expected == "1" ? "" : "s") + ", got " + std::to_string(given));
        }
        for (std::size_t k = 1; k < words.size(); ++k) {
            c.words.push_back(words[k].text);
            c.wordsAt.push_back(SourceLocation{name, lineNumber, words[k].column});
        }
        checkArguments(c, syntax->name);
        commands.push_back(std::move(c));
    }
    return commands;
}

std::vector<Command> parseScriptFile(const std::string& path) {
    // A regular file of a bounded size: a FIFO would block the viewer before
    // its window opens, and a device (/dev/zero) would feed it for good.
    constexpr std::uintmax_t kMostBytes = std::uintmax_t(16) << 20;
    if (const std::string why = unreadableReason(path); !why.empty()) {
        throw Error(SourceLocation{path, 0, 0}, "cannot read script: " + why);
    }
    std::error_code ec;
    if (const std::uintmax_t size = std::filesystem::file_size(path, ec); !ec && size > kMostBytes) {
        throw Error(SourceLocation{path, 0, 0}, "cannot read script: larger than 16 MiB");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(SourceLocation{path, 0, 0}, "cannot open script");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScript(text.str(), path);
}

std::string resolveScriptPath(const std::string& scriptPath, const std::string& path) {
    const std::filesystem::path p(path);
    if (p.is_absolute()) return path;
    return (std::filesystem::path(scriptPath).parent_path() / p).lexically_normal().string();
}

}  // namespace strata::view
