// The only translation unit that sees GLEW, legacy GL and OpenCSG (see the header).
#include <GL/glew.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
// Only to release strata's context; X11's macros stay out as in strata's Context.cpp.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <opencsg.h>

#include "OpenCsgComparator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "strata/core/Error.h"
#include "strata/core/Timing.h"
#include "strata/gpu/Context.h"

namespace strata::bench {
namespace {

std::string glfwWhy() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

void checkGl(const char* where) {
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    while (glGetError() != GL_NO_ERROR) {
    }
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", error);
    throw Error(std::string("OpenCSG comparator: GL error ") + code + " after " + where);
}

// glvnd refuses a GLX context on a thread that has an EGL one current.
void releaseEgl() {
    if (eglGetCurrentContext() != EGL_NO_CONTEXT)
        eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

// The comparator's compatibility context, however it was made.
class CompatGl {
public:
    virtual ~CompatGl() = default;
    virtual void makeCurrent() = 0;  // throws strata::Error
    virtual void release() = 0;      // leaves no context current
    virtual std::string kind() const = 0;
    virtual bool glx() const = 0;  // false: GLEW's GLX part finds no display (see initGlew)
};

// A hidden 64 x 64 GLFW window's GL 2.1 context: GLX, so it needs an X display.
class GlxWindow final : public CompatGl {
public:
    GlxWindow() {
        if (!glfwInit()) throw Error("no GLX compatibility context (GLFW could not start: " + glfwWhy() + ")");
        // GLFW stays initialised, as strata::gpu::WindowContext leaves it: terminating
        // it would close windows that other code in the process opened.
        glfwDefaultWindowHints();
        glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
        // GL 2.1 without a profile: a compatibility context, for OpenCSG's fixed-function drawing.
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
        releaseEgl();  // GLFW makes the new context current while creating it
        window_.reset(glfwCreateWindow(64, 64, "strata-bench OpenCSG", nullptr, nullptr));
        if (!window_) throw Error("no GLX compatibility context (" + glfwWhy() + ")");
        glfwMakeContextCurrent(nullptr);
    }

    void makeCurrent() override {
        releaseEgl();
        glfwMakeContextCurrent(window_.get());
        if (glfwGetCurrentContext() != window_.get()) throw Error("cannot make the compatibility context current");
    }
    void release() override { glfwMakeContextCurrent(nullptr); }
    std::string kind() const override { return "GLX"; }
    bool glx() const override { return true; }

private:
    std::unique_ptr<GLFWwindow, decltype(&glfwDestroyWindow)> window_{nullptr, &glfwDestroyWindow};
};

// An EGL context with the compatibility profile and no surface
// (gpu::Context's, on the display strata's own context gets): the comparator
// draws into framebuffer objects only.
class EglCompat final : public CompatGl {
public:
    EglCompat() : context_(compatibilityOptions()) { context_.release(); }

    // The thread's EGL context, strata's included, is replaced.
    void makeCurrent() override { context_.makeCurrent(); }
    void release() override { context_.release(); }
    std::string kind() const override { return "EGL " + context_.platform(); }
    bool glx() const override { return false; }

private:
    static gpu::ContextOptions compatibilityOptions() {
        gpu::ContextOptions options;
        options.debug = false;
        options.compatibility = true;
        return options;
    }
    gpu::Context context_;
};

// GLEW for the current context. Debian's GLEW is built for GLX: glewInit()
// loads GL's entry points through glXGetProcAddressARB (glvnd's dispatch
// stubs, which call into whichever context is current, an EGL one too) and
// then initialises its GLX extensions, which fails with
// GLEW_ERROR_NO_GLX_DISPLAY where no GLX context is current. In an EGL
// context that one error is taken as success once the entry points the
// comparator and OpenCSG use are seen loaded: GLEW clears a version's or an
// extension's flag where one of its functions did not load.
void initGlew(bool glx) {
    const GLenum glew = glewInit();
    if (glew == GLEW_OK) return;
    if (!glx && glew == GLEW_ERROR_NO_GLX_DISPLAY) {
        if (GLEW_VERSION_1_5 && GLEW_VERSION_2_0 && GLEW_VERSION_2_1 && glGenFramebuffers != nullptr) return;
        throw Error("GLEW loaded no GL 2.1 entry points in the EGL compatibility context");
    }
    throw Error(std::string("GLEW failed in the compatibility context (") +
                reinterpret_cast<const char*>(glewGetErrorString(glew)) + ")");
}

// RAII names of the compatibility context; destroyed while it is current.
struct GlBuffer {
    GLuint id = 0;
    GlBuffer() { glGenBuffers(1, &id); }
    ~GlBuffer() { glDeleteBuffers(1, &id); }
    GlBuffer(const GlBuffer&) = delete;
    GlBuffer& operator=(const GlBuffer&) = delete;
};

struct GlRenderbuffer {
    GLuint id = 0;
    GlRenderbuffer() { glGenRenderbuffers(1, &id); }
    ~GlRenderbuffer() { glDeleteRenderbuffers(1, &id); }
    GlRenderbuffer(const GlRenderbuffer&) = delete;
    GlRenderbuffer& operator=(const GlRenderbuffer&) = delete;
};

struct GlFramebuffer {
    GLuint id = 0;
    GlFramebuffer() { glGenFramebuffers(1, &id); }
    ~GlFramebuffer() { glDeleteFramebuffers(1, &id); }
    GlFramebuffer(const GlFramebuffer&) = delete;
    GlFramebuffer& operator=(const GlFramebuffer&) = delete;
};

// One operand: a range of the shared vertex buffer, drawn with the
// fixed-function pipeline (OpenCSG takes its matrices from GL's stacks).
class MeshPrimitive final : public OpenCSG::Primitive {
public:
    MeshPrimitive(OpenCSG::Operation operation, GLuint buffer, GLint first, GLsizei count)
        : OpenCSG::Primitive(operation, 1), buffer_(buffer), first_(first), count_(count) {}

    void render() override {
        glBindBuffer(GL_ARRAY_BUFFER, buffer_);
        glEnableClientState(GL_VERTEX_ARRAY);
        glVertexPointer(3, GL_FLOAT, 0, nullptr);
        glDrawArrays(GL_TRIANGLES, first_, count_);
        // Unbound again: OpenCSG's own full-screen passes take their vertices
        // from client memory, which a bound GL_ARRAY_BUFFER turns into offsets
        // into ours (parts of intersections stayed; OpenCsgComparatorGLTest).
        glBindBuffer(GL_ARRAY_BUFFER, 0);
    }

private:
    GLuint buffer_;
    GLint first_;
    GLsizei count_;
};

// Screen bounding box in normalized device coordinates (min x y z, max x y
// z), as OpenCSG::Primitive::setBoundingBox wants; the whole screen when a
// vertex lies behind the eye.
std::array<float, 6> screenBounds(const float* xyz, std::size_t vertices, const glm::dmat4& viewProjection) {
    glm::dvec3 lo(1.0), hi(-1.0);
    bool first = true;
    for (std::size_t v = 0; v < vertices; ++v) {
        const glm::dvec4 clip = viewProjection * glm::dvec4(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], 1.0);
        if (clip.w <= 1e-9) return {-1, -1, -1, 1, 1, 1};
        const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
        lo = first ? ndc : glm::min(lo, ndc);
        hi = first ? ndc : glm::max(hi, ndc);
        first = false;
    }
    lo = glm::clamp(lo, -1.0, 1.0);
    hi = glm::clamp(hi, -1.0, 1.0);
    return {float(lo.x), float(lo.y), float(lo.z), float(hi.x), float(hi.y), float(hi.z)};
}

// One product's primitives, in OpenSCAD's order: intersected, then subtracted.
struct ProductList {
    std::vector<OpenCSG::Primitive*> all;  // what OpenCSG::render takes
    std::vector<OpenCSG::Primitive*> intersections, subtractions;
};

// What one setScene() made; replaced whole by the next.
struct Scene {
    int width = 0, height = 0;
    ViewMatrices matrices;
    GlBuffer vertices;
    GlRenderbuffer color, depthStencil;
    GlFramebuffer target;
    std::vector<std::unique_ptr<MeshPrimitive>> primitives;  // every product's, owned here
    std::vector<ProductList> products;
    unsigned maxConvexity = 1;
    std::size_t bytes = 0;
};

class Comparator final : public OpenCsgComparator {
public:
    explicit Comparator(std::unique_ptr<CompatGl> gl) : gl_(std::move(gl)) {
        gl_->makeCurrent();
        try {
            initGlew(gl_->glx());
            if (!GLEW_ARB_framebuffer_object) throw Error("the compatibility context lacks GL_ARB_framebuffer_object");
            if (!compatibilityProfile())
                throw Error(std::string("got no compatibility profile (OpenGL ") +
                            reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ")");
        } catch (...) {
            gl_->release();
            throw;
        }
        renderer_ = std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + ", " +
                    reinterpret_cast<const char*>(glGetString(GL_VERSION));
        gl_->release();
    }

