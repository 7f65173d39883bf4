#include "CsgParserImpl.h"

namespace strata::scene::detail {

// An operation on its children: a boolean, a transform or colour, a node
// whose children become other leaves when it closes (hull, minkowski,
// resize), or one strata leaves out with a warning.
void Parser::operationStatement(const Statement& st, Open open) {
    NodeKind kind = NodeKind::Union;
    bool known = true;
    switch (st.module) {
        case Module::Group:
        case Module::Union:
        case Module::Render:
        case Module::Assign: open.collapsible = true; break;
        case Module::Intersection: kind = NodeKind::Intersection; break;
        case Module::Difference: kind = NodeKind::Difference; break;
        case Module::Hull:
        case Module::Minkowski:
            // Collects the children; closing turns them into hull leaves. The
            // children are placed relative to the node and its transform places
            // the result, as OpenSCAD transforms the result: a Minkowski sum of
            // children placed in the world would have their translations added.
            open.gather = st.module == Module::Hull ? Open::Gather::Hull : Open::Gather::Minkowski;
            open.placement = open.context.transform;
            open.resizesBefore = tree_.resizes.size();
            open.context.frame = open.context.frame * open.context.transform;
            open.context.transform = glm::dmat4(1.0);
            open.context.steps = nullptr;
            break;
        case Module::Resize:
            // Its leaves are placed relative to it, and scaled when the model is built.
            open.gather = Open::Gather::Resize;
            if (!st.dropped) {
                open.resize = resizeArguments(st.args);
                open.resize.outer = open.context.transform;
                open.resize.where = st.where;
                open.context.frame = open.context.frame * open.context.transform;
                open.context.transform = glm::dmat4(1.0);
                open.context.steps = nullptr;
            }
            break;
        case Module::Multmatrix:
            if (!st.dropped) {
                const glm::dmat4 m = multmatrix(st.args, st.where);
                open.context.transform = open.context.transform * m;
                open.context.steps = std::make_shared<const TransformStep>(TransformStep{m, open.context.steps});
            }
            open.collapsible = true;
            break;
        case Module::Color:
            if (!st.dropped) {
                const glm::dvec4 c = color(st.args, st.where);
                for (int i = 0; i < 4; ++i) {
                    if (open.context.color[i] < 0.0) open.context.color[i] = c[i];  // outermost wins
                }
            }
            open.collapsible = true;
            break;
        case Module::Unsupported:
            known = false;
            if (!st.dropped) unsupported(st.name, st.where);
            break;
        default: lex_.failAt(st.where, "unknown module '" + st.name + "'");
    }
    if (!known || st.dropped) {
        open.node = -1;
        open.gather = Open::Gather::None;
    } else {
        open.shape = open.gather != Open::Gather::None;
        open.node = tree_.addNode(kind, {});
        tree_.nodes[static_cast<std::size_t>(open.node)].where = st.where;
    }
    // No children at all: an empty group, difference or intersection.
    enterBlock(st, std::move(open));
}

glm::dmat4 Parser::multmatrix(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    const CsgArgument* m = find(args, "m", 0);
    if (m == nullptr) return glm::dmat4(1.0);
    const CsgValue& v = m->value;
    if (v.type != CsgValue::Type::Rows || (v.rowCount() != 4 && v.rowCount() != 3)) {
        lex_.failAt(m->where, "multmatrix needs a 4x4 matrix (rows of 4 numbers)");
    }
    glm::dmat4 result(1.0);
    for (std::size_t r = 0; r < v.rowCount(); ++r) {
        std::size_t b = v.rowBegin(r);
        if (v.rowEnds[r] - b != 4) lex_.failAt(m->where, "multmatrix row " + std::to_string(r) + " does not have 4 numbers");
        for (std::size_t c = 0; c < 4; ++c) {
            double x = v.numbers[b + c];
            if (!std::isfinite(x)) lex_.failAt(m->where, "multmatrix has a number that is not finite");
            result[static_cast<int>(c)][static_cast<int>(r)] = x;  // row-major text, column-major glm
        }
    }
    (void)where;
    return result;
}

glm::dvec4 Parser::color(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    glm::dvec4 c(-1.0);
    const CsgArgument* a = find(args, "c", 0);
    if (a != nullptr) {
        const CsgValue& v = a->value;
        if (v.type == CsgValue::Type::Numbers && (v.numbers.size() == 3 || v.numbers.size() == 4)) {
            for (std::size_t i = 0; i < v.numbers.size(); ++i) {
                double x = v.numbers[i];
                if (!std::isfinite(x)) lex_.failAt(a->where, "color has a number that is not finite");
                c[static_cast<int>(i)] = x < 0.0 ? -1.0 : std::min(x, 1.0);
            }
            if (v.numbers.size() == 3) c.a = 1.0;
        } else if (v.type == CsgValue::Type::String) {
            warnOnce("color-name", a->where, "color names are not supported; the colour is left unset");
        } else if (v.type != CsgValue::Type::Undef) {
            lex_.failAt(a->where, "color must be a vector of 3 or 4 numbers");
        }
    }
    const CsgArgument* alpha = find(args, "alpha", 1);
    if (alpha != nullptr && alpha->value.type == CsgValue::Type::Number) {
        double x = number(*alpha, "alpha");
        c.a = x < 0.0 ? -1.0 : std::min(x, 1.0);
    }
    (void)where;
    return c;
}

}  // namespace strata::scene::detail
