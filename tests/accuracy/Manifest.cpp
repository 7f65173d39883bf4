#include "Manifest.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <ostream>

#include "strata/core/Error.h"

namespace strata::accuracy {

namespace {

struct Field {
    std::string text;
    int column = 0;  // from 1
};

std::vector<Field> splitFields(const std::string& line) {
    std::vector<Field> fields;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        if (i >= line.size() || line[i] == '#') break;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        fields.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
    return fields;
}

double parseNumber(const std::string& text, const SourceLocation& where) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
        throw Error(where, "not a finite number: '" + text + "'");
    }
    return value;
}

std::vector<double> parseNumbers(const std::string& text, char separator, const SourceLocation& where) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        out.push_back(parseNumber(text.substr(start, end - start), where));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return out;
}

std::string stem(const std::string& file) {
    const std::size_t slash = file.find_last_of('/');
    std::string s = slash == std::string::npos ? file : file.substr(slash + 1);
    const std::size_t dot = s.find_last_of('.');
    if (dot != std::string::npos) s.resize(dot);
    for (char& c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return s;
}

}  // namespace

void PrintTo(const Shot& shot, std::ostream* out) { *out << shot.name << " (" << shot.scene << ")"; }

bool Shot::has(const std::string& flag) const { return std::find(flags.begin(), flags.end(), flag) != flags.end(); }

std::vector<Shot> loadManifest(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open the accuracy manifest");
    std::vector<Shot> shots;
    std::map<std::string, int> perScene;
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        const std::vector<Field> fields = splitFields(line);
        if (fields.empty()) continue;
        auto at = [&](const Field& f) { return SourceLocation{path, lineNumber, f.column}; };
        if (fields.size() < 5) {
            throw Error(at(fields.back()), "expected 'scene family p|o WxH ex,ey,ez,cx,cy,cz [options]', got " +
                                               std::to_string(fields.size()) + " fields");
        }
        Shot shot;
        shot.line = lineNumber;
        shot.scene = fields[0].text;
        shot.family = fields[1].text;
        if (fields[2].text == "p") {
            shot.camera.projection = camera::Projection::Perspective;
        } else if (fields[2].text == "o") {
            shot.camera.projection = camera::Projection::Orthographic;
        } else {
            throw Error(at(fields[2]), "projection must be 'p' or 'o', not '" + fields[2].text + "'");
        }
        const std::vector<double> size = parseNumbers(fields[3].text, 'x', at(fields[3]));
        if (size.size() != 2 || size[0] < 1 || size[1] < 1 || size[0] > 16384 || size[1] > 16384 ||
            size[0] != std::floor(size[0]) || size[1] != std::floor(size[1])) {
            throw Error(at(fields[3]), "image size must be WxH in whole pixels, not '" + fields[3].text + "'");
        }
        shot.camera.width = static_cast<int>(size[0]);
        shot.camera.height = static_cast<int>(size[1]);
        const std::vector<double> cam = parseNumbers(fields[4].text, ',', at(fields[4]));
        if (cam.size() != 6) {
            throw Error(at(fields[4]), "camera must be 6 numbers (eye, center), got " + std::to_string(cam.size()));
        }
        shot.camera.eye = {cam[0], cam[1], cam[2]};
        shot.camera.center = {cam[3], cam[4], cam[5]};
        if (shot.camera.eye == shot.camera.center) throw Error(at(fields[4]), "eye and center must differ");
        for (std::size_t k = 5; k < fields.size(); ++k) {
            const std::string& f = fields[k].text;
            if (f.rfind("fov=", 0) == 0) {
                const double fov = parseNumber(f.substr(4), at(fields[k]));
                if (!(fov > 0.0 && fov < 180.0)) throw Error(at(fields[k]), "fov must be in (0, 180) degrees");
                shot.camera.fovDegrees = fov;
            } else {
                shot.flags.push_back(f);
            }
        }
        shot.index = perScene[shot.scene]++;
        shot.name = stem(shot.scene) + "_" + fields[2].text + std::to_string(shot.index);
        shots.push_back(std::move(shot));
    }
    return shots;
}

}  // namespace strata::accuracy
