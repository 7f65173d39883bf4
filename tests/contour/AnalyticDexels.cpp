#include "AnalyticDexels.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace strata::contour::test {
namespace {

glm::dvec3 axisVector(int axis, double sign) {
    glm::dvec3 v(0.0);
    v[axis] = sign;
    return v;
}

class Box : public Solid {
public:
    Box(const glm::dvec3& low, const glm::dvec3& high) : low_(low), high_(high) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        for (int a = 0; a < 3; ++a) {
            if (a != axis && !(low_[a] < p[a] && p[a] < high_[a])) return {};
        }
        return {{low_[axis], high_[axis], axisVector(axis, -1.0), axisVector(axis, 1.0)}};
    }
    bool contains(const glm::dvec3& p) const override {
        return glm::all(glm::lessThan(low_, p)) && glm::all(glm::lessThan(p, high_));
    }

private:
    glm::dvec3 low_, high_;
};

class OrientedBox : public Solid {
public:
    OrientedBox(const glm::dvec3& center, const glm::dmat3& rotation, const glm::dvec3& half)
        : center_(center), rotation_(rotation), half_(half) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        // Slabs in the box's frame; t is the world coordinate along `axis`.
        glm::dvec3 start = p;
        start[axis] = 0.0;
        const glm::dvec3 o = glm::transpose(rotation_) * (start - center_);
        const glm::dvec3 d = glm::transpose(rotation_) * axisVector(axis, 1.0);
        double enter = -1e300, leave = 1e300;
        glm::dvec3 inNormal(0.0), outNormal(0.0);
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0) {
                if (std::abs(o[a]) >= half_[a]) return {};
                continue;
            }
            double t0 = (-half_[a] - o[a]) / d[a], t1 = (half_[a] - o[a]) / d[a];
            double s0 = -1.0, s1 = 1.0;
            if (t0 > t1) std::swap(t0, t1), std::swap(s0, s1);
            if (t0 > enter) enter = t0, inNormal = rotation_[a] * s0;
            if (t1 < leave) leave = t1, outNormal = rotation_[a] * s1;
        }
        if (!(enter < leave)) return {};
        return {{enter, leave, inNormal, outNormal}};
    }
    bool contains(const glm::dvec3& p) const override {
        const glm::dvec3 o = glm::transpose(rotation_) * (p - center_);
        return glm::all(glm::lessThan(glm::abs(o), half_));
    }

private:
    glm::dvec3 center_;
    glm::dmat3 rotation_;
    glm::dvec3 half_;
};

class Sphere : public Solid {
public:
    Sphere(const glm::dvec3& center, double radius) : center_(center), radius_(radius) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
            if (a != axis) d2 += (p[a] - center_[a]) * (p[a] - center_[a]);
        }
        const double h2 = radius_ * radius_ - d2;
        if (!(h2 > 0.0)) return {};
        const double h = std::sqrt(h2);
        Span s{center_[axis] - h, center_[axis] + h, {}, {}};
        glm::dvec3 q = p;
        q[axis] = s.in;
        s.inNormal = (q - center_) / radius_;
        q[axis] = s.out;
        s.outNormal = (q - center_) / radius_;
        return {s};
    }
    bool contains(const glm::dvec3& p) const override { return glm::length(p - center_) < radius_; }

private:
    glm::dvec3 center_;
    double radius_;
};

// The torus by its distance-like implicit function (negative inside):
// sign changes bracketed on a fine walk along the ray, then bisected to the
// last bit. A pair of crossings closer than one step (a grazing ray) is lost
// as a pair, which keeps every ray's count even.
class Torus : public Solid {
public:
    Torus(const glm::dvec3& center, double major, double minor) : center_(center), major_(major), minor_(minor) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        const double reach = major_ + minor_;
        const double step = minor_ / 256.0;
        glm::dvec3 q = p;
        auto at = [&](double t) {
            q[axis] = t;
            return value(q);
        };
        std::vector<double> roots;
        double t0 = center_[axis] - reach - step, f0 = at(t0);
        for (double t1 = t0 + step; t1 <= center_[axis] + reach + step; t0 = t1, t1 += step) {
            const double f1 = at(t1);
            if ((f0 < 0.0) != (f1 < 0.0)) roots.push_back(bisect(axis, p, t0, t1));
            f0 = f1;
        }
        Spans spans;
        for (std::size_t i = 0; i + 1 < roots.size(); i += 2) {
            Span s{roots[i], roots[i + 1], {}, {}};
            q[axis] = s.in;
            s.inNormal = gradient(q);
            q[axis] = s.out;
            s.outNormal = gradient(q);
            spans.push_back(s);
        }
        return spans;
    }
    bool contains(const glm::dvec3& p) const override { return value(p) < 0.0; }

