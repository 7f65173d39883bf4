#include "strata/reference/RayCaster.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "strata/core/Error.h"
#include "strata/core/Threads.h"
#include "strata/reference/IntervalCsg.h"
#include "strata/reference/RayTriangle.h"

namespace strata::reference {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Triangle boxes are padded by this fraction of the scene's diagonal, far
// more than float rounding of the boxes and of the (shifted) Embree ray can
// move anything, so Embree's float traversal never drops a triangle that the
// exact double test would count.
constexpr double kBoxPadding = 1e-5;
// Crossings of one leaf closer than this fraction of the scene's size count
// as one point (RayTriangle.h: a fold's two hits, rounded apart).
constexpr double kMergeFraction = 1e-9;

struct LeafGeometry {
    int leaf = -1;
    std::vector<glm::dvec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<glm::dvec3> normals;  // unit geometric normal per triangle
    glm::dvec3 offset{0.0};           // Embree works relative to the scene's centre
    double padding = 0.0;
};

struct RawHit {
    int leaf;
    unsigned triangle;
    double t;
    bool entering;
};

// Embree passes this through to the callback; RTCIntersectContext must come first.
struct TraceContext {
    RTCIntersectContext embree;
    const RayFrame* frame = nullptr;
    double tStart = 0.0;
    std::vector<RawHit>* hits = nullptr;
};

float roundDown(double v) {
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) <= v ? f : std::nextafter(f, -std::numeric_limits<float>::infinity());
}

float roundUp(double v) {
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) >= v ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

void boundsCallback(const RTCBoundsFunctionArguments* args) {
    const auto* geometry = static_cast<const LeafGeometry*>(args->geometryUserPtr);
    const auto& triangle = geometry->triangles[args->primID];
    glm::dvec3 lo{kInfinity}, hi{-kInfinity};
    for (uint32_t v : triangle) {
        const glm::dvec3 p = geometry->positions[v] - geometry->offset;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    lo -= geometry->padding;
    hi += geometry->padding;
    RTCBounds* box = args->bounds_o;
    box->lower_x = roundDown(lo.x);
    box->lower_y = roundDown(lo.y);
    box->lower_z = roundDown(lo.z);
    box->upper_x = roundUp(hi.x);
    box->upper_y = roundUp(hi.y);
    box->upper_z = roundUp(hi.z);
}

// Runs the exact test and records the crossing; never reports a hit to
// Embree, so the ray's tfar stays put and traversal goes on to every box.
void intersectCallback(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1 || !args->valid[0]) return;  // only rtcIntersect1 is used
    const auto* geometry = static_cast<const LeafGeometry*>(args->geometryUserPtr);
    auto* context = reinterpret_cast<TraceContext*>(args->context);
    const auto& triangle = geometry->triangles[args->primID];
    const auto crossing = crossTriangle(*context->frame, geometry->positions[triangle[0]],
                                        geometry->positions[triangle[1]], geometry->positions[triangle[2]]);
    if (crossing && crossing->t > context->tStart) {
        context->hits->push_back({geometry->leaf, args->primID, crossing->t, crossing->entering});
    }
}

// A leaf whose only crossings are an exit and then an entry: the ray passes
// a hair outside one of its silhouette edges, where rounding put the two
// faces' crossings in reverse order. It has no crossing there, as the GPU
// evaluator reads such a pair (evaluate.frag, grazesOutside). `hits` are
// ordered by leaf, then along the ray.
void dropGrazes(std::vector<RawHit>& hits) {
    std::size_t kept = 0;
    for (std::size_t first = 0; first < hits.size();) {
        std::size_t last = first;
        while (last < hits.size() && hits[last].leaf == hits[first].leaf) ++last;
        const bool graze = last - first == 2 && !hits[first].entering && hits[first + 1].entering &&
                           hits[first].t < hits[first + 1].t;
        for (; !graze && first < last; ++first) hits[kept++] = hits[first];
        first = last;
    }
    hits.resize(kept);
}

void occludedCallback(const RTCOccludedFunctionNArguments*) {}  // rtcOccluded is not used

void recordEmbreeError(void* userPtr, RTCError, const char* message) {
    auto* first = static_cast<std::string*>(userPtr);
    if (first->empty()) *first = message ? message : "unknown error";
}

