// The host program of docs/embedding.md, which quotes it: keep the two in sync.
//
// A host that has its own meshes and its own view and projection matrices
// hands them to strata, gets back the shaded colour, the depth, the normal and
// the leaf (operand) id of every pixel, and has strata draw into a
// framebuffer of its own. It uses only strata's public headers and libraries.
// It checks what it gets against closed forms it works out itself, and exits
// non-zero if anything is wrong: the test `EmbeddingExample` runs it.
//
//   strata-embedding-example [OUTPUT_DIR]   # OUTPUT_DIR: also save the image as PNG
//
// The scene: the host's unit cube [-1,1]^3 minus the host's pocket box
// [-0.5,0.5]^2 x [0,2], which cuts a square pocket 1 deep into the top face,
// seen from above and aside:
//
//          eye (1,-2,6), looking at the origin
//             .
//     _________.______ z = 1    top face of the cube (leaf 0)
//    |     |    .|    |
//    |     |_____o    | z = 0    pocket floor: the pocket's bottom face (leaf 1),
//    |                |          its normal flipped to point up, out of the result
//    |________________| z = -1

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "strata/camera/Camera.h"
#include "strata/core/Error.h"
#include "strata/gpu/Context.h"
#include "strata/gpu/Gl.h"
#include "strata/io/ImageWriter.h"
#include "strata/model/Model.h"
#include "strata/render/Renderer.h"
#include "strata/scene/Tree.h"

using namespace strata;

