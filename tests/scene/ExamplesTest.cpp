// OpenSCAD's own shipped examples, exported by OpenSCAD 2021.01 (and a few by its
// development version), read end to end: parse, tessellate, bound.
//
// Every expected figure below comes from tests/data/openscad/facts.py, which never
// calls strata: leaf counts and left-out nodes from the .csg text, bounds from
// OpenSCAD's own exact evaluation (`openscad -o x.stl`) of the same .csg. See
// tests/data/openscad/README.md for the files.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "strata/model/Model.h"
#include "strata/scene/CsgParser.h"

using namespace strata;

namespace {

struct Box {
    glm::dvec3 min;
    glm::dvec3 max;
};

// One node type strata leaves out: how many outermost nodes of it, and the line
// of the first (where its one warning points).
struct LeftOut {
    const char* name;
    int count;
    int firstLine;
};

struct Example {
    const char* file;        // in tests/data/openscad/
    int leaves;              // primitives outside left-out subtrees
    int background;          // of which under '%'
    std::vector<LeftOut> leftOut;
    // Bounds of all kept leaves: OpenSCAD's bbox of the file with left-out
    // subtrees cut and every difference/intersection made a union. Equal to
    // Model::bounds when the tessellation matches OpenSCAD's. nullopt: no leaves.
    std::optional<Box> leafBounds;
    // OpenSCAD's bbox of the exact result (left-out subtrees cut): the model's
    // bounds must contain it. nullopt: the result is empty.
    std::optional<Box> resultBounds;
};

// gtest prints a parameter with this instead of its bytes.
void PrintTo(const Example& e, std::ostream* os) { *os << e.file; }

// Pasted from the output of `python3 tests/data/openscad/facts.py` (openscad 2021.01).
const std::vector<Example>& examples() {
    static const std::vector<Example> all = {
        {"Basics_CSG-modules.csg", 22, 0, {},
         Box{{-27.4952, -10, -42.5}, {32.5, 10, 10}},
         Box{{-27.4952, -7.5, -42.5}, {32.5, 7.5, 7.5}}},
        {"Basics_CSG.csg", 6, 0, {},
         Box{{-34, -9.94522, -9.94522}, {34, 9.94522, 9.94522}},
         Box{{-34, -9.94522, -9.94522}, {31.5, 9.94522, 9.94522}}},
        {"Basics_LetterBlock.csg", 2, 0, {},
         Box{{-15, -15, 0}, {15, 15, 35}},
         Box{{-15, -15, 0}, {15, 15, 15}}},
        {"Basics_logo.csg", 4, 0, {},
         Box{{-31.25, -31.25, -31.25}, {31.25, 31.25, 31.25}},
         Box{{-21.6505, -21.6505, -21.6428}, {21.6505, 21.6505, 21.6428}}},
        {"Basics_rotate_extrude.csg", 6, 0, {},
         Box{{-15, -14.9178, -0.13559}, {57.5, 57.4041, 20}},
         Box{{-15, -14.9178, -0.13559}, {57.5, 57.4041, 20}}},
        {"Old_example002.csg", 6, 0, {},
         Box{{-25, -25, -50}, {25, 25, 30}},
         Box{{-15, -15, -20}, {15, 15, 15}}},
        {"Old_example006.csg", 22, 0, {},
         Box{{-59.9452, -59.9452, -59.9452}, {59.9452, 59.9452, 59.9452}},
         Box{{-50, -49.9452, -49.9452}, {50, 49.9452, 49.9452}}},
        {"Old_example011.csg", 1, 0, {},
         Box{{-10, -10, 0}, {10, 10, 10}},
         Box{{-10, -10, 0}, {10, 10, 10}}},
        {"Old_example012.csg", 2, 0, {},
         Box{{-20, -19.8904, -19.8904}, {20, 19.8904, 20}},
         Box{{-20, -19.8904, -19.8904}, {20, 19.8904, 15}}},
        {"Old_example014.csg", 4, 0, {},
         Box{{-50, -48.8848, -50.4169}, {50, 48.8848, 50.4169}},
         Box{{-12.5122, -10, -10}, {12.5122, 10, 10}}},
        {"Old_example016.csg", 13, 0, {},
         Box{{-33, -16, -16}, {32.5, 16, 16}},
         Box{{-32.5, -14, -14}, {32.5, 14, 14}}},
        {"Old_example024.csg", 221, 0, {},
         Box{{-100, -100, -200}, {100, 100, 86.6025}},
         Box{{-61.2373, -70.7107, 0}, {81.6497, 70.7107, 86.6025}}},
        {"Parametric_candleStand.csg", 39, 0, {},
         Box{{-26.5166, -28.3713, 0}, {29, 28.3713, 54.5}},
         Box{{-26.5166, -28.3713, 0}, {29, 28.3713, 53.5}}},
        // OpenSCAD's development version writes the same examples in its newer
        // dialect; the figures are those of the 2021.01 exports above.
        {"Newer_Old_example012.csg", 2, 0, {},
         Box{{-20, -19.8904, -19.8904}, {20, 19.8904, 20}},
         Box{{-20, -19.8904, -19.8904}, {20, 19.8904, 15}}},
        {"Newer_Basics_rotate_extrude.csg", 6, 0, {},
         Box{{-15, -14.9178, -0.13559}, {57.5, 57.4041, 20}},
         Box{{-15, -14.9178, -0.13559}, {57.5, 57.4041, 20}}},
        {"Newer_Parametric_candleStand.csg", 39, 0, {},
         Box{{-26.5166, -28.3713, 0}, {29, 28.3713, 54.5}},
         Box{{-26.5166, -28.3713, 0}, {29, 28.3713, 53.5}}},
    };
    return all;
}

// OpenSCAD 2021.01 writes STL coordinates with 6 significant digits, so a
// pasted value is off by at most half a unit in its 6th digit: below 5e-6 of its
// magnitude. Allow twice that, and an absolute floor for values near zero.
double printTolerance(double v) { return 1e-5 * std::max(1.0, std::abs(v)); }

std::string path(const Example& e) { return std::string(STRATA_TEST_DIR) + "/data/openscad/" + e.file; }

std::string testName(const testing::TestParamInfo<Example>& info) {
    std::string name = info.param.file;
    name.erase(name.size() - 4);  // ".csg"
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return name;
}

class OpenScadExample : public testing::TestWithParam<Example> {};

}  // namespace

