// DXF import as OpenSCAD 2021.01 does it (src/dxfdata.cc, DxfData's reading
// constructor, fixup_path_direction and toPolygon2d), rule for rule:
//
// - The file is read as pairs of lines (group code, value), both trimmed. A
//   group code that is not an integer ends the reading; a value that is not a
//   number where one is expected is skipped.
// - Codes 10/11 (x) and 20/21 (y) collect the current entity's points, with the
//   origin subtracted and the scale applied outside BLOCKS (also for the
//   ELLIPSE's major-axis vector, as 2021.01 does); 40 is a radius (scaled too,
//   also when it is an ELLIPSE's axis ratio), 41/42 and 50/51 angles or an
//   INSERT's scales and rotation, 70 flags, 8 the layer, 2 a name.
// - An entity is processed when the next group 0 arrives: LINE, LWPOLYLINE
//   (straight segments; bulges are ignored; flag 1 closes it), CIRCLE and ARC
//   ($fn/$fa/$fs fragments of the scaled radius; an arc gets
//   ceil(n * sweep / 360)), ELLIPSE (fragments of the major radius, scaled by
//   the sweep over 2 pi), INSERT (the block's segments scaled by 41/42, rotated
//   by 50, scaled, moved to the insertion point), BLOCK/ENDBLK and SECTION.
//   POLYLINE, SPLINE and every other entity are ignored (2021.01 warns). If
//   processing throws for missing coordinates, the entity's state is not
//   reset, as in 2021.01.
// - Segment end points are snapped to a 2^-10 grid (an existing point in a
//   neighbouring cell wins), and the segments are joined into paths: first
//   every open path (from the lowest-numbered segment with a free end), then
//   closed ones; open paths are closed. Paths turn clockwise as
//   fixup_path_direction leaves them and come out reversed, as toPolygon2d
//   writes them.
//
// 2021.01 reads DXF with its own reader, not with dxflib, so neither does
// this file: dxflib keeps only the last value of a repeated group code, reads
// POLYLINE and bulges that 2021.01 ignores, and allocates arrays as large as a
// file's vertex counts ask for.

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <locale.h>
#include <stdlib.h>

#include "strata/core/DegreeTrig.h"
#include "FlatImportDetail.h"
#include "strata/core/Error.h"
#include "strata/core/LexicalCast.h"

namespace strata::flat::detail {
namespace {

constexpr double kGridCoarse = 0.0009765625;          // 2^-10, OpenSCAD's GRID_COARSE
constexpr double kGridFine = 0.00000095367431640625;  // 2^-20, GRID_FINE
constexpr double kPi = 3.14159265358979323846;        // M_PI
constexpr std::size_t kMaxSegments = std::size_t(1) << 21;

// ---------------------------------------------------------------------------
// Numbers as boost::lexical_cast reads them (Boost 1.74).

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
    while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
    return s;
}

// lexical_cast<int>: an optional sign and at least one digit, nothing else, in range.
bool castInt(std::string_view s, int& out) {
    if (s.empty()) return false;
    bool minus = false;
    if (s.front() == '-' || s.front() == '+') {
        minus = s.front() == '-';
        s.remove_prefix(1);
    }
    if (s.empty()) return false;
    std::uint64_t v = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + static_cast<std::uint64_t>(c - '0');
        if (v > std::uint64_t(INT_MAX) + 1) return false;
    }
    if (!minus && v > std::uint64_t(INT_MAX)) return false;
    out = minus ? static_cast<int>(-static_cast<std::int64_t>(v)) : static_cast<int>(v);
    return true;
}

struct BadValue {};  // boost::bad_lexical_cast

double number(std::string_view s) {
    double v = 0;
    if (!lexicalCastDouble(s, v)) throw BadValue{};
    return v;
}

// ---------------------------------------------------------------------------
// OpenSCAD's Grid2d<std::vector<int>>(GRID_COARSE), with the cells numbered.

