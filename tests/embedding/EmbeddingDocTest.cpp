// docs/embedding.md quotes tests/embedding/EmbeddingExample.cpp (and the
// CMakeLists.txt files that build it, this folder's and installed/'s, the
// host project built against an installed strata); the quotes must stay verbatim, so the page shows
// code that the EmbeddingExample test compiles and runs. A quoted block may
// be dedented: each of its lines must equal a run of consecutive source
// lines with one common indentation removed.

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> readLines(const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

struct Block {
    std::string language;
    int line = 0;  // of the opening fence, from 1
    std::vector<std::string> lines;
};

// Fenced code blocks (```lang ... ```) of a Markdown file.
std::vector<Block> codeBlocks(const std::vector<std::string>& doc) {
    std::vector<Block> blocks;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        if (doc[i].rfind("```", 0) != 0) continue;
        Block block{doc[i].substr(3), static_cast<int>(i) + 1, {}};
        for (++i; i < doc.size() && doc[i].rfind("```", 0) != 0; ++i) block.lines.push_back(doc[i]);
        blocks.push_back(block);
    }
    return blocks;
}

// True when `block` equals source lines [k, k + n) less one common indentation.
bool quotedAt(const std::vector<std::string>& source, std::size_t k, const std::vector<std::string>& block) {
    if (block.empty() || k + block.size() > source.size()) return false;
    const std::string& first = source[k];
    if (first.size() < block[0].size() || first.compare(first.size() - block[0].size(), std::string::npos,
                                                         block[0]) != 0) {
        return false;
    }
    const std::string indent = first.substr(0, first.size() - block[0].size());
    if (indent.find_first_not_of(' ') != std::string::npos) return false;
    for (std::size_t m = 0; m < block.size(); ++m) {
        const std::string& s = source[k + m];
        if (block[m].empty() ? !s.empty() : s != indent + block[m]) return false;
    }
    return true;
}

bool quoted(const std::vector<std::string>& source, const std::vector<std::string>& block) {
    for (std::size_t k = 0; k < source.size(); ++k) {
        if (quotedAt(source, k, block)) return true;
    }
    return false;
}

// A CMake block that builds the example (rather than sketching a host's own
// project) names its target.
bool namesExample(const std::vector<std::string>& block) {
    for (const std::string& line : block) {
        if (line.find("strata-embedding-example") != std::string::npos) return true;
    }
    return false;
}

}  // namespace

TEST(EmbeddingDoc, QuotesTheExampleVerbatim) {
    const std::string dir = STRATA_TEST_DIR;
    const std::vector<std::string> doc = readLines(dir + "/../docs/embedding.md");
    const std::vector<std::string> example = readLines(dir + "/embedding/EmbeddingExample.cpp");
    const std::vector<std::string> cmake = readLines(dir + "/embedding/CMakeLists.txt");
    const std::vector<std::string> host = readLines(dir + "/embedding/installed/CMakeLists.txt");
    int cpp = 0;
    for (const Block& block : codeBlocks(doc)) {
        if (block.language == "cpp") {
            ++cpp;
            EXPECT_TRUE(quoted(example, block.lines))
                << "docs/embedding.md:" << block.line
                << ": this C++ block is not in tests/embedding/EmbeddingExample.cpp as written";
        } else if (block.language == "cmake" && namesExample(block.lines)) {
            EXPECT_TRUE(quoted(cmake, block.lines) || quoted(host, block.lines))
                << "docs/embedding.md:" << block.line
                << ": this CMake block is not in tests/embedding/CMakeLists.txt or"
                   " tests/embedding/installed/CMakeLists.txt as written";
        }
    }
    // The page walks through the program: context, meshes, tree, camera, render, renderInto.
    EXPECT_GE(cpp, 6) << "docs/embedding.md quotes too little of the example";
}

TEST(EmbeddingDoc, AQuoteMustMatchLineForLine) {
    // The checker itself: a dedented run matches, an edited line does not.
    const std::vector<std::string> source{"int f() {", "    int a = 1;", "", "    return a;", "}"};
    EXPECT_TRUE(quoted(source, {"int a = 1;", "", "return a;"}));
    EXPECT_FALSE(quoted(source, {"int a = 2;", "", "return a;"}));
    EXPECT_FALSE(quoted(source, {"int a = 1;", "return a;"}));
    EXPECT_TRUE(quoted(source, {"int f() {", "    int a = 1;"}));
}
