// The table of the files strata imports (strata/scene/ImportFormats.h):
// every reader accepts what the table lists, in any case, and refuses the
// rest with the list the table makes.

#include <gtest/gtest.h>

#include <string>

#include "strata/core/InputFile.h"
#include "strata/scene/ImportFormats.h"

using namespace strata;
using scene::ImportKind;

TEST(ImportFormats, EachExtensionIsItsKindInAnyCaseAndNoOther) {
    for (const char* mesh : {"a.stl", "b.OFF", "dir.x/c.Obj", "d.pLy"}) {
        EXPECT_TRUE(scene::isImportPath(mesh, ImportKind::Mesh)) << mesh;
        EXPECT_FALSE(scene::isImportPath(mesh, ImportKind::Drawing)) << mesh;
    }
    for (const char* drawing : {"a.dxf", "b.SVG"}) {
        EXPECT_TRUE(scene::isImportPath(drawing, ImportKind::Drawing)) << drawing;
        EXPECT_FALSE(scene::isImportPath(drawing, ImportKind::Mesh)) << drawing;
    }
    for (const char* other : {"a.3mf", "b.csg", "stl", "c.stl.gz", "d.", ".stl/e", "f.st"}) {
        EXPECT_FALSE(scene::isImportPath(other, ImportKind::Mesh)) << other;
        EXPECT_FALSE(scene::isImportPath(other, ImportKind::Drawing)) << other;
    }
    EXPECT_TRUE(scene::isImportExtension(".ply", ImportKind::Mesh));
    EXPECT_FALSE(scene::isImportExtension(".PLY", ImportKind::Mesh));  // already lower case, or not at all
}

TEST(ImportFormats, MessagesListTheTableInOrder) {
    EXPECT_EQ(scene::importExtensionList(ImportKind::Mesh), ".stl, .off, .obj or .ply");
    EXPECT_EQ(scene::importExtensionList(ImportKind::Drawing), ".dxf or .svg");
    EXPECT_EQ(scene::importExtensionList(ImportKind::Mesh, ".csg, .scad"), ".csg, .scad, .stl, .off, .obj or .ply");
}

TEST(ImportFormats, AnExtensionIsLoweredInAsciiOnly) {
    EXPECT_EQ(lowerExtension("Model.STL"), ".stl");
    EXPECT_EQ(lowerExtension("dir.D/model"), "");
    EXPECT_EQ(lowerExtension("a.tar.GZ"), ".gz");
    EXPECT_EQ(lowerExtension("x.\xC3\x89"), ".\xC3\x89");  // UTF-8 É stays as it is
}
