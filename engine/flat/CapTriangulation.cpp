#include "CapTriangulation.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>

#include <GL/glu.h>
#include <glm/vec3.hpp>

#include "BoxGroups.h"
#include "strata/core/Error.h"

namespace strata::flat::detail {
namespace {

// The tessellator's callbacks write here (GLU passes it as polygon data).
struct Collector {
    std::vector<glm::dvec3> vertices;  // GLU reads coordinates through stable pointers
    CapTriangles* out = nullptr;
    std::vector<uint32_t> pending;     // the current triangle's corners
    bool failed = false;
    GLenum error = 0;
};

void GLAPIENTRY onBegin(GLenum, void*) {}
void GLAPIENTRY onEdgeFlag(GLboolean, void*) {}  // its presence makes GLU emit plain triangles
void GLAPIENTRY onEnd(void*) {}

void GLAPIENTRY onVertex(void* vertex, void* data) {
    auto* c = static_cast<Collector*>(data);
    c->pending.push_back(static_cast<uint32_t>(reinterpret_cast<std::uintptr_t>(vertex)));
    if (c->pending.size() == 3) {
        c->out->triangles.push_back({c->pending[0], c->pending[1], c->pending[2]});
        c->pending.clear();
    }
}

// Called where outlines touch or cross: a point at that position is added.
void GLAPIENTRY onCombine(GLdouble coords[3], void*[4], GLfloat[4], void** result, void* data) {
    auto* c = static_cast<Collector*>(data);
    c->out->points.emplace_back(coords[0], coords[1]);
    *result = reinterpret_cast<void*>(static_cast<std::uintptr_t>(c->out->points.size() - 1));
}

void GLAPIENTRY onError(GLenum error, void* data) {
    auto* c = static_cast<Collector*>(data);
    c->failed = true;
    c->error = error;
}

struct TessDeleter {
    void operator()(GLUtesselator* t) const { gluDeleteTess(t); }
};

double signedArea(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

}  // namespace

CapTriangles triangulateCap(const Outlines& shape) {
    CapTriangles result;
    std::size_t total = 0;
    for (const Outline& o : shape.outlines) total += o.points.size();
    if (total == 0) return result;
    // Every outline's points first, in order (GLU reads them through stable
    // pointers; points it adds where outlines cross come after them all).
    result.points.reserve(total);
    Collector collector;
    collector.out = &result;
    collector.vertices.reserve(total);
    std::vector<std::size_t> firstPoint;
    std::vector<FlatBox<double>> boxes;
    firstPoint.reserve(shape.outlines.size());
    boxes.reserve(shape.outlines.size());
    for (const Outline& o : shape.outlines) {
        firstPoint.push_back(result.points.size());
        FlatBox<double> b{1.0, 1.0, -1.0, -1.0};
        for (const glm::dvec2& p : o.points) {
            result.points.push_back(p);
            collector.vertices.emplace_back(p.x, p.y, 0.0);
            b = b.x0 > b.x1 ? FlatBox<double>{p.x, p.y, p.x, p.y}
                            : FlatBox<double>{std::min(b.x0, p.x), std::min(b.y0, p.y), std::max(b.x1, p.x),
                                              std::max(b.y1, p.y)};
        }
        boxes.push_back(b);
    }

    std::unique_ptr<GLUtesselator, TessDeleter> tess(gluNewTess());
    if (!tess) throw Error("the cap tessellator could not be created");
    using Callback = void(GLAPIENTRY*)();
    gluTessCallback(tess.get(), GLU_TESS_BEGIN_DATA, reinterpret_cast<Callback>(&onBegin));
    gluTessCallback(tess.get(), GLU_TESS_EDGE_FLAG_DATA, reinterpret_cast<Callback>(&onEdgeFlag));
    gluTessCallback(tess.get(), GLU_TESS_VERTEX_DATA, reinterpret_cast<Callback>(&onVertex));
    gluTessCallback(tess.get(), GLU_TESS_END_DATA, reinterpret_cast<Callback>(&onEnd));
    gluTessCallback(tess.get(), GLU_TESS_COMBINE_DATA, reinterpret_cast<Callback>(&onCombine));
    gluTessCallback(tess.get(), GLU_TESS_ERROR_DATA, reinterpret_cast<Callback>(&onError));
    gluTessProperty(tess.get(), GLU_TESS_WINDING_RULE, GLU_TESS_WINDING_ODD);
    gluTessNormal(tess.get(), 0.0, 0.0, 1.0);

    // One polygon per group of outlines whose boxes meet (BoxGroups.h):
    // outlines of different groups neither cross nor nest, so under the odd
    // rule each group covers what it covers alone, and GLU's sweep stays
    // as short as one group (a line of text: one glyph at a time).
    for (const std::vector<std::size_t>& group : meetingBoxGroups(boxes)) {
        gluTessBeginPolygon(tess.get(), &collector);
        for (std::size_t k : group) {
            gluTessBeginContour(tess.get());
            const std::size_t first = firstPoint[k];
            for (std::size_t v = first; v < first + shape.outlines[k].points.size(); ++v) {
                gluTessVertex(tess.get(), &collector.vertices[v].x, reinterpret_cast<void*>(static_cast<std::uintptr_t>(v)));
            }
            gluTessEndContour(tess.get());
        }
        gluTessEndPolygon(tess.get());
        if (collector.failed) break;
    }
    if (collector.failed) {
        throw Error(std::string("the cap of an extrusion could not be triangulated: ") +
                    reinterpret_cast<const char*>(gluErrorString(collector.error)));
    }
    // GLU orients triangles by the normal; make sure of it. Triangles with no
    // area stay: the mesh's clean-up removes them without opening the mesh.
    for (auto& t : result.triangles) {
        if (signedArea(result.points[t[0]], result.points[t[1]], result.points[t[2]]) < 0.0) std::swap(t[1], t[2]);
    }
    return result;
}

}  // namespace strata::flat::detail
