#include "CsgParserImpl.h"

#include "strata/core/InputFile.h"
#include "strata/scene/ImportFormats.h"

namespace strata::scene::detail {

// A solid (cube, sphere, cylinder, polyhedron, import, surface): a leaf.
void Parser::leafStatement(const Statement& st, Open open, const Open& parent) {
    const int leafNode = st.dropped ? -1 : makeLeaf(st.module, st.args, open.context, st.where);
    if (leafNode >= 0) {
        if (open.isRoot) rootNode_ = leafNode;
        else if (open.isBackgroundRoot) tree_.background.push_back(leafNode);
        else attach(leafNode, parent);
    }
    if (!st.hasBlock) {
        statementFinished();
    } else {
        // A primitive with children: OpenSCAD ignores them; so do we, but parse them.
        open.node = -1;
        pushBlock(std::move(open), st.where);
    }
}

Fragments Parser::fragments(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Fragments f;
    f.fn = number(args, "$fn", -1, 0.0);
    f.fa = number(args, "$fa", -1, 12.0);
    f.fs = number(args, "$fs", -1, 2.0);
    if (f.fn > options_.maxFragments) {
        warnOnce("fn-clamp", where,
                 "$fn = " + std::to_string(f.fn) + " is clamped to " + std::to_string(static_cast<int>(options_.maxFragments)));
        f.fn = options_.maxFragments;
    }
    // OpenSCAD clamps $fa and $fs from below to 0.01.
    if (f.fa < 0.01) f.fa = 0.01;
    if (f.fs < 0.01) f.fs = 0.01;
    return f;
}

Cube Parser::cube(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Cube c;
    const CsgArgument* size = find(args, "size", 0);
    if (size != nullptr && size->value.type != CsgValue::Type::Undef) {
        if (size->value.type == CsgValue::Type::Number) {
            double s = number(*size, "size");
            c.size = glm::dvec3(s);
        } else if (size->value.type == CsgValue::Type::Numbers && size->value.numbers.size() == 3) {
            for (int i = 0; i < 3; ++i) {
                double s = size->value.numbers[static_cast<std::size_t>(i)];
                if (!std::isfinite(s)) lex_.failAt(size->where, "size must be finite");
                c.size[i] = s;
            }
        } else {
            lex_.failAt(size->where, "size must be a number or a vector of 3 numbers");
        }
        if (c.size.x < 0 || c.size.y < 0 || c.size.z < 0) lex_.failAt(size->where, "size must not be negative");
    }
    c.center = boolean(args, "center", 1, false);
    (void)where;
    return c;
}

Sphere Parser::sphere(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Sphere s;
    s.r = radius(args, "r", "d", s.r, 0);
    s.fragments = fragments(args, where);
    return s;
}

Cylinder Parser::cylinder(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Cylinder c;
    const CsgArgument* h = find(args, "h", 0);
    if (h != nullptr && h->value.type != CsgValue::Type::Undef) {
        c.h = number(*h, "h");
        if (c.h < 0) lex_.failAt(h->where, "h must not be negative");
    }
    double r = radius(args, "r", "d", 1.0, 1);
    c.r1 = radius(args, "r1", "d1", r, 2);
    c.r2 = radius(args, "r2", "d2", r, 3);
    c.center = boolean(args, "center", 4, false);
    c.fragments = fragments(args, where);
    return c;
}

std::optional<Polyhedron> Parser::polyhedron(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Polyhedron p;
    const CsgArgument* points = find(args, "points", 0);
    if (points == nullptr) lex_.failAt(where, "polyhedron has no points");
    const CsgValue& pv = points->value;
    if (pv.type == CsgValue::Type::Numbers && pv.numbers.empty()) {
        // OpenSCAD writes `polyhedron(points = [], faces = [])` for an empty one: nothing to draw.
        warnOnce("empty-polyhedron", where, "polyhedron has no points; left out");
        return std::nullopt;
    }
    if (pv.type != CsgValue::Type::Rows) lex_.failAt(points->where, "points must be a vector of 3-vectors of numbers");
    p.points.reserve(pv.rowCount());
    for (std::size_t r = 0; r < pv.rowCount(); ++r) {
        std::size_t b = pv.rowBegin(r);
        if (pv.rowEnds[r] - b != 3) {
            lex_.failAt(points->where, "point " + std::to_string(r) + " does not have 3 coordinates");
        }
        glm::dvec3 q(pv.numbers[b], pv.numbers[b + 1], pv.numbers[b + 2]);
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
            lex_.failAt(points->where, "point " + std::to_string(r) + " is not finite");
        }
        p.points.push_back(q);
    }
    const CsgArgument* faces = find(args, "faces", 1);
    if (faces == nullptr || faces->value.type == CsgValue::Type::Undef) faces = find(args, "triangles", -1);
    if (faces == nullptr) lex_.failAt(where, "polyhedron has no faces");
    const CsgValue& fv = faces->value;
    if (fv.type != CsgValue::Type::Rows) lex_.failAt(faces->where, "faces must be a vector of vectors of point indices");
    p.faces.reserve(fv.rowCount());
    for (std::size_t r = 0; r < fv.rowCount(); ++r) {
        std::vector<int> face;
        for (std::size_t k = fv.rowBegin(r); k < fv.rowEnds[r]; ++k) {
            double idx = fv.numbers[k];
            if (!(idx >= 0) || idx >= static_cast<double>(p.points.size()) || idx != std::floor(idx)) {
                lex_.failAt(faces->where, "face " + std::to_string(r) + " has an invalid point index");
            }
            face.push_back(static_cast<int>(idx));
        }
        if (face.size() < 3) lex_.failAt(faces->where, "face " + std::to_string(r) + " has fewer than 3 points");
        p.faces.push_back(std::move(face));
    }
    return p;
}

