#pragma once
// Argument values of the CSG export: numbers, booleans, strings, undef and
// (nested) vectors. Vectors of numbers and vectors of number-vectors (points,
// faces, matrices) are stored flat, so a million-point polyhedron costs its
// doubles and little else.

#include <cstdint>
#include <string>
#include <vector>

#include "strata/core/Error.h"

namespace strata::scene {

struct CsgValue {
    enum class Type { Undef, Number, Bool, String, Numbers, Rows, List };
    Type type = Type::Undef;
    double number = 0.0;
    bool boolean = false;
    std::string string;
    std::vector<double> numbers;          // Numbers: the elements; Rows: all rows, concatenated
    std::vector<std::uint32_t> rowEnds;   // Rows: end offset of each row in `numbers`
    std::vector<CsgValue> items;          // List: any other vector

    std::size_t rowCount() const { return rowEnds.size(); }
    std::size_t rowBegin(std::size_t r) const { return r == 0 ? 0 : rowEnds[r - 1]; }

    // Appends an element to a vector value under construction (type Numbers/Rows/List).
    void append(CsgValue element);
    // Turns Numbers/Rows into a general List (used when a vector's elements mix types).
    void toList();
    std::size_t size() const;  // elements of a vector
};

// "number", "vector", ... for messages.
const char* typeName(CsgValue::Type type);

struct CsgArgument {
    std::string name;  // empty for a positional argument
    CsgValue value;
    SourceLocation where;
};

}  // namespace strata::scene