struct KeyHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& k) const {
        return std::hash<std::int64_t>()(k.first) * 0x9E3779B97F4A7C15ull ^ std::hash<std::int64_t>()(k.second);
    }
};

class Grid {
public:
    // Aligns (x, y) to the grid or to an existing point in a neighbouring cell;
    // returns the cell (created when new).
    int align(double& x, double& y) {
        const double qx = x / kGridCoarse, qy = y / kGridCoarse;
        if (!std::isfinite(qx) || !std::isfinite(qy) || std::fabs(qx) > 4.0e18 || std::fabs(qy) > 4.0e18) {
            throw Error("import: a DXF coordinate is not finite or too large");
        }
        std::int64_t ix = static_cast<std::int64_t>(std::round(qx));
        std::int64_t iy = static_cast<std::int64_t>(std::round(qy));
        if (cells_.find({ix, iy}) == cells_.end()) {
            int dist = 10;
            const std::int64_t cx = ix, cy = iy;
            for (std::int64_t jx = cx - 1; jx <= cx + 1; ++jx) {
                for (std::int64_t jy = cy - 1; jy <= cy + 1; ++jy) {
                    if (cells_.find({jx, jy}) == cells_.end()) continue;
                    const int d = std::abs(int(cx - jx)) + std::abs(int(cy - jy));
                    if (d < dist) {
                        dist = d;
                        ix = jx;
                        iy = jy;
                    }
                }
            }
        }
        x = static_cast<double>(ix) * kGridCoarse;
        y = static_cast<double>(iy) * kGridCoarse;
        auto [it, inserted] = cells_.try_emplace({ix, iy}, static_cast<int>(entries.size()));
        if (inserted) entries.emplace_back();
        return it->second;
    }

    std::vector<std::vector<int>> entries;  // per cell: the segment numbers pushed there

private:
    std::unordered_map<std::pair<std::int64_t, std::int64_t>, int, KeyHash> cells_;
};

struct Segment {
    int idx[2];  // into points
};

struct Path {
    std::vector<int> indices;
    bool closed = false;
};

class DxfReader {
public:
    explicit DxfReader(const scene::FlatImport& import) : import_(import) {}

    Outlines read(const std::string& text) {
        parse(text);
        extractPaths();
        fixupPathDirection();
        return toOutlines();
    }

private:
    // ---- parsing -------------------------------------------------------

    void parse(const std::string& text) {
        std::size_t pos = 0;
        bool eof = false;
        auto getline = [&]() -> std::string_view {
            if (eof || pos >= text.size()) {
                eof = true;
                return {};
            }
            const std::size_t nl = text.find('\n', pos);
            std::string_view line;
            if (nl == std::string::npos) {
                line = std::string_view(text).substr(pos);
                pos = text.size();
                eof = true;
            } else {
                line = std::string_view(text).substr(pos, nl - pos);
                pos = nl + 1;
            }
            return line;
        };

        const double scale = this->scale(), xorigin = import_.origin.x, yorigin = import_.origin.y;
        while (!eof) {
            const std::string_view idStr = trim(getline());
            const std::string_view data = trim(getline());
            int id = 0;
            if (!castInt(idStr, id)) break;  // 2021.01: "Illegal ID", reading stops
            try {
                switch (id) {
                    case 0: endEntity(data); break;
                    case 2: iddata_ = data; break;
                    case 8: layer_ = data; break;
                    case 10:
                    case 11: xverts_.push_back(inBlocks_ ? number(data) : (number(data) - xorigin) * scale); break;
                    case 20:
                    case 21: yverts_.push_back(inBlocks_ ? number(data) : (number(data) - yorigin) * scale); break;
                    case 40:
                        radius_ = number(data);
                        if (!inBlocks_) radius_ *= scale;
                        break;
                    case 41: ellipseStart_ = number(data); break;
                    case 50: arcStart_ = number(data); break;
                    case 42: ellipseStop_ = number(data); break;
                    case 51: arcStop_ = number(data); break;
                    case 70: {
                        int v = 0;
                        if (!castInt(data, v)) throw BadValue{};
                        dimtype_ = v;
                        break;
                    }
                    default:
                        // Codes 12-16 and 22-26 are DIMENSION points: read, never used here.
                        if ((id >= 12 && id <= 16) || (id >= 22 && id <= 26)) (void)number(data);
                        break;
                }
            } catch (const BadValue&) {
                // 2021.01: "Illegal value", the pair is skipped.
            } catch (const std::out_of_range&) {
                // 2021.01: "Not enough input values"; the entity's state stays as it was.
            }
        }
    }