namespace {

// --- The host's own data -------------------------------------------------

// A closed triangle mesh as a host engine keeps it: triangles counter-
// clockwise seen from outside (OpenGL's and glTF's front faces).
struct HostMesh {
    std::vector<glm::dvec3> points;
    std::vector<std::array<int, 3>> triangles;
};

HostMesh box(glm::dvec3 lo, glm::dvec3 hi) {
    HostMesh m;
    for (int k = 0; k < 8; ++k) {
        m.points.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    }
    // Two counter-clockwise triangles per face (corner k has bit 0 = x, 1 = y, 2 = z).
    m.triangles = {{0, 2, 3}, {0, 3, 1},   // z = lo, normal -z
                   {4, 5, 7}, {4, 7, 6},   // z = hi, normal +z
                   {0, 1, 5}, {0, 5, 4},   // y = lo, normal -y
                   {2, 6, 7}, {2, 7, 3},   // y = hi, normal +y
                   {0, 4, 6}, {0, 6, 2},   // x = lo, normal -x
                   {1, 3, 7}, {1, 7, 5}};  // x = hi, normal +x
    return m;
}

// --- Meshes into strata ----------------------------------------------------

// A leaf made of the host's mesh. strata's Polyhedron is OpenSCAD's, whose
// faces run clockwise seen from outside, so each triangle is reversed.
// model::buildModel checks that the mesh is closed and consistently
// oriented, and throws a strata::Error saying what is wrong if not.
scene::Leaf leafFromHostMesh(const HostMesh& mesh, std::optional<glm::dvec4> color = std::nullopt) {
    scene::Polyhedron poly;
    poly.points = mesh.points;
    for (const auto& t : mesh.triangles) poly.faces.push_back({t[2], t[1], t[0]});
    scene::Leaf leaf;
    leaf.primitive = std::move(poly);
    leaf.color = color;  // none: the colour scheme's face colours
    return leaf;
}

// --- Matrices into a strata camera -------------------------------------------

// strata's Camera is OpenSCAD's: eye, center, vertical field of view, Z up
// (strata/camera/Camera.h). This turns a host's lookAt-style view matrix (world
// to eye space, the eye looking down its -Z) and a symmetric perspective or
// orthographic projection, OpenGL style (glm::perspective / glm::ortho), into
// one. Throws strata::Error for what such a camera cannot express: a roll (an
// up vector out of the plane of the view direction and world Z), an
// off-centre frustum, or an aspect ratio other than width / height.
camera::Camera cameraFromMatrices(const glm::dmat4& view, const glm::dmat4& projection, int width, int height) {
    camera::Camera camera;
    camera.width = width;
    camera.height = height;
    // The eye is where eye space's origin lands in the world.
    camera.eye = glm::dvec3(glm::inverse(view) * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    // The rows of the view's rotation are the eye's axes in world space; it
    // looks down the third one, negated. (glm is column-major: m[column][row].)
    const glm::dvec3 forward = -glm::normalize(glm::dvec3(view[0][2], view[1][2], view[2][2]));
    const glm::dvec3 up = glm::normalize(glm::dvec3(view[0][1], view[1][1], view[2][1]));

    const bool perspective = projection[2][3] == -1.0 && projection[3][3] == 0.0;
    const bool orthographic = projection[2][3] == 0.0 && projection[3][3] == 1.0;
    if (!perspective && !orthographic) throw Error("camera: not a perspective or orthographic projection");
    const bool offCentre = perspective ? (projection[2][0] != 0.0 || projection[2][1] != 0.0)
                                       : (projection[3][0] != 0.0 || projection[3][1] != 0.0);
    if (offCentre) throw Error("camera: an off-centre frustum has no strata camera");
    const double aspect = projection[1][1] / projection[0][0];
    if (std::abs(aspect - double(width) / double(height)) > 1e-6 * aspect) {
        throw Error("camera: the projection's aspect ratio is not width / height");
    }

    if (perspective) {
        // projection[1][1] = 1 / tan(fov / 2); how far away `center` is does not matter.
        camera.projection = camera::Projection::Perspective;
        camera.fovDegrees = glm::degrees(2.0 * std::atan(1.0 / projection[1][1]));
        camera.center = camera.eye + forward;
    } else {
        // projection[1][1] = 1 / h, h the half height of the view; the contract's
        // orthographic camera has h = |center - eye| * tan(fov / 2), so keep the
        // default fov and put `center` at the distance that gives h.
        camera.projection = camera::Projection::Orthographic;
        const double halfHeight = 1.0 / projection[1][1];
        const double distance = halfHeight / std::tan(glm::radians(camera.fovDegrees) / 2.0);
        camera.center = camera.eye + forward * distance;
    }
    // strata derives "up" from world Z; the host's up must be the same vector.
    if (glm::dot(camera.up(), up) < 1.0 - 1e-9) {
        throw Error("camera: the view is rolled; strata's camera keeps world Z up");
    }
    return camera;
}

// The host's own depth-buffer value for a view depth that strata returns:
// where the host's projection puts that point, with OpenGL's default clip
// depth (-1..1, no glClipControl) and glDepthRange(0, 1). For compositing
// strata's image with the host's own drawing.
double hostWindowDepth(const glm::dmat4& projection, double viewDepth) {
    const glm::dvec4 clip = projection * glm::dvec4(0.0, 0.0, -viewDepth, 1.0);
    return 0.5 * clip.z / clip.w + 0.5;
}

// --- Checks against closed forms --------------------------------------------

int failures = 0;

void expect(bool ok, const std::string& what) {
    if (ok) return;
    if (++failures <= 20) std::fprintf(stderr, "FAILED: %s\n", what.c_str());
}

bool near(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance; }

struct HostRay {
    glm::dvec3 origin, direction;
};

// The ray through pixel (i, j) (row j from the top, at the pixel centre), by
// unprojecting with the host's own matrices: nothing of strata's camera code.
HostRay hostRay(const glm::dmat4& view, const glm::dmat4& projection, int width, int height, int i, int j) {
    const glm::dmat4 toWorld = glm::inverse(projection * view);
    const double x = 2.0 * (i + 0.5) / width - 1.0;
    const double y = 1.0 - 2.0 * (j + 0.5) / height;
    const glm::dvec4 a = toWorld * glm::dvec4(x, y, -1.0, 1.0);
    const glm::dvec4 b = toWorld * glm::dvec4(x, y, 1.0, 1.0);
    const glm::dvec3 origin = glm::dvec3(a) / a.w;
    return {origin, glm::normalize(glm::dvec3(b) / b.w - origin)};
}

// Checks every pixel whose answer follows from the geometry alone.
void checkFrame(const render::Frame& frame, const glm::dmat4& view, const glm::dmat4& projection, int cubeLeaf,
                int pocketLeaf, const char* label) {
    const glm::dvec3 eye = glm::dvec3(glm::inverse(view) * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const glm::dvec3 forward = -glm::normalize(glm::dvec3(view[0][2], view[1][2], view[2][2]));
    const double tolerance = 1e-4 * std::sqrt(12.0);  // 1e-4 of the cube's diagonal
    const double margin = 0.02;                       // keep clear of edges
    int top = 0, floor = 0, miss = 0;
    for (int j = 0; j < frame.height; ++j) {
        for (int i = 0; i < frame.width; ++i) {
            const std::size_t p = static_cast<std::size_t>(j) * frame.width + i;
            const HostRay ray = hostRay(view, projection, frame.width, frame.height, i, j);
            const auto at = [&](double z) {
                return ray.origin + ray.direction * ((z - ray.origin.z) / ray.direction.z);
            };
            const glm::dvec3 onTop = at(1.0), onFloor = at(0.0);
            const double topReach = std::max(std::abs(onTop.x), std::abs(onTop.y));
            const double floorReach = std::max(std::abs(onFloor.x), std::abs(onFloor.y));
            // Distance of the ray's line from the origin: beyond sqrt(3) it misses the cube.
            const double offAxis = glm::length(glm::cross(-ray.origin, ray.direction));
            const std::string where =
                std::string(label) + " pixel (" + std::to_string(i) + "," + std::to_string(j) + ")";
            if (topReach > 0.5 + margin && topReach < 1.0 - margin) {
                ++top;  // the top face, outside the pocket
                expect(near(frame.depth[p], glm::dot(onTop - eye, forward), tolerance), where + ": top face depth");
                expect(frame.leaf[p] == cubeLeaf, where + ": top face leaf");
                expect(glm::length(frame.normal[p] - glm::vec3(0, 0, 1)) < 1e-4f, where + ": top face normal");
            } else if (topReach < 0.5 - margin && floorReach < 0.5 - margin) {
                ++floor;  // down the pocket onto its floor, clear of its walls
                expect(near(frame.depth[p], glm::dot(onFloor - eye, forward), tolerance), where + ": floor depth");
                expect(frame.leaf[p] == pocketLeaf, where + ": floor leaf");
                expect(glm::length(frame.normal[p] - glm::vec3(0, 0, 1)) < 1e-4f, where + ": floor normal");
            } else if (offAxis > std::sqrt(3.0) + margin) {
                ++miss;
                expect(std::isinf(frame.depth[p]) && frame.leaf[p] == -1 && frame.normal[p] == glm::vec3(0.0f),
                       where + ": a miss");
            }
        }
    }
    std::printf("%s: checked %d top-face, %d pocket-floor and %d empty pixels\n", label, top, floor, miss);
    expect(top > 500 && floor > 100 && miss > 1000, std::string(label) + ": too few pixels checked");
}

}  // namespace

int main(int argc, char** argv) {
    try {
        // 1. A current OpenGL 4.5 core context. Headless here; a windowed host
        //    makes its own (GLFW, SDL, Qt) current instead: strata reaches GL
        //    through libepoxy, which resolves against whatever context is current.
        //    The context must outlive the renderer: made first, destroyed last.
        gpu::Context context;

        // 2. The scene: the host's meshes as leaves of a CSG tree built in code.
        //    addLeaf returns a NODE index; the frame's leaf ids index tree.leaves.
        scene::Tree tree;
        const int cubeNode = tree.addLeaf(leafFromHostMesh(box({-1, -1, -1}, {1, 1, 1})));
        const int pocketNode = tree.addLeaf(leafFromHostMesh(box({-0.5, -0.5, 0.0}, {0.5, 0.5, 2.0})));
        tree.root = tree.addNode(scene::NodeKind::Difference, {cubeNode, pocketNode});
        const int cubeLeaf = tree.nodes[static_cast<std::size_t>(cubeNode)].leaf;
        const int pocketLeaf = tree.nodes[static_cast<std::size_t>(pocketNode)].leaf;

        // 3. The meshes, checked, and uploaded with the compiled tree. Call
        //    setScene again after editing the tree.
        const model::Model model = model::buildModel(tree);
        render::Renderer renderer;
        renderer.setScene(tree, model);

        // 4. The host's camera matrices, turned into strata's camera.
        const int width = 161, height = 121;  // odd: the centre pixel's ray is the view axis
        const glm::dvec3 eye(1.0, -2.0, 6.0);
        const glm::dmat4 view = glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0));
        const glm::dmat4 projection = glm::perspective(glm::radians(40.0), double(width) / height, 0.1, 100.0);
        const camera::Camera camera = cameraFromMatrices(view, projection, width, height);

        // A rolled view has no strata camera: the helper refuses it.
        bool refused = false;
        try {
            const glm::dmat4 rolled = glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0));
            cameraFromMatrices(rolled, projection, width, height);
        } catch (const Error&) {
            refused = true;
        }
        expect(refused, "a rolled view is refused");

        // 5. Render and read everything back: rows top first.
        render::RenderSettings settings;  // auto layers, Cornfield, 512 MiB budget
        const render::Frame frame = renderer.render(camera, settings);
        const std::size_t centre = static_cast<std::size_t>(height / 2) * width + width / 2;
        std::printf("centre pixel: rgba %d %d %d %d, depth %.6f, leaf %d, normal (%g, %g, %g)\n",
                    frame.rgba[centre * 4], frame.rgba[centre * 4 + 1], frame.rgba[centre * 4 + 2],
                    frame.rgba[centre * 4 + 3], frame.depth[centre], frame.leaf[centre], frame.normal[centre].x,
                    frame.normal[centre].y, frame.normal[centre].z);
        std::printf("frame: %.2f ms (peel %.2f, evaluate %.2f, shade %.2f), %zu pixels covered\n",
                    frame.stats.totalMs, frame.stats.peelMs, frame.stats.evaluateMs, frame.stats.shadeMs,
                    frame.stats.coveredPixels);

        // The centre ray runs from the eye to the origin, the middle of the
        // pocket floor: its depth is |eye| = sqrt(41), and the floor is the
        // pocket's bottom face (normal -z) seen from the pocket, flipped: +z.
        expect(near(frame.depth[centre], std::sqrt(41.0), 1e-4), "centre depth is sqrt(41)");
        expect(frame.leaf[centre] == pocketLeaf, "centre leaf is the pocket");
        expect(glm::length(frame.normal[centre] - glm::vec3(0.0f, 0.0f, 1.0f)) < 1e-4f, "centre normal is +z");
        checkFrame(frame, view, projection, cubeLeaf, pocketLeaf, "perspective");
        // The host's depth buffer would hold, for the centre: a perspective
        // projection's window depth (1/d - 1/n) / (1/f - 1/n), n = 0.1, f = 100.
        const double d = frame.depth[centre];
        expect(near(hostWindowDepth(projection, d), (1.0 / d - 10.0) / (0.01 - 10.0), 1e-9), "host window depth");

        // The same from an orthographic host projection.
        const glm::dmat4 ortho = glm::ortho(-2.0 * width / height, 2.0 * width / height, -2.0, 2.0, 0.1, 100.0);
        const render::Frame flat = renderer.render(cameraFromMatrices(view, ortho, width, height), settings);
        expect(near(flat.depth[centre], std::sqrt(41.0), 1e-4), "orthographic centre depth is sqrt(41)");
        checkFrame(flat, view, ortho, cubeLeaf, pocketLeaf, "orthographic");

        // 6. Draw into the host's own framebuffer: a colour texture larger than
        //    the image, cleared to the host's colour; strata's image lands with
        //    its lower-left corner at (x, y).
        const int hostWidth = width + 40, hostHeight = height + 30, x = 25, y = 10;
        GLuint texture = 0, framebuffer = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA8, hostWidth, hostHeight);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
        const float hostColor[4] = {0.2f, 0.4f, 0.6f, 1.0f};
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, hostColor);
        const render::FrameStats stats = renderer.renderInto(framebuffer, x, y, camera, settings);
        // strata changed GL state (see Renderer.h): a host resets what it relies on.
        std::printf("renderInto: %.2f ms\n", stats.totalMs);

        std::vector<std::uint8_t> pixels(static_cast<std::size_t>(hostWidth) * hostHeight * 4);
        glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
        int inside = 0, outside = 0;
        for (int row = 0; row < hostHeight; ++row) {  // GL rows count from the bottom
            for (int col = 0; col < hostWidth; ++col) {
                const std::uint8_t* got = &pixels[(static_cast<std::size_t>(row) * hostWidth + col) * 4];
                const int i = col - x, j = height - 1 - (row - y);  // the frame's pixel, rows top first
                if (i >= 0 && i < width && j >= 0 && j < height) {
                    const std::uint8_t* want = &frame.rgba[(static_cast<std::size_t>(j) * width + i) * 4];
                    inside += got[0] == want[0] && got[1] == want[1] && got[2] == want[2] && got[3] == want[3];
                } else {
                    outside += got[0] == 51 && got[1] == 102 && got[2] == 153 && got[3] == 255;
                }
            }
        }
        expect(inside == width * height, "renderInto: the host framebuffer holds render()'s image");
        expect(outside == hostWidth * hostHeight - width * height, "renderInto: the rest keeps the host's colour");
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(1, &texture);

        if (argc > 1) {
            std::filesystem::create_directories(argv[1]);
            io::writePng((std::filesystem::path(argv[1]) / "embedding.png").string(), width, height, frame.rgba);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strata-embedding-example: %s\n", e.what());
        return 1;
    }
    if (failures != 0) {
        std::fprintf(stderr, "strata-embedding-example: %d check(s) failed\n", failures);
        return 1;
    }
    std::printf("strata-embedding-example: all checks passed\n");
    return 0;
}
