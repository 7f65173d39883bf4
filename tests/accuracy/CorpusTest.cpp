// The accuracy corpus keeps its promises: at least 30 scenes, every
// family there, and the properties that make each scene hard for image-space
// CSG measured on the scenes themselves, not taken from generate.py's word:
// tree depth, n-ary fan-out, mirrored and sheared leaves, the depth complexity
// of imported meshes and of the operand each non-convex stack subtracts,
// cameras inside the model, and leaves that touch exactly in the coincident
// family.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "Manifest.h"
#include "strata/core/Error.h"
#include "strata/mesh/MeshImport.h"
#include "strata/model/Model.h"
#include "strata/reference/RayTriangle.h"
#include "strata/scene/CsgParser.h"

using namespace strata;
using accuracy::Shot;

namespace {

const std::string kDir = STRATA_TEST_DIR "/accuracy";

const std::vector<Shot>& shots() {
    static const std::vector<Shot> all = accuracy::loadManifest(kDir + "/scenes.txt");
    return all;
}

std::set<std::string> sceneFiles() {
    std::set<std::string> files;
    for (const Shot& s : shots()) files.insert(s.scene);
    return files;
}

scene::Tree parse(const std::string& file) { return scene::parseCsgFile(kDir + "/scenes/" + file); }

// Boolean nodes of two or more children on the longest path from the root
// (group() wrappers of one child do not count).
int booleanDepth(const scene::Tree& tree, int node) {
    const scene::Node& n = tree.nodes[static_cast<std::size_t>(node)];
    if (n.kind == scene::NodeKind::Leaf) return 0;
    int below = 0;
    for (int c : n.children) below = std::max(below, booleanDepth(tree, c));
    return below + (n.children.size() >= 2 ? 1 : 0);
}

// Number of crossings of the ray with the mesh after its start (t > 0).
int crossings(const mesh::Mesh& mesh, const camera::Ray& ray) {
    const reference::RayFrame frame(ray);
    int count = 0;
    for (const auto& t : mesh.triangles) {
        const auto hit = reference::crossTriangle(frame, mesh.positions[t[0]], mesh.positions[t[1]],
                                                  mesh.positions[t[2]]);
        if (hit && hit->t > 0.0) ++count;
    }
    return count;
}

// The most crossings of one ray with the mesh, over a grid of rays through its
// bounds along each axis and the four body diagonals.
int depthComplexity(const mesh::Mesh& mesh) {
    const mesh::Bounds b = mesh::boundsOf(mesh);
    const glm::dvec3 c = b.center();
    const double reach = b.diagonal();
    const glm::dvec3 directions[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-1, 1, 1}, {1, -1, 1}, {1, 1, -1}};
    int best = 0;
    constexpr int kGrid = 24;
    for (glm::dvec3 d : directions) {
        d = glm::normalize(d);
        const glm::dvec3 helper = std::abs(d.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        const glm::dvec3 u = glm::normalize(glm::cross(d, helper)), v = glm::cross(d, u);
        for (int i = 0; i < kGrid; ++i) {
            for (int j = 0; j < kGrid; ++j) {
                // Off the grid's round numbers, so no ray runs through an edge on purpose.
                const double s = ((i + 0.5137) / kGrid - 0.5) * reach, t = ((j + 0.4719) / kGrid - 0.5) * reach;
                best = std::max(best, crossings(mesh, {c - d * reach + u * s + v * t, d}));
            }
        }
    }
    return best;
}

// The most crossings of one leaf by one ray of a coarse grid over the shot's image.
int operandComplexityInView(const Shot& shot, const model::Model& model, int leaf) {
    camera::Camera coarse = shot.camera;
    coarse.width = 32;
    coarse.height = 32;
    int best = 0;
    for (int j = 0; j < coarse.height; ++j) {
        for (int i = 0; i < coarse.width; ++i) {
            best = std::max(best, crossings(model.leafMeshes[static_cast<std::size_t>(leaf)], coarse.ray(i, j)));
        }
    }
    return best;
}

}  // namespace