    ~Comparator() override {
        // The scene's GL objects and OpenCSG's go while their context is current.
        try {
            gl_->makeCurrent();
        } catch (const Error&) {
            return;  // nothing to free them in; they go with the context
        }
        scene_.reset();
        OpenCSG::freeResources();
        gl_->release();
    }

    std::string renderer() const override { return renderer_; }
    std::string context() const override { return gl_->kind(); }

    void makeCurrent() override { gl_->makeCurrent(); }
    void release() override { gl_->release(); }

    void setScene(const CsgProducts& products, int width, int height, const ViewMatrices& matrices,
                  ConvexityMode mode) override {
        scene_.reset();
        auto scene = std::make_unique<Scene>();
        scene->width = width;
        scene->height = height;
        scene->matrices = matrices;

        // Each leaf's range of the one vertex buffer; leaves in no product have none.
        std::vector<GLint> first(products.leaves.size(), 0);
        std::vector<GLsizei> count(products.leaves.size(), 0);
        std::vector<float> all;
        for (std::size_t i = 0; i < products.leaves.size(); ++i) {
            const ProductLeaf& leaf = products.leaves[i];
            first[i] = GLint(all.size() / 3);
            count[i] = GLsizei(leaf.positions.size() / 3);
            all.insert(all.end(), leaf.positions.begin(), leaf.positions.end());
        }
        glBindBuffer(GL_ARRAY_BUFFER, scene->vertices.id);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(all.size() * sizeof(float)), all.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, 0);