    // ImportModule replaces a scale <= 0 by 1.
    double scale() const { return import_.scale <= 0 ? 1.0 : import_.scale; }

    bool layerMatches() const { return import_.layer.empty() || import_.layer == layer_; }

    // OpenSCAD's ADD_LINE.
    void addLine(double p1x, double p1y, double p2x, double p2y) {
        if (!inEntities_ && !inBlocks_) return;
        if (inEntities_ && !layerMatches()) return;
        const int c1 = grid_.align(p1x, p1y);
        const int c2 = grid_.align(p2x, p2y);
        // The segment's number, also for segments of blocks (stale there, as in 2021.01).
        grid_.entries[static_cast<std::size_t>(c1)].push_back(static_cast<int>(lines_.size()));
        grid_.entries[static_cast<std::size_t>(c2)].push_back(static_cast<int>(lines_.size()));
        if (++segmentCount_ > kMaxSegments) {
            throw Error("import: the DXF file has more than " + std::to_string(kMaxSegments) + " segments");
        }
        if (inEntities_) lines_.push_back({{addPoint(p1x, p1y, c1), addPoint(p2x, p2y, c2)}});
        if (inBlocks_ && !currentBlock_.empty()) {
            const int a = addPoint(p1x, p1y, c1), b = addPoint(p2x, p2y, c2);
            blocks_[currentBlock_].push_back({{a, b}});
        }
    }

    int addPoint(double x, double y, int cell) {
        points_.push_back({x, y});
        pointCell_.push_back(cell);
        return static_cast<int>(points_.size() - 1);
    }

    // Calc::get_fragments_from_r, without the $fa/$fs clamp (import() does not clamp).
    int fragments(double r) const {
        const double fn = import_.fragments.fn, fs = import_.fragments.fs, fa = import_.fragments.fa;
        if (r < kGridFine || std::isinf(fn) || std::isnan(fn)) return 3;
        if (fn > 0.0) return toIntX86(fn >= 3 ? fn : 3);
        return toIntX86(std::ceil(std::fmax(std::fmin(360.0 / fa, r * 2 * kPi / fs), 5)));
    }

    static void checkCount(int n) {
        if (n > 0 && static_cast<std::size_t>(n) > kMaxSegments) {
            throw Error("import: a DXF curve needs more than " + std::to_string(kMaxSegments) + " segments");
        }
    }

    // A curve that goes round more than once (the file's angles lie further
    // apart than a turn, which no drawing program writes) would trace the
    // same points again and again: 2021.01 draws every turn, and the
    // outlines that make cost Clipper time that grows with their square.
    static void checkSweep(double turns, const char* entity) {
        if (turns > 1.0 + 1e-9) {
            throw Error(std::string("import: ") + entity + " in the DXF file sweeps " + std::to_string(turns) +
                        " turns; at most one is drawn");
        }
    }

    // The while loops that bring an end angle past the start, bounded.
    static void unwrap(double start, double& stop, double turn) {
        if (start > stop && (start - stop) / turn > 1.0e7) {
            throw Error("import: a DXF arc's angles are too far apart");
        }
        while (start > stop) stop += turn;
    }