TEST_P(OpenScadExample, ParsesWithTheExpectedLeavesAndWarnings) {
    const Example& e = GetParam();
    scene::Tree tree;
    ASSERT_NO_THROW(tree = scene::parseCsgFile(path(e)));

    EXPECT_EQ(tree.leaves.size(), static_cast<std::size_t>(e.leaves));
    const auto background = std::count_if(tree.leaves.begin(), tree.leaves.end(), [](const scene::Leaf& l) {
        return l.display == scene::Display::Background;
    });
    EXPECT_EQ(background, e.background);

    std::map<std::string, int> expected;
    for (const LeftOut& u : e.leftOut) expected[u.name] = u.count;
    EXPECT_EQ(tree.unsupported, expected);

    // One warning per left-out node type, at its first occurrence, and no others.
    EXPECT_EQ(tree.warnings.size(), e.leftOut.size());
    for (const LeftOut& u : e.leftOut) {
        const std::string where = tree.source + ":" + std::to_string(u.firstLine) + ":";
        const std::string quoted = std::string("'") + u.name + "'";
        const bool found = std::any_of(tree.warnings.begin(), tree.warnings.end(), [&](const Warning& w) {
            return w.message.rfind(where, 0) == 0 && w.message.find(quoted) != std::string::npos;
        });
        EXPECT_TRUE(found) << "no warning for " << quoted << " starting with " << where;
    }
}

