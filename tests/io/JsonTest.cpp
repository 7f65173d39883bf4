#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "strata/io/Json.h"
#include "strata/io/Stats.h"

using namespace strata;

TEST(Json, WritesNestedValuesInOrder) {
    io::JsonWriter json;
    json.beginObject();
    json.key("a").value(1);
    json.key("b").beginArray().value(1.5).value(true).null().endArray();
    json.key("c").beginObject().endObject();
    json.key("d").beginArray().endArray();
    json.key("e").value("x");
    json.endObject();
    EXPECT_EQ(json.str(), R"({"a": 1, "b": [1.5, true, null], "c": {}, "d": [], "e": "x"})");
}

TEST(Json, IndentsOneMemberPerLine) {
    io::JsonWriter json(2);
    json.beginObject().key("a").beginArray().value(1).value(2).endArray().key("b").value(false).endObject();
    EXPECT_EQ(json.str(), "{\n  \"a\": [\n    1,\n    2\n  ],\n  \"b\": false\n}");
}

TEST(Json, OneLineArrayStaysOnOneLineWhenIndenting) {
    io::JsonWriter json(2);
    json.beginObject().key("a").beginArray(true).value(1).value(2).beginObject().key("k").value(3).endObject();
    json.endArray().key("b").value(4).endObject();
    EXPECT_EQ(json.str(), "{\n  \"a\": [1, 2, {\"k\": 3}],\n  \"b\": 4\n}");
}

TEST(Json, EscapesStringsAndNullsNonFiniteNumbers) {
    EXPECT_EQ(io::JsonWriter::quote("a\"b\\c\nd\te\x01"), R"("a\"b\\c\nd\te\u0001")");
    io::JsonWriter json;
    json.beginArray()
        .value(std::numeric_limits<double>::infinity())
        .value(std::numeric_limits<double>::quiet_NaN())
        .value(0.1)
        .value(1e-300)
        .value(std::uint64_t{18446744073709551615ull})
        .value(-3)
        .endArray();
    EXPECT_EQ(json.str(), "[null, null, 0.1, 1e-300, 18446744073709551615, -3]");
}

TEST(Stats, HoldsEveryFigureOfTheContract) {
    io::RunStats s;
    s.scene = "a \"quoted\".csg";
    s.width = 64;
    s.height = 32;
    s.frame.peelMs = 1.25;
    s.frame.evaluateMs = 2.5;
    s.frame.normalMs = 0.75;
    s.frame.layersPerLeaf = {1, 3, 0};
    s.frame.operands = 2;
    s.frame.textureBytes = 4096;
    s.frame.coveredPixels = 100;
    s.frame.tiles = 2;
    s.frame.peelPasses = 5;
    s.frame.listPeeledOperands = 1;
    s.frame.notes = {"tiled"};
    s.warnings = {"a.csg:3:1: warning: unsupported 'hull'"};
    s.unsupported = {{"hull", 1}};
    const std::string json = io::statsJson(s, 0);
    EXPECT_EQ(json.front(), '{');
    EXPECT_EQ(json.back(), '}');
    EXPECT_EQ(json.find('\n'), std::string::npos);
    for (const char* part : {R"("scene": "a \"quoted\".csg")", R"("width": 64)", R"("height": 32)",
                             R"("peel": 1.25)", R"("evaluate": 2.5)", R"("normal": 0.75)",
                             R"("layers_per_operand": [1, 3, 0])", R"("layers_max": 3)",
                             R"("layers_total": 4)", R"("operands": 2)", R"("texture_bytes": 4096)",
                             R"("covered_pixels": 100)", R"("tiles": 2)", R"("peel_passes": 5)",
                             R"("list_peeled_operands": 1)", R"("notes": ["tiled"])",
                             R"("warnings": ["a.csg:3:1: warning: unsupported 'hull'"])",
                             R"("unsupported": {"hull": 1})"})
        EXPECT_NE(json.find(part), std::string::npos) << part << "\nin " << json;
}
