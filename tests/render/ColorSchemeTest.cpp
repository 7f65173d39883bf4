#include <gtest/gtest.h>

#include <string>

#include "strata/core/Error.h"
#include "strata/render/ColorScheme.h"

using namespace strata;

TEST(ColorScheme, CornfieldIsOpenScadsDefault) {
    const render::ColorScheme& s = render::colorScheme(render::kDefaultColorScheme);
    EXPECT_EQ(s.name, "Cornfield");
    // ColorMap.cc: background #ffffe5, face front #f9d72c, face back #9dcb51.
    EXPECT_FLOAT_EQ(s.background.r, 1.0f);
    EXPECT_FLOAT_EQ(s.background.b, 0xe5 / 255.0f);
    EXPECT_FLOAT_EQ(s.faceFront.r, 0xf9 / 255.0f);
    EXPECT_FLOAT_EQ(s.faceFront.g, 0xd7 / 255.0f);
    EXPECT_FLOAT_EQ(s.faceFront.b, 0x2c / 255.0f);
    EXPECT_FLOAT_EQ(s.faceBack.g, 0xcb / 255.0f);
    EXPECT_FLOAT_EQ(s.faceFront.a, 1.0f);
}

TEST(ColorScheme, NamesMatchLooselyAndAllResolve) {
    EXPECT_EQ(render::colorScheme("tomorrow-night").name, "Tomorrow Night");
    EXPECT_EQ(render::colorScheme("DEEPOCEAN").name, "DeepOcean");
    // tomorrow-night.json: opencsg-face-back #de935f.
    EXPECT_FLOAT_EQ(render::colorScheme("Tomorrow Night").faceBack.r, 0xde / 255.0f);
    const auto names = render::colorSchemeNames();
    EXPECT_GE(names.size(), 11u);
    EXPECT_EQ(names.front(), "Cornfield");
    for (const std::string& name : names) EXPECT_EQ(render::colorScheme(name).name, name);
}

TEST(ColorScheme, UnknownNameListsTheValidOnes) {
    try {
        render::colorScheme("Nope");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'Nope'"), std::string::npos) << what;
        EXPECT_NE(what.find("Cornfield"), std::string::npos) << what;
        EXPECT_NE(what.find("Solarized"), std::string::npos) << what;
    }
    EXPECT_THROW(render::colorScheme(""), Error);
}