private:
    double value(const glm::dvec3& p) const {
        const glm::dvec3 d = p - center_;
        const double rho = std::sqrt(d.x * d.x + d.y * d.y) - major_;
        return rho * rho + d.z * d.z - minor_ * minor_;
    }
    glm::dvec3 gradient(const glm::dvec3& p) const {
        const glm::dvec3 d = p - center_;
        const double r = std::sqrt(d.x * d.x + d.y * d.y);
        const double k = (r - major_) / r;
        return glm::normalize(glm::dvec3(k * d.x, k * d.y, d.z));
    }
    double bisect(int axis, glm::dvec3 q, double low, double high) const {
        q[axis] = low;
        const bool lowInside = value(q) < 0.0;
        for (;;) {
            const double mid = 0.5 * (low + high);
            if (mid <= low || mid >= high) return mid;
            q[axis] = mid;
            ((value(q) < 0.0) == lowInside ? low : high) = mid;
        }
    }
    glm::dvec3 center_;
    double major_, minor_;
};

// Spans of a union: overlapping spans merged, each end keeping its normal.
Spans merge(Spans all) {
    std::sort(all.begin(), all.end(), [](const Span& a, const Span& b) { return a.in < b.in; });
    Spans merged;
    for (const Span& s : all) {
        if (!merged.empty() && s.in <= merged.back().out) {
            if (s.out > merged.back().out) merged.back().out = s.out, merged.back().outNormal = s.outNormal;
        } else {
            merged.push_back(s);
        }
    }
    return merged;
}

class Union : public Solid {
public:
    explicit Union(std::vector<SolidPtr> parts) : parts_(std::move(parts)) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        Spans all;
        for (const SolidPtr& s : parts_) {
            const Spans some = s->along(axis, p);
            all.insert(all.end(), some.begin(), some.end());
        }
        return merge(std::move(all));
    }
    bool contains(const glm::dvec3& p) const override {
        return std::any_of(parts_.begin(), parts_.end(), [&](const SolidPtr& s) { return s->contains(p); });
    }

private:
    std::vector<SolidPtr> parts_;
};

class Difference : public Solid {
public:
    Difference(SolidPtr from, SolidPtr cut) : from_(std::move(from)), cut_(std::move(cut)) {}
    Spans along(int axis, const glm::dvec3& p) const override {
        Spans result = from_->along(axis, p);
        for (const Span& c : cut_->along(axis, p)) {
            Spans next;
            for (const Span& s : result) {
                if (c.out <= s.in || s.out <= c.in) {
                    next.push_back(s);
                    continue;
                }
                if (s.in < c.in) next.push_back({s.in, c.in, s.inNormal, -c.inNormal});
                if (c.out < s.out) next.push_back({c.out, s.out, -c.outNormal, s.outNormal});
            }
            result = std::move(next);
        }
        return result;
    }
    bool contains(const glm::dvec3& p) const override { return from_->contains(p) && !cut_->contains(p); }

private:
    SolidPtr from_, cut_;
};

}  // namespace

SolidPtr box(const glm::dvec3& low, const glm::dvec3& high) { return std::make_shared<Box>(low, high); }
SolidPtr orientedBox(const glm::dvec3& center, const glm::dmat3& rotation, const glm::dvec3& half) {
    return std::make_shared<OrientedBox>(center, rotation, half);
}
SolidPtr sphere(const glm::dvec3& center, double radius) { return std::make_shared<Sphere>(center, radius); }
SolidPtr torus(const glm::dvec3& center, double major, double minor) {
    return std::make_shared<Torus>(center, major, minor);
}
SolidPtr unite(std::vector<SolidPtr> parts) { return std::make_shared<Union>(std::move(parts)); }
SolidPtr subtract(SolidPtr from, SolidPtr cut) { return std::make_shared<Difference>(std::move(from), std::move(cut)); }

DexelGrid gridAround(const glm::dvec3& low, const glm::dvec3& high, double spacing) {
    constexpr double kSpare = 2.0;
    const glm::dvec3 offGrid(0.3719, 0.4137, 0.2953);
    DexelGrid grid;
    grid.spacing = spacing;
    grid.origin = low - spacing * (kSpare + offGrid);
    for (int a = 0; a < 3; ++a) {
        grid.count[a] = int(std::ceil((high[a] - low[a]) / spacing + offGrid[a] + 2.0 * kSpare)) + 1;
    }
    return grid;
}

Dexels sample(const Solid& solid, const DexelGrid& grid) {
    Dexels dexels;
    dexels.grid = grid;
    for (int a = 0; a < 3; ++a) {
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        DexelRays& rays = dexels.axes[a];
        rays.first.push_back(0);
        for (int iv = 0; iv < grid.count[v]; ++iv) {
            for (int iu = 0; iu < grid.count[u]; ++iu) {
                glm::dvec3 p(0.0);
                p[u] = grid.origin[u] + grid.spacing * iu;
                p[v] = grid.origin[v] + grid.spacing * iv;
                for (const Span& s : solid.along(a, p)) {
                    if (!(s.in < s.out)) continue;
                    rays.crossings.push_back({s.in, glm::vec3(s.inNormal), true});
                    rays.crossings.push_back({s.out, glm::vec3(s.outNormal), false});
                }
                rays.first.push_back(std::uint32_t(rays.crossings.size()));
            }
        }
    }
    return dexels;
}

glm::dmat3 rotation(double x, double y, double z) {
    const double cx = std::cos(x), sx = std::sin(x), cy = std::cos(y), sy = std::sin(y);
    const double cz = std::cos(z), sz = std::sin(z);
    const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);
    const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
    const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
    return rz * ry * rx;
}

}  // namespace strata::contour::test