TEST_P(OpenScadExample, LeafBoundsMatchOpenScadsTessellation) {
    const Example& e = GetParam();
    const scene::Tree tree = scene::parseCsgFile(path(e));
    model::Model model;
    ASSERT_NO_THROW(model = model::buildModel(tree));

    ASSERT_EQ(model.leafMeshes.size(), tree.leaves.size());
    for (std::size_t i = 0; i < model.leafMeshes.size(); ++i) {
        EXPECT_GE(model.leafMeshes[i].triangles.size(), 4u) << "leaf " << i << " at " << tree.leaves[i].where.str();
    }

    if (!e.leafBounds) {
        EXPECT_TRUE(model.bounds.empty());
        return;
    }
    ASSERT_FALSE(model.bounds.empty());
    const Box& want = *e.leafBounds;
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(model.bounds.min[k], want.min[k], printTolerance(want.min[k])) << "min, axis " << k;
        EXPECT_NEAR(model.bounds.max[k], want.max[k], printTolerance(want.max[k])) << "max, axis " << k;
    }
}

TEST_P(OpenScadExample, BoundsContainOpenScadsResult) {
    const Example& e = GetParam();
    if (!e.resultBounds) return;  // OpenSCAD's result is empty: nothing to contain
    const model::Model model = model::buildModel(scene::parseCsgFile(path(e)));
    ASSERT_FALSE(model.bounds.empty());
    const Box& result = *e.resultBounds;
    for (int k = 0; k < 3; ++k) {
        EXPECT_LE(model.bounds.min[k], result.min[k] + printTolerance(result.min[k])) << "axis " << k;
        EXPECT_GE(model.bounds.max[k], result.max[k] - printTolerance(result.max[k])) << "axis " << k;
    }
}

INSTANTIATE_TEST_SUITE_P(Exports, OpenScadExample, testing::ValuesIn(examples()), testName);

// The same example in both dialects gives the same scene.
TEST(OpenScadExamples, NewerDialectGivesTheSameLeavesAsOld) {
    const std::string dir = std::string(STRATA_TEST_DIR) + "/data/openscad/";
    for (const char* name : {"Old_example012", "Parametric_candleStand"}) {
        const scene::Tree older = scene::parseCsgFile(dir + name + ".csg");
        const scene::Tree newer = scene::parseCsgFile(dir + "Newer_" + name + ".csg");
        ASSERT_EQ(older.leaves.size(), newer.leaves.size()) << name;
        for (std::size_t i = 0; i < older.leaves.size(); ++i) {
            EXPECT_EQ(older.leaves[i].primitive.index(), newer.leaves[i].primitive.index()) << name << " leaf " << i;
            for (int c = 0; c < 4; ++c) {
                for (int r = 0; r < 4; ++r) {
                    // "-0" and "0" are equal as doubles; EXPECT_EQ compares values.
                    EXPECT_EQ(older.leaves[i].transform[c][r], newer.leaves[i].transform[c][r])
                        << name << " leaf " << i << " m[" << c << "][" << r << "]";
                }
            }
        }
    }
}

// The scenes in examples/ (the README's main job renders them): each reads
// without a warning and builds into closed leaves. Leaf counts are the
// primitive lines (cube, sphere, cylinder, polyhedron, import) in each file,
// counted with grep.
TEST(BundledExamples, ParseAndBuildWithoutWarnings) {
    const std::map<std::string, std::size_t> leaves = {
        {"stacked_holes.csg", 23}, {"gear.csg", 35}, {"deep_tree.csg", 12}, {"imported_mesh.csg", 4},
        {"openscad_CSG.csg", 6}, {"openscad_logo.csg", 4}, {"openscad_menger_sponge.csg", 221},
    };
    for (const auto& [file, count] : leaves) {
        SCOPED_TRACE(file);
        const std::string p = std::string(STRATA_TEST_DIR) + "/../examples/" + file;
        scene::Tree tree;
        ASSERT_NO_THROW(tree = scene::parseCsgFile(p));
        EXPECT_EQ(tree.leaves.size(), count);
        EXPECT_TRUE(tree.warnings.empty()) << tree.warnings.front().message;
        model::Model model;
        ASSERT_NO_THROW(model = model::buildModel(tree));
        EXPECT_FALSE(model.bounds.empty());
    }
}