// Per-thread scratch, reused ray after ray.
struct Workspace {
    std::vector<RawHit> hits;
    std::vector<Crossing> crossings;
    std::vector<IntervalList> leafLists;
    std::vector<int> touched;
    std::vector<std::size_t> order;  // hits by t
    std::vector<double> placed;      // per hit: the t of its group of coincident crossings
    std::vector<char> inside;        // per leaf, while choosing the surface shown
    std::vector<char> stack;         // CsgProgram::contains
    std::vector<const RawHit*> face; // the crossings of one face, while choosing the surface shown
    CsgProgram::Workspace evaluation;
};

// Order by leaf, then along the ray; drop repeats (a triangle referenced twice by the hierarchy).
inline void orderHits(std::vector<RawHit>& hits) {
    std::sort(hits.begin(), hits.end(), [](const RawHit& a, const RawHit& b) {
        if (a.leaf != b.leaf) return a.leaf < b.leaf;
        if (a.t != b.t) return a.t < b.t;
        return a.triangle < b.triangle;
    });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const RawHit& a, const RawHit& b) {
                               return a.leaf == b.leaf && a.triangle == b.triangle && a.t == b.t;
                           }),
               hits.end());
    dropGrazes(hits);
}

// Coincident crossings (docs/algorithm.md, "Coincident surfaces"): in
// order along the ray, crossings no more than `coincidence` apart belong
// to one group (a chain: each within the tolerance of the one before),
// and every crossing takes its group's first t. The tree then sees one
// place where the surfaces of several leaves were, as exact arithmetic
// would.
inline void placeCoincident(const std::vector<RawHit>& hits, double coincidence, std::vector<std::size_t>& order,
                            std::vector<double>& placed) {
    order.resize(hits.size());
    for (std::size_t k = 0; k < hits.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return hits[a].t != hits[b].t ? hits[a].t < hits[b].t : a < b;
    });
    placed.resize(hits.size());
    double anchor = -kInfinity, previous = -kInfinity;
    for (std::size_t k : order) {
        if (!(hits[k].t - previous <= coincidence)) anchor = hits[k].t;
        previous = hits[k].t;
        placed[k] = anchor;
    }
}

// The surface shown, by the GPU evaluator's rule (evaluate.frag): the
// group's crossings in order along the ray, the tree asked after each t;
// the first after which the result differs from before the group marks
// the face (crossings chained within a quarter of the tolerance) whose
// crossing is shown. Of the face's crossings, those whose leaf decides
// the result (set back alone, with every leaf as it is after the face,
// it would undo the change) where some do and some do not; of those, one
// whose facing changes its leaf as the result changes, else one facing
// the other way (its normal flipped); the lowest leaf, then the nearest.
struct ShownCrossing {
    const CsgProgram& program;
    const FirstChange& change;
    std::vector<char>& inside;  // each leaf's membership, from just before the change's group
    std::vector<char>& stack;   // CsgProgram::contains
    std::vector<const RawHit*>& face;
    const RawHit* pick = nullptr;
    bool pickSame = false;

    // Whether `hit` (facing as the result changes where `same`) is to be shown rather than the pick so far.
    bool better(const RawHit& hit, bool same) const {
        return !pick || (same && !pickSame) ||
               (same == pickSame && (hit.leaf < pick->leaf || (hit.leaf == pick->leaf && hit.t < pick->t)));
    }

    // `inside`: every leaf as it is after the face.
    void settleFace() {
        if (face.size() < 2) return;
        const bool now = program.contains(inside, stack);
        std::vector<const RawHit*> deciding;
        for (const RawHit* hit : face) {
            inside[static_cast<std::size_t>(hit->leaf)] ^= 1;
            if (program.contains(inside, stack) != now) deciding.push_back(hit);
            inside[static_cast<std::size_t>(hit->leaf)] ^= 1;
        }
        if (deciding.empty() || deciding.size() == face.size()) return;
        pick = nullptr;
        for (const RawHit* hit : deciding) {
            const bool same = hit->entering == change.resultEnters;
            if (better(*hit, same)) {
                pick = hit;
                pickSame = same;
            }
        }
    }