        glBindRenderbuffer(GL_RENDERBUFFER, scene->color.id);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, scene->depthStencil.id);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, scene->target.id);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, scene->color.id);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                  scene->depthStencil.id);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("OpenCSG comparator: its target framebuffer is incomplete");

        // Per leaf, once: its convexity and its screen box.
        const glm::dmat4 viewProjection = matrices.projection * matrices.view;
        std::vector<unsigned> convexity(products.leaves.size(), 1);
        std::vector<std::array<float, 6>> box(products.leaves.size());
        for (std::size_t i = 0; i < products.leaves.size(); ++i) {
            if (count[i] == 0) continue;
            const ProductLeaf& leaf = products.leaves[i];
            MeshPrimitive probe(OpenCSG::Intersection, scene->vertices.id, first[i], count[i]);
            box[i] = screenBounds(leaf.positions.data(), std::size_t(count[i]), viewProjection);
            convexity[i] = mode == ConvexityMode::OpenScad ? std::max(1u, leaf.convexity)
                           : leaf.convex                   ? 1u
                                                           : measureConvexity(*scene, probe);
            scene->maxConvexity = std::max(scene->maxConvexity, convexity[i]);
        }
        auto add = [&](ProductList& list, int leafIndex, OpenCSG::Operation operation) {
            const std::size_t i = std::size_t(leafIndex);
            if (count[i] == 0) return;  // no triangles: OpenSCAD leaves a leaf without geometry out
            auto primitive = std::make_unique<MeshPrimitive>(operation, scene->vertices.id, first[i], count[i]);
            primitive->setConvexity(convexity[i]);
            const std::array<float, 6>& b = box[i];
            primitive->setBoundingBox(b[0], b[1], b[2], b[3], b[4], b[5]);
            (operation == OpenCSG::Intersection ? list.intersections : list.subtractions).push_back(primitive.get());
            list.all.push_back(primitive.get());
            scene->primitives.push_back(std::move(primitive));
        };
        for (const NormalizedProduct& product : products.sum.products) {
            ProductList list;
            for (int leaf : product.intersections) add(list, leaf, OpenCSG::Intersection);
            for (int leaf : product.subtractions) add(list, leaf, OpenCSG::Subtraction);
            if (!list.all.empty()) scene->products.push_back(std::move(list));
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        // Target and OpenCSG's offscreen buffer: RGBA8 + depth-stencil each.
        scene->bytes = all.size() * sizeof(float) + 2 * std::size_t(width) * std::size_t(height) * 8;
        checkGl("setScene");
        scene_ = std::move(scene);
    }

    double drawFrame(const OpenCsgSetting& setting) override {
        Scene& scene = requireScene();
        OpenCSG::setOption(OpenCSG::AlgorithmSetting,
                           setting.algorithm == CsgAlgorithm::Goldfeather ? OpenCSG::Goldfeather : OpenCSG::SCS);
        OpenCSG::setOption(OpenCSG::DepthComplexitySetting,
                           setting.depthComplexity == DepthComplexity::None ? OpenCSG::NoDepthComplexitySampling
                           : setting.depthComplexity == DepthComplexity::OcclusionQuery
                               ? OpenCSG::OcclusionQuery
                               : OpenCSG::DepthComplexitySampling);
        OpenCSG::setOption(OpenCSG::OffscreenSetting, OpenCSG::FrameBufferObject);
        loadMatrices(scene);

        const auto start = std::chrono::steady_clock::now();
        bindTarget(scene);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // black: coverage() reads any colour as covered
        glClearDepth(1.0);
        glClearStencil(0);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);  // OpenSCAD's between products
        for (const ProductList& product : scene.products) {
            if (product.all.size() > 1) {
                OpenCSG::render(product.all);
                checkGl("OpenCSG::render");
                // OpenCSG has merged the product's depth into the target's;
                // shade what matches it, as OpenSCAD does.
                bindTarget(scene);
                glEnable(GL_DEPTH_TEST);
                glDepthFunc(GL_EQUAL);
            }
            glColor3f(0.98f, 0.84f, 0.18f);
            for (OpenCSG::Primitive* primitive : product.intersections) primitive->render();
            // A subtracted primitive shows where it cut: its back faces only.
            glColor3f(0.62f, 0.81f, 0.39f);
            glEnable(GL_CULL_FACE);
            glCullFace(GL_FRONT);
            for (OpenCSG::Primitive* primitive : product.subtractions) primitive->render();
            glDisable(GL_CULL_FACE);
            glCullFace(GL_BACK);
            glDepthFunc(GL_LEQUAL);
        }
        glDepthFunc(GL_LESS);
        glFinish();
        return msSince(start);
    }

    std::vector<std::uint8_t> coverage() override {
        Scene& scene = requireScene();
        const std::size_t w = std::size_t(scene.width), h = std::size_t(scene.height);
        std::vector<std::uint8_t> rgba(w * h * 4);
        glBindFramebuffer(GL_FRAMEBUFFER, scene.target.id);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, scene.width, scene.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        checkGl("reading OpenCSG's image");
        std::vector<std::uint8_t> out(w * h);
        for (std::size_t y = 0; y < h; ++y)  // GL's rows are bottom first
            for (std::size_t x = 0; x < w; ++x) {
                const std::uint8_t* p = &rgba[((h - 1 - y) * w + x) * 4];
                out[y * w + x] = (p[0] | p[1] | p[2]) != 0;
            }
        return out;
    }

    unsigned maxConvexity() const override { return scene_ ? scene_->maxConvexity : 1; }
    std::size_t bufferBytes() const override { return scene_ ? scene_->bytes : 0; }