std::optional<Import> Parser::import(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    const CsgArgument* file = find(args, "file", 0);
    if (file == nullptr || file->value.type != CsgValue::Type::String) {
        lex_.failAt(file ? file->where : where, "import needs a file name string");
    }
    if (file->value.string.empty()) {
        // OpenSCAD exports `import(file = "")` for an import with no file: it imports nothing.
        warnOnce("empty-import", where, "import has an empty file name; left out");
        return std::nullopt;
    }
    if (!isImportPath(file->value.string, ImportKind::Mesh)) {
        const std::string ext = lowerExtension(file->value.string);
        unsupported("import" + (ext.empty() ? std::string() : "(" + ext + ")"), where);
        return std::nullopt;
    }
    return Import{resolvePath(*file, "import")};
}

Surface Parser::surface(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Surface surf;
    const CsgArgument* file = find(args, "file", 0);
    if (file == nullptr || file->value.type != CsgValue::Type::String || file->value.string.empty()) {
        lex_.failAt(file ? file->where : where, "surface needs a file name string");
    }
    surf.path = resolvePath(*file, "surface");
    surf.center = boolean(args, "center", 1, false);
    surf.invert = boolean(args, "invert", -1, false);
    return surf;
}

int Parser::makeLeaf(Module module, const std::vector<CsgArgument>& args, const Context& ctx,
                     const SourceLocation& where) {
    Leaf leaf;
    if (module == Module::Cube) leaf.primitive = cube(args, where);
    else if (module == Module::Surface) leaf.primitive = surface(args, where);
    else if (module == Module::Sphere) leaf.primitive = sphere(args, where);
    else if (module == Module::Cylinder) leaf.primitive = cylinder(args, where);
    else if (module == Module::Polyhedron) {
        std::optional<Polyhedron> p = polyhedron(args, where);
        if (!p) return -1;
        leaf.primitive = std::move(*p);
    } else {
        std::optional<Import> imported = import(args, where);
        if (!imported) return -1;
        leaf.primitive = std::move(*imported);
    }
    Leaf placed = leafAt(ctx, where);
    placed.primitive = std::move(leaf.primitive);
    return tree_.addLeaf(std::move(placed));
}

Leaf Parser::leafAt(const Context& ctx, const SourceLocation& where) const {
    Leaf leaf;
    leaf.transform = ctx.transform;
    leaf.steps = ctx.steps;
    if (ctx.color.r >= 0.0 || ctx.color.g >= 0.0 || ctx.color.b >= 0.0 || ctx.color.a >= 0.0) leaf.color = ctx.color;
    leaf.display = ctx.display;
    leaf.where = where;
    return leaf;
}

}  // namespace strata::scene::detail
