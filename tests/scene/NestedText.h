#pragma once
// Deeply nested scene text for the tests of the nesting limits.

#include <string>

namespace strata::test {

// `open` written `depth` times, one a line, around `inner`, each closed by `close`.
inline std::string nested(int depth, const std::string& open, const std::string& inner, const std::string& close) {
    std::string text;
    for (int i = 0; i < depth; ++i) text += open + "\n";
    text += inner + "\n";
    for (int i = 0; i < depth; ++i) text += close + "\n";
    return text;
}

}  // namespace strata::test