private:
    Scene& requireScene() {
        if (!scene_) throw Error("OpenCSG comparator: no scene set");
        return *scene_;
    }

    static void bindTarget(const Scene& scene) {
        glBindFramebuffer(GL_FRAMEBUFFER, scene.target.id);
        glViewport(0, 0, scene.width, scene.height);
    }

    static void loadMatrices(const Scene& scene) {
        glMatrixMode(GL_PROJECTION);
        glLoadMatrixd(glm::value_ptr(scene.matrices.projection));
        glMatrixMode(GL_MODELVIEW);
        glLoadMatrixd(glm::value_ptr(scene.matrices.view));
    }

    // The most front faces the primitive has on one pixel in this view:
    // counted with the stencil (back faces culled), read back, maximum taken.
    static unsigned measureConvexity(const Scene& scene, MeshPrimitive& primitive) {
        loadMatrices(scene);
        bindTarget(scene);
        glClearStencil(0);
        glStencilMask(0xff);
        glClear(GL_STENCIL_BUFFER_BIT);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, 0, 0xff);
        glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
        primitive.render();
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_CULL_FACE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        std::vector<std::uint8_t> counts(std::size_t(scene.width) * std::size_t(scene.height));
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, scene.width, scene.height, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, counts.data());
        checkGl("measuring a primitive's convexity");
        return std::max(1u, unsigned(*std::max_element(counts.begin(), counts.end())));
    }

    // Before 3.2 every context is a compatibility one; from 3.2 on GL says
    // which profile it is.
    static bool compatibilityProfile() {
        int major = 0, minor = 0;
        const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        if (version == nullptr || std::sscanf(version, "%d.%d", &major, &minor) != 2) return false;
        if (major < 3 || (major == 3 && minor < 2)) return true;
        GLint mask = 0;
        glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
        return (mask & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT) != 0;
    }

    std::unique_ptr<CompatGl> gl_;
    std::string renderer_;
    std::unique_ptr<Scene> scene_;
};

}  // namespace

const char* openCsgVersion() {
    return OPENCSG_VERSION_STRING;
}

std::unique_ptr<OpenCsgComparator> openOpenCsgComparator(CompatContext kind) {
    std::string glxWhy;
    if (kind != CompatContext::Egl) {
        try {
            return std::make_unique<Comparator>(std::make_unique<GlxWindow>());
        } catch (const Error& e) {
            if (kind == CompatContext::Glx) throw;
            glxWhy = e.what();
        }
    }
    try {
        return std::make_unique<Comparator>(std::make_unique<EglCompat>());
    } catch (const Error& e) {
        if (glxWhy.empty()) throw;
        throw Error(glxWhy + "; " + e.what());
    }
}

}  // namespace strata::bench