TEST(AccuracyCorpus, HasThirtyScenesOfOneToThreeSmallShotsEach) {
    ASSERT_FALSE(shots().empty());
    std::map<std::string, int> perScene;
    for (const Shot& s : shots()) {
        ++perScene[s.scene];
        EXPECT_GE(s.camera.width, 96) << s.name;
        EXPECT_LE(s.camera.width, 200) << s.name;
        EXPECT_GE(s.camera.height, 96) << s.name;
        EXPECT_LE(s.camera.height, 150) << s.name;
    }
    EXPECT_GE(perScene.size(), 30u);
    for (const auto& [scene, count] : perScene) {
        EXPECT_GE(count, 1) << scene;
        EXPECT_LE(count, 3) << scene;
    }
    std::set<std::string> names;
    for (const Shot& s : shots()) EXPECT_TRUE(names.insert(s.name).second) << "two shots named " << s.name;
}

TEST(AccuracyCorpus, EverySceneFileHasAShot) {
    const std::set<std::string> listed = sceneFiles();
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(kDir + "/scenes")) {
        if (entry.path().extension() != ".csg") continue;
        ++files;
        EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " is in no manifest line";
    }
    EXPECT_EQ(static_cast<std::size_t>(files), listed.size());
}

TEST(AccuracyCorpus, CoversEveryFamilyAndBothProjections) {
    std::set<std::string> families;
    bool perspective = false, orthographic = false;
    for (const Shot& s : shots()) {
        families.insert(s.family);
        (s.camera.projection == camera::Projection::Perspective ? perspective : orthographic) = true;
    }
    for (const char* f : {"stack", "deep", "nary", "nonconvex", "through", "thin", "near", "inside", "transform", "flat", "hull",
                          "coincident"}) {
        EXPECT_TRUE(families.count(f)) << "no scene of family " << f;
    }
    EXPECT_TRUE(perspective);
    EXPECT_TRUE(orthographic);
}

TEST(AccuracyCorpus, EverySceneParsesCleanlyIntoClosedLeaves) {
    for (const std::string& file : sceneFiles()) {
        SCOPED_TRACE(file);
        scene::Tree tree;
        ASSERT_NO_THROW(tree = parse(file));
        EXPECT_TRUE(tree.warnings.empty()) << (tree.warnings.empty() ? "" : tree.warnings.front().message);
        EXPECT_TRUE(tree.unsupported.empty());
        EXPECT_FALSE(tree.leaves.empty());
        model::Model model;
        ASSERT_NO_THROW(model = model::buildModel(tree));
        EXPECT_FALSE(model.bounds.empty());
        for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
            EXPECT_FALSE(model.leafMeshes[i].triangles.empty()) << "leaf " << i << " is empty";
        }
    }
}

TEST(AccuracyCorpus, HasDeepTreesAndNaryNodesOfFiftyOperands) {
    int deepest = 0;
    std::size_t widest[4] = {0, 0, 0, 0};  // by NodeKind
    for (const std::string& file : sceneFiles()) {
        const scene::Tree tree = parse(file);
        std::set<scene::NodeKind> kinds;
        for (const scene::Node& n : tree.nodes) {
            if (n.kind != scene::NodeKind::Leaf && n.children.size() >= 2) kinds.insert(n.kind);
            widest[static_cast<int>(n.kind)] = std::max(widest[static_cast<int>(n.kind)], n.children.size());
        }
        if (kinds.size() == 3) deepest = std::max(deepest, booleanDepth(tree, tree.root));
    }
    EXPECT_GE(deepest, 8) << "no tree of depth >= 8 mixing all three operations";
    EXPECT_GE(widest[static_cast<int>(scene::NodeKind::Union)], 50u);
    EXPECT_GE(widest[static_cast<int>(scene::NodeKind::Intersection)], 50u);
    EXPECT_GE(widest[static_cast<int>(scene::NodeKind::Difference)], 50u);
}

TEST(AccuracyCorpus, HasMirroredAndShearedLeaves) {
    int mirrored = 0, sheared = 0;
    for (const std::string& file : sceneFiles()) {
        const scene::Tree tree = parse(file);
        for (const scene::Leaf& leaf : tree.leaves) {
            const glm::dmat3 m(leaf.transform);
            if (glm::determinant(m) < 0.0) ++mirrored;
            const double c01 = glm::dot(m[0], m[1]), c02 = glm::dot(m[0], m[2]), c12 = glm::dot(m[1], m[2]);
            if (std::max({std::abs(c01), std::abs(c02), std::abs(c12)}) > 1e-3) ++sheared;
        }
    }
    EXPECT_GE(mirrored, 3);
    EXPECT_GE(sheared, 3);
}

