#pragma once
// OpenCSG (Goldfeather and SCS) drawing a scene's sum of products
// (CsgProduct.h), as OpenSCAD 2021.01's preview does, for the bench to time
// against strata in the same process.
//
// OpenCSG reaches GL through GLEW, which Debian builds for GLX, and draws
// with the fixed-function pipeline: it needs a compatibility context. So the
// comparator owns one of its own, next to strata's EGL 4.5 core context: a
// hidden GLFW window's GLX context where an X display is there, else an EGL
// compatibility context without a surface (drawing into framebuffer objects
// only), on the display strata's context uses. glvnd lets a thread have one
// current context of one API at a time, so makeCurrent() first releases the
// thread's EGL context; the caller makes strata's current again after
// release(). GLEW and GL headers stay inside OpenCsgComparator.cpp: this
// header includes none.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "CsgProduct.h"
#include "ViewMatrices.h"

namespace strata::bench {

enum class CsgAlgorithm { Goldfeather, Scs };
// OpenCSG's DepthComplexitySetting: none, occlusion queries ("oq") or
// depth complexity sampling ("dcs").
enum class DepthComplexity { None, OcclusionQuery, Sampling };

struct OpenCsgSetting {
    CsgAlgorithm algorithm = CsgAlgorithm::Goldfeather;
    DepthComplexity depthComplexity = DepthComplexity::None;
    // "goldfeather", "goldfeather-oq", "goldfeather-dcs", "scs", "scs-oq", "scs-dcs"
    std::string name() const;
};

// Every setting the bench times, in that order.
const std::vector<OpenCsgSetting>& openCsgSettings();

// Where each primitive's convexity (OpenCSG's bound on its front faces on
// one pixel) comes from.
enum class ConvexityMode {
    OpenScad,  // what OpenSCAD passes: ProductLeaf::convexity (the file's, else 1)
    Measured,  // counted in this view for each non-convex leaf: always enough, never more
};

class OpenCsgComparator {
public:
    virtual ~OpenCsgComparator() = default;

    virtual std::string renderer() const = 0;  // "GL_RENDERER, GL_VERSION" of the compatibility context
    virtual std::string context() const = 0;   // what made it: "GLX", "EGL surfaceless", "EGL device", ...
    virtual void makeCurrent() = 0;            // releases the thread's EGL context first
    virtual void release() = 0;                // leaves no context current

    // Needs makeCurrent(). Uploads the leaves in any product into one vertex
    // buffer (each once), makes a width x height target (RGBA8, depth 24 +
    // stencil 8), sets each primitive's screen bounding box from its vertices
    // through `matrices`, and gives each its convexity by `mode`. Throws
    // strata::Error on a GL error.
    virtual void setScene(const CsgProducts& products, int width, int height, const ViewMatrices& matrices,
                          ConvexityMode mode) = 0;

    // One frame as OpenSCAD's OpenCSGRenderer draws one: clear, then for each
    // product in turn, OpenCSG::render() of its primitives with `setting`
    // (offscreen type: frame buffer object) where it has more than one, and
    // its intersected primitives shaded with glDepthFunc(GL_EQUAL), its
    // subtracted ones' back faces too; a product of one primitive is drawn
    // plainly with GL_LEQUAL. All products share the colour and depth buffer,
    // so they merge by depth. glFinish. Returns wall-clock milliseconds.
    virtual double drawFrame(const OpenCsgSetting& setting) = 0;

    // Reads the last frame's colour: 1 where a product covers the pixel,
    // rows top first (as strata's Frame). Throws strata::Error on a GL error.
    virtual std::vector<std::uint8_t> coverage() = 0;

    virtual unsigned maxConvexity() const = 0;  // over the scene's primitives
    // GPU memory the scene takes: vertex buffer, target, and OpenCSG's own
    // offscreen buffer (RGBA8 + depth-stencil, assumed the target's size).
    virtual std::size_t bufferBytes() const = 0;
};

// "OpenCSG 1.5.0": the version the comparator was built against.
const char* openCsgVersion();

// Which compatibility context the comparator makes.
enum class CompatContext {
    Auto,  // GLX where GLFW can open a window (an X display), else EGL
    Glx,   // a hidden GLFW window's GLX context only
    Egl,   // an EGL compatibility context only, also where a display is there
};

// Opens the comparator and leaves no context current. Throws strata::Error
// saying why it is unavailable: built without OpenCSG, no compatibility
// context of the kind asked for (or of either, for Auto), GLEW failed.
std::unique_ptr<OpenCsgComparator> openOpenCsgComparator(CompatContext kind = CompatContext::Auto);

}  // namespace strata::bench