    // The entity that ends here becomes segments (or changes the section or
    // block), then the next one, `data`, starts.
    void endEntity(std::string_view data) {
        const double scale = this->scale();
        if (mode_ == "SECTION") {
            inEntities_ = iddata_ == "ENTITIES";
            inBlocks_ = iddata_ == "BLOCKS";
        } else if (mode_ == "LINE") {
            addLine(xverts_.at(0), yverts_.at(0), xverts_.at(1), yverts_.at(1));
        } else if (mode_ == "LWPOLYLINE") {
            addPolyline();
        } else if (mode_ == "CIRCLE") {
            addCircle();
        } else if (mode_ == "ARC") {
            addArc();
        } else if (mode_ == "ELLIPSE") {
            addEllipse();
        } else if (mode_ == "INSERT") {
            addInsert(scale);
        } else if (mode_ == "BLOCK") {
            currentBlock_ = iddata_;
        } else if (mode_ == "ENDBLK") {
            currentBlock_.clear();
        }
        // (DIMENSION entities only matter to dxf_dim(); the rest 2021.01 warns about.)
        startEntity(data);
    }

    // LWPOLYLINE: a segment between each vertex and the next, closed when flag 1 is set.
    void addPolyline() {
        const int numverts = static_cast<int>(std::max(xverts_.size(), yverts_.size()));
        for (int i = 1; i < numverts; ++i) {
            addLine(xverts_.at(std::size_t(i - 1)), yverts_.at(std::size_t(i - 1)),
                    xverts_.at(std::size_t(i % numverts)), yverts_.at(std::size_t(i % numverts)));
        }
        if (dimtype_ & 0x01) {
            addLine(xverts_.at(static_cast<std::size_t>(numverts - 1)),
                    yverts_.at(static_cast<std::size_t>(numverts - 1)), xverts_.at(0), yverts_.at(0));
        }
    }

    // CIRCLE: the radius's fragments, all the way round.
    void addCircle() {
        const int n = fragments(radius_);
        const double cx = xverts_.at(0), cy = yverts_.at(0);
        checkCount(n);
        for (int i = 0; i < n; ++i) {
            const double a1 = (360.0 * i) / n;
            const double a2 = (360.0 * (i + 1)) / n;
            addLine(cosDegrees(a1) * radius_ + cx, sinDegrees(a1) * radius_ + cy, cosDegrees(a2) * radius_ + cx,
                    sinDegrees(a2) * radius_ + cy);
        }
    }

    // ARC: the share of the radius's fragments its sweep covers, from 50 to 51 degrees.
    void addArc() {
        const double cx = xverts_.at(0), cy = yverts_.at(0);
        int n = fragments(radius_);
        unwrap(arcStart_, arcStop_, 360.0);
        const double arcAngle = arcStop_ - arcStart_;
        checkSweep(arcAngle / 360.0, "an ARC");
        n = toIntX86(std::ceil(n * arcAngle / 360));
        checkCount(n);
        for (int i = 0; i < n; ++i) {
            const double a1 = arcStart_ + arcAngle * i / n;
            const double a2 = arcStart_ + arcAngle * (i + 1) / n;
            addLine(cosDegrees(a1) * radius_ + cx, sinDegrees(a1) * radius_ + cy, cosDegrees(a2) * radius_ + cx,
                    sinDegrees(a2) * radius_ + cy);
        }
    }