TEST(AccuracyCorpus, ImportedMeshesHaveDepthComplexityOfSixOrMore) {
    const std::string meshes[] = {kDir + "/meshes/comb.stl", kDir + "/meshes/coil.off",
                                  std::string(STRATA_TEST_DIR) + "/../examples/meshes/twisted_star.stl"};
    for (const std::string& path : meshes) {
        SCOPED_TRACE(path);
        const mesh::Mesh mesh = mesh::importMesh(path);
        EXPECT_GE(depthComplexity(mesh), 6);
    }
}

// What makes a stack non-convex: ONE operand that a ray of the shot crosses
// four times or more, so one dual-peel pass (its nearest and farthest layer)
// cannot hold it.
TEST(AccuracyCorpus, NonConvexStacksHaveAnOperandCrossedFourTimesInView) {
    std::set<std::string> flaggedScenes;
    for (const Shot& shot : shots()) {
        if (!shot.has("nonconvex-stack")) continue;
        SCOPED_TRACE(shot.name);
        flaggedScenes.insert(shot.scene);
        const scene::Tree tree = parse(shot.scene);
        const model::Model model = model::buildModel(tree);
        int best = 0;
        for (std::size_t leaf = 0; leaf < tree.leaves.size(); ++leaf) {
            best = std::max(best, operandComplexityInView(shot, model, static_cast<int>(leaf)));
        }
        EXPECT_GE(best, 4);
    }
    EXPECT_GE(flaggedScenes.size(), 4u);
}

TEST(AccuracyCorpus, StackScenesHaveACameraStraightAlongTheStack) {
    std::map<std::string, bool> straight;
    for (const Shot& s : shots()) {
        if (s.family != "stack") continue;
        const glm::dvec3 f = s.camera.forward();
        const double axis = std::max({std::abs(f.x), std::abs(f.y), std::abs(f.z)});
        straight[s.scene] = straight[s.scene] || axis > 1.0 - 1e-12;
    }
    EXPECT_GE(straight.size(), 8u);
    for (const auto& [scene, ok] : straight) EXPECT_TRUE(ok) << scene;
}