    // Walks the change's group along the ray, face by face, and leaves the crossing shown in `pick`.
    void choose(const std::vector<RawHit>& hits, const std::vector<std::size_t>& order,
                const std::vector<double>& placed, double coincidence) {
        const bool resultBefore = !change.resultEnters;
        const double faceTolerance = coincidence * 0.25;
        bool changed = false;
        face.clear();
        double faceEnd = -kInfinity;
        bool settled = false;
        for (std::size_t at = 0; at < order.size() && !settled;) {
            if (placed[order[at]] != change.t) {
                ++at;
                continue;
            }
            std::size_t next = at;
            for (; next < order.size() && hits[order[next]].t == hits[order[at]].t; ++next) {
                const RawHit& hit = hits[order[next]];
                if (placed[order[next]] != change.t) continue;
                // Considered before it is applied: the first crossing of the
                // next face finds every leaf as it is after this one.
                if (hit.t - faceEnd > faceTolerance) {
                    if (changed) {
                        settleFace();
                        settled = true;
                        break;
                    }
                    pick = nullptr;
                    face.clear();
                }
                faceEnd = hit.t;
                face.push_back(&hit);
                const bool same = hit.entering == change.resultEnters;
                if (better(hit, same)) {
                    pick = &hit;
                    pickSame = same;
                }
            }
            if (settled) break;
            for (std::size_t k = at; k < next; ++k)
                if (placed[order[k]] == change.t) inside[static_cast<std::size_t>(hits[order[k]].leaf)] ^= 1;
            if (program.contains(inside, stack) != resultBefore) changed = true;
            at = next;
        }
        if (!settled) settleFace();
    }
};

}  // namespace

struct ReferenceScene::Impl {
    explicit Impl(const scene::Tree& tree) : program(tree) {}
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    void check(int line) const {
        if (rtcGetDeviceError(device) != RTC_ERROR_NONE || !embreeError.empty()) {
            throw Error(std::string("engine/reference/RayCaster.cpp:") + std::to_string(line) +
                        ": embree: " + (embreeError.empty() ? "error" : embreeError));
        }
    }

    RayHit trace(const camera::Ray& ray, double tStart, double coincidence, Workspace& workspace) const;
    bool clipToBox(const glm::dvec3& origin, const glm::dvec3& direction, double& enter) const;
    void gatherHits(const RayFrame& frame, const glm::dvec3& origin, const glm::dvec3& direction, double enter,
                    double tStart, Workspace& workspace) const;
    void buildLeafLists(const glm::dvec3& origin, Workspace& workspace) const;
    std::optional<FirstChange> evaluateAlong(Workspace& workspace) const;
    RayHit shownHit(const RawHit& pick, bool pickSame) const;

    CsgProgram program;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string embreeError;
    std::vector<std::unique_ptr<LeafGeometry>> geometries;
    std::vector<const LeafGeometry*> byLeaf;  // tree leaf -> its geometry, or null
    glm::dvec3 boxMin{kInfinity}, boxMax{-kInfinity};  // padded box of every traced triangle
    glm::dvec3 offset{0.0};
    double size = 0.0;  // the box's diagonal
    mesh::Bounds bounds;  // of every leaf mesh, background leaves too: the GPU's box for the tolerance
    double padding = 0.0;
};

// Where the ray is in the scene's box: `enter` (from tStart) moves up to where
// it comes in; false where it misses the box.
inline bool ReferenceScene::Impl::clipToBox(const glm::dvec3& origin, const glm::dvec3& direction,
                                            double& enter) const {
    double leave = kInfinity;
    for (int k = 0; k < 3; ++k) {
        if (direction[k] == 0.0) {
            if (origin[k] < boxMin[k] || origin[k] > boxMax[k]) return false;
            continue;
        }
        double t0 = (boxMin[k] - origin[k]) / direction[k], t1 = (boxMax[k] - origin[k]) / direction[k];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
    }
    return enter <= leave;
}