    // ELLIPSE: centre, major-axis vector and axis ratio, from 41 to 42 radians.
    void addEllipse() {
        unwrap(ellipseStart_, ellipseStop_, 2 * kPi);
        const double cx = xverts_.at(0), cy = yverts_.at(0);
        const double ex = xverts_.at(1), ey = yverts_.at(1);
        const double rMajor = std::sqrt(ex * ex + ey * ey);
        double rotAngle;
        {
            double cosval = ex / rMajor;
            if (cosval > 1.0) cosval = 1.0;
            if (cosval < -1.0) cosval = -1.0;
            rotAngle = std::acos(cosval);
            if (ey < 0.0) rotAngle = 2 * kPi - rotAngle;
        }
        // The axis ratio is in the radius (scaled like one), as in 2021.01.
        const double rMinor = rMajor * radius_;
        const double sweep = ellipseStop_ - ellipseStart_;
        checkSweep(sweep / (2 * kPi), "an ELLIPSE");
        int n = fragments(rMajor);
        n = toIntX86(std::ceil(n * sweep / (2 * kPi)));
        checkCount(n);
        double p1x = 0.0, p1y = 0.0;
        for (int i = 0; i <= n; ++i) {
            const double a = (ellipseStart_ + sweep * i / n);
            const double p2x = std::cos(a) * rMajor, p2y = std::sin(a) * rMinor;
            double rx = std::cos(rotAngle) * p2x - std::sin(rotAngle) * p2y;
            double ry = std::sin(rotAngle) * p2x + std::cos(rotAngle) * p2y;
            rx += cx;
            ry += cy;
            if (i > 0) addLine(p1x, p1y, rx, ry);
            p1x = rx;
            p1y = ry;
        }
    }

    // INSERT: the named block's segments, scaled, rotated, scaled again and moved to the insertion point.
    void addInsert(double scale) {
        // Scales in ellipseStart_/ellipseStop_ (41/42), rotation in arcStart_ (50).
        const std::size_t n = blocks_[iddata_].size();
        for (std::size_t i = 0; i < n; ++i) {
            const double a = arcStart_;
            const Segment s = blocks_[iddata_][i];
            const double lx1 = points_[std::size_t(s.idx[0])][0] * ellipseStart_;
            const double ly1 = points_[std::size_t(s.idx[0])][1] * ellipseStop_;
            const double lx2 = points_[std::size_t(s.idx[1])][0] * ellipseStart_;
            const double ly2 = points_[std::size_t(s.idx[1])][1] * ellipseStop_;
            const double px1 = (cosDegrees(a) * lx1 - sinDegrees(a) * ly1) * scale + xverts_.at(0);
            const double py1 = (sinDegrees(a) * lx1 + cosDegrees(a) * ly1) * scale + yverts_.at(0);
            const double px2 = (cosDegrees(a) * lx2 - sinDegrees(a) * ly2) * scale + xverts_.at(0);
            const double py2 = (sinDegrees(a) * lx2 + cosDegrees(a) * ly2) * scale + yverts_.at(0);
            addLine(px1, py1, px2, py2);
        }
    }

    // Clears the entity's state for the next one, `data`; an INSERT's scales start at 1.
    void startEntity(std::string_view data) {
        mode_ = data;
        layer_.clear();
        iddata_.clear();
        dimtype_ = 0;
        xverts_.clear();
        yverts_.clear();
        radius_ = arcStart_ = arcStop_ = 0;
        ellipseStart_ = ellipseStop_ = 0;
        if (mode_ == "INSERT") ellipseStart_ = ellipseStop_ = 1.0;
    }

    // ---- joining segments into paths ------------------------------------

    bool valid(int k) const { return k >= 0 && static_cast<std::size_t>(k) < lines_.size(); }
    bool enabled(int k) const { return valid(k) && !disabled_[std::size_t(k)]; }
    int cellOf(int line, int j) const { return pointCell_[std::size_t(lines_[std::size_t(line)].idx[j])]; }

    // 2021.01: an end is free when every segment listed in its cell is this
    // one or disabled. Counted: the cell's enabled entries are this segment's own.
    bool isFree(int line, int j) const {
        const int c = cellOf(line, j);
        return activeCount_[std::size_t(c)] == selfCount_[std::size_t(line)][std::size_t(j)];
    }