// The 'inside' scenes put the eye (perspective) inside the model's bounds, or
// the orthographic ray origins' plane through them.
TEST(AccuracyCorpus, InsideShotsStartRaysInsideTheModel) {
    int count = 0;
    for (const Shot& shot : shots()) {
        if (shot.family != "inside") continue;
        SCOPED_TRACE(shot.name);
        ++count;
        const model::Model model = model::buildModel(parse(shot.scene));
        const mesh::Bounds& b = model.bounds;
        if (shot.camera.projection == camera::Projection::Perspective) {
            const glm::dvec3 e = shot.camera.eye;
            EXPECT_TRUE(e.x > b.min.x && e.x < b.max.x && e.y > b.min.y && e.y < b.max.y && e.z > b.min.z &&
                        e.z < b.max.z);
        } else {
            double lo = 1e300, hi = -1e300;
            for (int k = 0; k < 8; ++k) {
                const glm::dvec3 c{(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                   (k & 4) ? b.max.z : b.min.z};
                lo = std::min(lo, shot.camera.viewDepth(c));
                hi = std::max(hi, shot.camera.viewDepth(c));
            }
            EXPECT_LT(lo, 0.0);
            EXPECT_GT(hi, 0.0);
        }
    }
    EXPECT_GE(count, 4);
}

// The coincident family's scenes coincide: a vertex of one leaf lies on a
// triangle of another, in its plane within rounding (1e-9 of the scene's
// size; turned copies of one plane lie a rounding apart). That holds for
// faces in one plane, shared faces, identical solids and a ring of vertices
// in a face; the near family's faces, 1e-3 apart, do not count.
bool leavesTouch(const model::Model& model) {
    const double tolerance = 1e-9 * model.bounds.diagonal();
    for (std::size_t a = 0; a < model.leafMeshes.size(); ++a) {
        for (std::size_t b = 0; b < model.leafMeshes.size(); ++b) {
            if (a == b) continue;
            const mesh::Mesh& on = model.leafMeshes[b];
            for (const glm::dvec3& p : model.leafMeshes[a].positions) {
                for (const auto& t : on.triangles) {
                    const glm::dvec3 p0 = on.positions[t[0]], p1 = on.positions[t[1]], p2 = on.positions[t[2]];
                    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
                    const double area2 = glm::length(n);
                    if (!(area2 > 0.0)) continue;
                    if (std::abs(glm::dot(p - p0, n)) / area2 > tolerance) continue;
                    // Inside (or on) the triangle: the sub-triangles' areas, signed along n.
                    const double u = glm::dot(glm::cross(p1 - p, p2 - p), n) / (area2 * area2);
                    const double v = glm::dot(glm::cross(p2 - p, p0 - p), n) / (area2 * area2);
                    const double w = 1.0 - u - v;
                    if (u >= -1e-9 && v >= -1e-9 && w >= -1e-9) return true;
                }
            }
        }
    }
    return false;
}

TEST(AccuracyCorpus, CoincidentScenesHaveLeavesThatTouchExactly) {
    int scenes = 0;
    for (const std::string& file : sceneFiles()) {
        const auto shot = std::find_if(shots().begin(), shots().end(), [&](const Shot& s) { return s.scene == file; });
        if (shot->family != "coincident" && shot->family != "near") continue;
        SCOPED_TRACE(file);
        const model::Model model = model::buildModel(parse(file));
        if (shot->family == "near") {
            EXPECT_FALSE(leavesTouch(model)) << "the near family's faces lie 1e-3 of the size apart, never closer";
            continue;
        }
        ++scenes;
        EXPECT_TRUE(leavesTouch(model));
    }
    EXPECT_GE(scenes, 20);
}

TEST(AccuracyManifest, NamesTheLineAndColumnOfAMistake) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "strata_accuracy_manifest_test.txt";
    auto expectError = [&](const std::string& text, const std::string& where) {
        {
            std::ofstream out(path);
            out << "# comment\n\nok.csg stack p 96x96 0,0,10,0,0,0\n" << text << "\n";
        }
        try {
            accuracy::loadManifest(path.string());
            ADD_FAILURE() << "no error for: " << text;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path.string() + ":" + where + ": ", 0), 0u) << e.what();
        }
    };
    expectError("a.csg stack x 96x96 0,0,10,0,0,0", "4:13");
    expectError("a.csg stack p 96x 0,0,10,0,0,0", "4:15");
    expectError("a.csg stack p 96x96 0,0,10,0,0", "4:21");
    expectError("a.csg stack p 96x96 0,0,10,0,0,nan", "4:21");
    expectError("a.csg stack p 96x96 0,0,0,0,0,0", "4:21");
    expectError("a.csg stack p 96x96 0,0,10,0,0,0 fov=0", "4:34");
    expectError("a.csg stack p", "4:13");
    std::filesystem::remove(path);
}

TEST(AccuracyManifest, ReadsCamerasOptionsAndFlags) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "strata_accuracy_manifest_ok.txt";
    {
        std::ofstream out(path);
        out << "sub/a-b.csg stack o 100x120 1,2,3,4,5,6 fov=30 nonconvex-stack  # note\n"
            << "sub/a-b.csg stack p 96x96 0,0,10,0,0,0\n";
    }
    const std::vector<Shot> s = accuracy::loadManifest(path.string());
    std::filesystem::remove(path);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].scene, "sub/a-b.csg");
    EXPECT_EQ(s[0].name, "a_b_o0");
    EXPECT_EQ(s[1].name, "a_b_p1");
    EXPECT_EQ(s[0].camera.projection, camera::Projection::Orthographic);
    EXPECT_EQ(s[0].camera.width, 100);
    EXPECT_EQ(s[0].camera.height, 120);
    EXPECT_EQ(s[0].camera.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(s[0].camera.center, glm::dvec3(4, 5, 6));
    EXPECT_EQ(s[0].camera.fovDegrees, 30.0);
    EXPECT_EQ(s[1].camera.fovDegrees, 22.5);
    EXPECT_TRUE(s[0].has("nonconvex-stack"));
    EXPECT_FALSE(s[1].has("nonconvex-stack"));
    EXPECT_EQ(s[0].line, 1);
}