// Every exact crossing after tStart of a triangle Embree finds along the ray, in workspace.hits.
inline void ReferenceScene::Impl::gatherHits(const RayFrame& frame, const glm::dvec3& origin,
                                             const glm::dvec3& direction, double enter, double tStart,
                                             Workspace& workspace) const {
    // Embree's float ray starts at the box (shortly before it), so float
    // rounding is relative to the scene's size, not to the eye's distance.
    const double shift = enter - padding;
    const glm::dvec3 start = origin + shift * direction - offset;
    RTCRayHit rayHit{};
    rayHit.ray.org_x = static_cast<float>(start.x);
    rayHit.ray.org_y = static_cast<float>(start.y);
    rayHit.ray.org_z = static_cast<float>(start.z);
    rayHit.ray.dir_x = static_cast<float>(direction.x);
    rayHit.ray.dir_y = static_cast<float>(direction.y);
    rayHit.ray.dir_z = static_cast<float>(direction.z);
    rayHit.ray.tnear = 0.0f;
    rayHit.ray.tfar = std::numeric_limits<float>::infinity();
    rayHit.ray.mask = 0xFFFFFFFFu;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;

    workspace.hits.clear();
    TraceContext context;
    rtcInitIntersectContext(&context.embree);
    context.frame = &frame;
    context.tStart = tStart;
    context.hits = &workspace.hits;
    rtcIntersect1(scene, &context.embree, &rayHit);
}

// Each hit leaf's intervals along the ray, from its crossings at their groups' t;
// the leaves are noted in workspace.touched.
inline void ReferenceScene::Impl::buildLeafLists(const glm::dvec3& origin, Workspace& workspace) const {
    const std::vector<RawHit>& hits = workspace.hits;
    const std::vector<double>& placed = workspace.placed;
    if (workspace.leafLists.size() < program.leafCount()) workspace.leafLists.resize(program.leafCount());
    const double tolerance = kMergeFraction * (size + glm::length(origin - offset));
    for (std::size_t first = 0; first < hits.size();) {
        std::size_t last = first;
        workspace.crossings.clear();
        for (; last < hits.size() && hits[last].leaf == hits[first].leaf; ++last) {
            workspace.crossings.push_back({placed[last], hits[last].entering, static_cast<int>(last)});
        }
        const int leaf = hits[first].leaf;
        leafIntervals(leaf, workspace.crossings, tolerance, workspace.leafLists[static_cast<std::size_t>(leaf)]);
        workspace.touched.push_back(leaf);
        first = last;
    }
}

// The tree's first change along the ray, with each leaf's membership just
// before it in workspace.inside; the leaf lists are left empty for the next ray.
inline std::optional<FirstChange> ReferenceScene::Impl::evaluateAlong(Workspace& workspace) const {
    const std::optional<FirstChange> change =
        firstChange(program.evaluate(workspace.leafLists, workspace.evaluation));
    // Each leaf's membership just before the change's group, while the lists are at hand.
    std::vector<char>& inside = workspace.inside;
    inside.assign(program.leafCount(), 0);
    if (change) {
        for (int leaf : workspace.touched) {
            for (const Interval& interval : workspace.leafLists[static_cast<std::size_t>(leaf)]) {
                if (interval.begin < change->t && change->t <= interval.end) inside[static_cast<std::size_t>(leaf)] = 1;
            }
        }
    }
    for (int leaf : workspace.touched) workspace.leafLists[static_cast<std::size_t>(leaf)].clear();
    workspace.touched.clear();
    return change;
}

// The hit at the crossing shown: its leaf's normal, flipped where it faces the other way.
inline RayHit ReferenceScene::Impl::shownHit(const RawHit& pick, bool pickSame) const {
    const LeafGeometry& geometry = *byLeaf[static_cast<std::size_t>(pick.leaf)];
    RayHit result;
    result.t = pick.t;
    result.leaf = pick.leaf;
    result.normal = geometry.normals[pick.triangle];
    result.cut = !pickSame;
    if (result.cut) result.normal = -result.normal;
    return result;
}

// The reference's inner loop for one ray: clip to the box, gather Embree's
// candidates, exact crossings, order, the tree along the ray; each step's
// arrays stay in the workspace.
RayHit ReferenceScene::Impl::trace(const camera::Ray& ray, double tStart, double coincidence,
                                   Workspace& workspace) const {
    RayHit miss;
    miss.t = kInfinity;
    if (!scene) return miss;
    const RayFrame frame(ray);
    const glm::dvec3 origin = frame.ray().origin, direction = frame.ray().direction;

    // Where the ray is in the scene's box. Missing it means no crossings, and a
    // result made of nothing but empty leaves is empty.
    double enter = tStart;
    if (!clipToBox(origin, direction, enter)) return miss;

    gatherHits(frame, origin, direction, enter, tStart, workspace);
    orderHits(workspace.hits);
    placeCoincident(workspace.hits, coincidence, workspace.order, workspace.placed);
    buildLeafLists(origin, workspace);
    const std::optional<FirstChange> change = evaluateAlong(workspace);
    if (!change) return miss;

    ShownCrossing shown{program, *change, workspace.inside, workspace.stack, workspace.face};
    shown.choose(workspace.hits, workspace.order, workspace.placed, coincidence);
    if (!shown.pick) return miss;  // cannot happen: the change has a crossing of its group
    return shownHit(*shown.pick, shown.pickSame);
}

