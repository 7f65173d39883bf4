#include "CsgValue.h"

#include <utility>

namespace strata::scene {

std::size_t CsgValue::size() const {
    switch (type) {
        case Type::Numbers: return numbers.size();
        case Type::Rows: return rowEnds.size();
        case Type::List: return items.size();
        default: return 0;
    }
}

void CsgValue::toList() {
    if (type == Type::List) return;
    std::vector<CsgValue> list;
    if (type == Type::Numbers) {
        list.reserve(numbers.size());
        for (double d : numbers) {
            CsgValue v;
            v.type = Type::Number;
            v.number = d;
            list.push_back(std::move(v));
        }
    } else if (type == Type::Rows) {
        list.reserve(rowEnds.size());
        for (std::size_t r = 0; r < rowEnds.size(); ++r) {
            CsgValue row;
            row.type = Type::Numbers;
            row.numbers.assign(numbers.begin() + static_cast<std::ptrdiff_t>(rowBegin(r)),
                               numbers.begin() + static_cast<std::ptrdiff_t>(rowEnds[r]));
            list.push_back(std::move(row));
        }
    }
    numbers.clear();
    numbers.shrink_to_fit();
    rowEnds.clear();
    rowEnds.shrink_to_fit();
    items = std::move(list);
    type = Type::List;
}

void CsgValue::append(CsgValue element) {
    const bool empty = size() == 0;
    if (empty && type != Type::List) {
        // The first element decides the flat layout.
        if (element.type == Type::Number) type = Type::Numbers;
        else if (element.type == Type::Numbers) type = Type::Rows;
        else type = Type::List;
    }
    if (type == Type::Numbers && element.type == Type::Number) {
        numbers.push_back(element.number);
        return;
    }
    if (type == Type::Rows && element.type == Type::Numbers) {
        numbers.insert(numbers.end(), element.numbers.begin(), element.numbers.end());
        rowEnds.push_back(static_cast<std::uint32_t>(numbers.size()));
        return;
    }
    toList();
    items.push_back(std::move(element));
}

const char* typeName(CsgValue::Type type) {
    switch (type) {
        case CsgValue::Type::Undef: return "undef";
        case CsgValue::Type::Number: return "number";
        case CsgValue::Type::Bool: return "boolean";
        case CsgValue::Type::String: return "string";
        case CsgValue::Type::Numbers:
        case CsgValue::Type::Rows:
        case CsgValue::Type::List: return "vector";
    }
    return "?";
}

}  // namespace strata::scene
