// The table of export formats against the writers that write them.

#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "strata/core/Error.h"
#include "strata/io/ExportFormats.h"
#include "strata/io/FlatWriter.h"
#include "strata/io/MeshWriter.h"

using namespace strata;

TEST(ExportFormats, EveryFormatIsWrittenByItsKindsWriterInAnyCase) {
    int meshes = 0, drawings = 0;
    for (const io::ExportFormat& format : io::exportFormats()) {
        std::string upper(format.extension);
        for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        for (const std::string& path : {"a/model" + std::string(format.extension), "model" + upper}) {
            ASSERT_EQ(io::exportFormatOf(path), &format) << path;
            EXPECT_EQ(io::isFlatPath(path), format.kind == io::ExportKind::Drawing) << path;
            if (format.kind == io::ExportKind::Mesh) {
                EXPECT_NO_THROW(io::meshFormatOf(path)) << path;
                EXPECT_EQ(format.colors, io::meshFormatOf(path) == io::MeshFormat::ThreeMf) << path;
            } else {
                EXPECT_THROW(io::meshFormatOf(path), Error) << path;
            }
        }
        (format.kind == io::ExportKind::Mesh ? meshes : drawings)++;
    }
    EXPECT_EQ(meshes, 4);
    EXPECT_EQ(drawings, 2);
    for (const std::string path : {"model.png", "model", "model.stl.bak", ".stl"}) EXPECT_EQ(io::exportFormatOf(path), nullptr) << path;
    EXPECT_EQ(io::extensionList(io::ExportKind::Mesh), ".stl, .off, .obj or .3mf");
    EXPECT_EQ(io::extensionList(io::ExportKind::Drawing), ".svg or .dxf");
    EXPECT_EQ(io::extensionList(), ".stl, .off, .obj, .3mf, .svg or .dxf");
}