ReferenceScene::ReferenceScene(const scene::Tree& tree, const model::Model& model)
    : impl_(std::make_unique<Impl>(tree)) {
    if (model.leafMeshes.size() != tree.leaves.size()) {
        throw Error("reference: the model has " + std::to_string(model.leafMeshes.size()) +
                    " leaf meshes for a tree of " + std::to_string(tree.leaves.size()) + " leaves");
    }
    Impl& impl = *impl_;
    impl.byLeaf.assign(tree.leaves.size(), nullptr);
    for (const mesh::Mesh& mesh : model.leafMeshes) {
        if (!mesh.triangles.empty()) impl.bounds.extend(mesh::boundsOf(mesh));
    }

    // The box of what is traced, and the padding that follows from its size.
    double largest = 0.0;
    for (int leaf : impl.program.leaves()) {
        const mesh::Mesh& mesh = model.leafMeshes[static_cast<std::size_t>(leaf)];
        for (const auto& triangle : mesh.triangles) {
            for (uint32_t v : triangle) {
                if (v >= mesh.positions.size()) {
                    throw Error("reference: leaf " + std::to_string(leaf) + " has a triangle with vertex index " +
                                std::to_string(v) + " out of range");
                }
                const glm::dvec3& p = mesh.positions[v];
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                    throw Error("reference: leaf " + std::to_string(leaf) + " has a vertex that is not finite");
                }
                impl.boxMin = glm::min(impl.boxMin, p);
                impl.boxMax = glm::max(impl.boxMax, p);
                largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            }
        }
    }
    if (impl.boxMin.x > impl.boxMax.x) return;  // nothing to trace: every ray misses

    impl.size = glm::length(impl.boxMax - impl.boxMin);
    impl.padding = std::max({kBoxPadding * impl.size, 1e-7 * largest, std::numeric_limits<double>::min()});
    impl.offset = (impl.boxMin + impl.boxMax) * 0.5;
    impl.boxMin -= 2.0 * impl.padding;
    impl.boxMax += 2.0 * impl.padding;

    impl.device = rtcNewDevice(nullptr);
    if (!impl.device) {
        throw Error("engine/reference/RayCaster.cpp:" + std::to_string(__LINE__) +
                    ": embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    }
    rtcSetDeviceErrorFunction(impl.device, recordEmbreeError, &impl.embreeError);
    impl.scene = rtcNewScene(impl.device);
    rtcSetSceneFlags(impl.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl.scene, RTC_BUILD_QUALITY_HIGH);
    impl.check(__LINE__);

    for (int leaf : impl.program.leaves()) {
        const mesh::Mesh& mesh = model.leafMeshes[static_cast<std::size_t>(leaf)];
        if (mesh.triangles.empty()) continue;
        auto geometry = std::make_unique<LeafGeometry>();
        geometry->leaf = leaf;
        geometry->positions = mesh.positions;
        geometry->triangles = mesh.triangles;
        geometry->normals.reserve(mesh.triangles.size());
        for (const auto& t : mesh.triangles) {
            const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                            mesh.positions[t[2]] - mesh.positions[t[0]]);
            const double length = glm::length(n);
            geometry->normals.push_back(length > 0.0 ? n / length : glm::dvec3(0.0));
        }
        geometry->offset = impl.offset;
        geometry->padding = impl.padding;

        RTCGeometry handle = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(handle, static_cast<unsigned>(mesh.triangles.size()));
        rtcSetGeometryUserData(handle, geometry.get());
        rtcSetGeometryBoundsFunction(handle, boundsCallback, nullptr);
        rtcSetGeometryIntersectFunction(handle, intersectCallback);
        rtcSetGeometryOccludedFunction(handle, occludedCallback);
        rtcCommitGeometry(handle);
        rtcAttachGeometryByID(impl.scene, handle, static_cast<unsigned>(leaf));
        rtcReleaseGeometry(handle);
        impl.check(__LINE__);
        impl.byLeaf[static_cast<std::size_t>(leaf)] = geometry.get();
        impl.geometries.push_back(std::move(geometry));
    }
    rtcCommitScene(impl.scene);
    impl.check(__LINE__);
}