    void extractPaths() {
        const std::size_t nCells = grid_.entries.size();
        const std::size_t nLines = lines_.size();
        disabled_.assign(nLines, false);
        activeCount_.assign(nCells, 0);
        maxSelf_.assign(nCells, 0);
        selfCount_.assign(nLines, {0, 0});
        occurrences_.assign(nLines, {});
        walk_.resize(nCells);
        walkStart_.assign(nCells, 0);
        // In one pass over the cells (linear in their entries: a file can put
        // a hundred thousand segment ends in one cell): each cell's walk list,
        // each segment once in first-listed order; and, for every segment end
        // in the cell, how often the cell lists that segment (its own ends,
        // and stale numbers of blocks that happen to equal it).
        std::vector<int> listedIn(nLines, -1), timesListed(nLines, 0);
        for (std::size_t c = 0; c < nCells; ++c) {
            for (int k : grid_.entries[c]) {
                if (!valid(k)) continue;
                ++activeCount_[c];
                occurrences_[std::size_t(k)].push_back(static_cast<int>(c));
                ++timesListed[std::size_t(k)];
                if (listedIn[std::size_t(k)] != static_cast<int>(c)) {
                    listedIn[std::size_t(k)] = static_cast<int>(c);
                    walk_[c].push_back(k);
                }
            }
            for (int k : walk_[c]) {
                for (int j = 0; j < 2; ++j) {
                    if (cellOf(k, j) != static_cast<int>(c)) continue;
                    selfCount_[std::size_t(k)][std::size_t(j)] = timesListed[std::size_t(k)];
                    maxSelf_[c] = std::max(maxSelf_[c], timesListed[std::size_t(k)]);
                }
            }
            for (int k : walk_[c]) timesListed[std::size_t(k)] = 0;
        }

        // Open paths, from the lowest-numbered enabled segment with a free end.
        std::priority_queue<int, std::vector<int>, std::greater<int>> candidates;
        for (std::size_t l = 0; l < nLines; ++l) {
            if (isFree(int(l), 0) || isFree(int(l), 1)) candidates.push(int(l));
        }
        while (true) {
            while (!candidates.empty() && !enabled(candidates.top())) candidates.pop();
            if (candidates.empty()) break;
            const int line = candidates.top();
            const int j = isFree(line, 0) ? 0 : 1;
            walkPath(line, j, false, &candidates);
        }
        // Then closed ones, from the lowest-numbered enabled segment.
        for (std::size_t l = 0; l < nLines; ++l) {
            if (!disabled_[l]) walkPath(int(l), 0, true, &candidates);
        }
    }

    void disable(int line, std::priority_queue<int, std::vector<int>, std::greater<int>>* candidates) {
        disabled_[std::size_t(line)] = true;
        std::vector<int>& occ = occurrences_[std::size_t(line)];
        for (int c : occ) --activeCount_[std::size_t(c)];
        std::sort(occ.begin(), occ.end());
        occ.erase(std::unique(occ.begin(), occ.end()), occ.end());
        for (int c : occ) {
            if (activeCount_[std::size_t(c)] > maxSelf_[std::size_t(c)]) continue;
            const std::vector<int>& list = walk_[std::size_t(c)];
            for (std::size_t i = walkStart_[std::size_t(c)]; i < list.size(); ++i) {
                const int k = list[i];
                if (!enabled(k)) continue;
                for (int j = 0; j < 2; ++j) {
                    if (cellOf(k, j) == c && isFree(k, j)) candidates->push(k);
                }
            }
        }
    }

    void walkPath(int line, int point, bool closed,
                  std::priority_queue<int, std::vector<int>, std::greater<int>>* candidates) {
        paths_.push_back({});
        Path& path = paths_.back();
        path.closed = closed;
        path.indices.push_back(lines_[std::size_t(line)].idx[point]);
        while (true) {
            const int far = lines_[std::size_t(line)].idx[!point];
            path.indices.push_back(far);
            disable(line, candidates);
            const int c = pointCell_[std::size_t(far)];
            std::vector<int>& list = walk_[std::size_t(c)];
            std::size_t& first = walkStart_[std::size_t(c)];
            // The first enabled segment listed in the cell with an end there.
            bool found = false;
            std::size_t i = first;
            for (; i < list.size() && !found; ++i) {
                const int k = list[i];
                if (disabled_[std::size_t(k)]) continue;
                for (int j = 0; j < 2 && !found; ++j) {
                    if (cellOf(k, j) != c) continue;
                    line = k;
                    point = j;
                    found = true;
                }
            }
            // The disabled entries passed over leave the list: the enabled
            // ones before `i` move up against it, in their order, and the
            // list now starts after the gap. Only the part scanned moves, so
            // a cell that many segments share costs its length once, not once
            // per step.
            std::size_t keep = i;
            for (std::size_t r = i; r-- > first;) {
                if (!disabled_[std::size_t(list[r])]) list[--keep] = list[r];
            }
            first = keep;
            if (!found) break;
        }
    }