ReferenceScene::~ReferenceScene() = default;
ReferenceScene::ReferenceScene(ReferenceScene&&) noexcept = default;
ReferenceScene& ReferenceScene::operator=(ReferenceScene&&) noexcept = default;

RayHit ReferenceScene::trace(const camera::Ray& ray, double tStart, double coincidence) const {
    Workspace workspace;
    return impl_->trace(ray, tStart, coincidence, workspace);
}

ReferenceImage ReferenceScene::render(const camera::Camera& camera, const ReferenceOptions& options) const {
    if (camera.width <= 0 || camera.height <= 0) throw Error("reference: image size must be positive");
    if (!(options.nearDepth >= 0.0) || !std::isfinite(options.nearDepth)) {
        throw Error("reference: nearDepth must be finite and >= 0");
    }
    ReferenceImage image;
    image.width = camera.width;
    image.height = camera.height;
    const auto pixels = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(camera.height);
    image.depth.assign(pixels, std::numeric_limits<float>::infinity());
    image.normal.assign(pixels, glm::vec3(0.0f));
    image.leaf.assign(pixels, -1);
    image.cut.assign(pixels, 0);

    const glm::dvec3 forward = camera.forward();
    const double coincidence = options.coincidence ? coincidenceTolerance(camera, impl_->bounds) : 0.0;
    std::atomic<int> nextRow{0};
    int rowsDone = 0;
    std::mutex progressMutex;

    auto work = [&] {
        try {
            Workspace workspace;
            for (int j = nextRow++; j < camera.height; j = nextRow++) {
                for (int i = 0; i < camera.width; ++i) {
                    const camera::Ray ray = camera.ray(i, j);
                    // The start where the ray crosses the plane at view depth nearDepth.
                    const double tStart =
                        (options.nearDepth - glm::dot(ray.origin - camera.eye, forward)) / glm::dot(ray.direction, forward);
                    // The tolerance is a view depth; along this ray it is that much more t.
                    const double along = coincidence / glm::dot(ray.direction, forward);
                    const RayHit hit = impl_->trace(ray, std::max(tStart, 0.0), along, workspace);
                    if (!hit.hit()) continue;
                    const std::size_t index = static_cast<std::size_t>(j) * camera.width + i;
                    image.depth[index] = static_cast<float>(camera.viewDepth(ray.origin + hit.t * ray.direction));
                    image.normal[index] = glm::vec3(hit.normal);
                    image.leaf[index] = hit.leaf;
                    image.cut[index] = hit.cut ? 1 : 0;
                }
                std::lock_guard lock(progressMutex);
                ++rowsDone;
                if (options.progress) options.progress(rowsDone, camera.height);
            }
        } catch (...) {
            nextRow = camera.height;  // the other threads take no more rows
            throw;
        }
    };
    runOnThreads(std::clamp(options.threads > 0 ? options.threads : hardwareThreads(), 1, camera.height), work);
    return image;
}

ReferenceImage renderReference(const scene::Tree& tree, const model::Model& model, const camera::Camera& camera,
                               const ReferenceOptions& options) {
    return ReferenceScene(tree, model).render(camera, options);
}

std::function<void(int done, int total)> progressOnStderr(const char* label) {
    struct State {
        std::string label;
        std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
        int lastTenth = 0;
    };
    auto state = std::make_shared<State>();
    state->label = label ? label : "reference";
    return [state](int done, int total) {
        const int tenth = total > 0 ? static_cast<int>(10LL * done / total) : 10;
        if (tenth <= state->lastTenth) return;
        if (std::chrono::steady_clock::now() - state->start < std::chrono::seconds(1)) return;
        state->lastTenth = tenth;
        std::fprintf(stderr, "%s: %d%%\n", state->label.c_str(), tenth * 10);
    };
}

}  // namespace strata::reference