    // fixup_path_direction: closed paths (until the first open one) are
    // reversed when they turn the other way at their leftmost point.
    void fixupPathDirection() {
        for (Path& path : paths_) {
            if (!path.closed) break;
            const std::vector<int>& ix = path.indices;
            double minX = points_[std::size_t(ix[0])][0];
            std::size_t minXPoint = 0;
            for (std::size_t j = 1; j < ix.size(); ++j) {
                if (points_[std::size_t(ix[j])][0] < minX) {
                    minX = points_[std::size_t(ix[j])][0];
                    minXPoint = j;
                }
            }
            const std::size_t b = minXPoint;
            const std::size_t a = b == 0 ? ix.size() - 2 : b - 1;
            const std::size_t c = b == ix.size() - 1 ? 1 : b + 1;
            const auto& pa = points_[std::size_t(ix[a])];
            const auto& pb = points_[std::size_t(ix[b])];
            const auto& pc = points_[std::size_t(ix[c])];
            const double ax = pa[0] - pb[0], ay = pa[1] - pb[1];
            const double cx = pc[0] - pb[0], cy = pc[1] - pb[1];
            if (std::atan2(ax, ay) < std::atan2(cx, cy)) std::reverse(path.indices.begin(), path.indices.end());
        }
    }

    // toPolygon2d: each path backwards; a closed path without its repeated
    // first point, an open one closed.
    Outlines toOutlines() const {
        Outlines result;
        for (const Path& path : paths_) {
            Outline outline;
            std::size_t endidx = path.indices.size();
            if (!path.closed) endidx++;
            for (std::size_t j = 1; j < endidx; ++j) {
                const auto& p = points_[std::size_t(path.indices[path.indices.size() - j])];
                outline.points.push_back({p[0], p[1]});
            }
            result.outlines.push_back(std::move(outline));
        }
        if (result.outlines.empty()) {
            throw Error("import: " + quotedPath(import_.path) + " has no outlines" +
                        (import_.layer.empty() ? std::string() : " on layer " + quotedPath(import_.layer)));
        }
        return result;
    }

    const scene::FlatImport& import_;

    // Parser state, as DxfData's locals.
    bool inEntities_ = false, inBlocks_ = false;
    std::string currentBlock_;
    std::string mode_, layer_, iddata_;
    int dimtype_ = 0;
    std::vector<double> xverts_, yverts_;
    double radius_ = 0, arcStart_ = 0, arcStop_ = 0, ellipseStart_ = 0, ellipseStop_ = 0;

    Grid grid_;
    std::vector<std::array<double, 2>> points_;
    std::vector<int> pointCell_;
    std::vector<Segment> lines_;
    std::unordered_map<std::string, std::vector<Segment>> blocks_;
    std::size_t segmentCount_ = 0;

    // Path extraction.
    std::vector<bool> disabled_;
    std::vector<int> activeCount_, maxSelf_;
    std::vector<std::array<int, 2>> selfCount_;
    std::vector<std::vector<int>> occurrences_;
    std::vector<std::vector<int>> walk_;
    std::vector<std::size_t> walkStart_;   // walk_[c] starts at walkStart_[c]; entries before it are spent
    std::vector<Path> paths_;
};

}  // namespace

Outlines importDxf(const scene::FlatImport& import, const std::string& text) { return DxfReader(import).read(text); }

}  // namespace strata::flat::detail
