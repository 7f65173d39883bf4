#include "CsgParserImpl.h"

#include "strata/scene/ImportFormats.h"

namespace strata::scene::detail {

namespace {

bool isFlatImportPath(const std::string& file) { return isImportPath(file, ImportKind::Drawing); }

// A transform that keeps the plane z = 0 and moves nothing out of it: a flat
// slab under it can join a flat result without changing what it shows.
bool keepsPlane(const glm::dmat4& m) {
    return m[0][2] == 0.0 && m[1][2] == 0.0 && m[3][2] == 0.0 && m[2][0] == 0.0 && m[2][1] == 0.0 &&
           m[2][3] == 0.0 && m[0][3] == 0.0 && m[1][3] == 0.0 && m[3][3] == 1.0;
}

FlatOp flatOpOf(NodeKind kind) {
    if (kind == NodeKind::Intersection) return FlatOp::Intersection;
    if (kind == NodeKind::Difference) return FlatOp::Difference;
    return FlatOp::Union;
}

}  // namespace

// An extrusion, or a 2D statement among solids: a leaf whose shape is read
// from here on (the extrusion's children, or this statement itself, shown as
// a slab).
void Parser::openFlatLeaf(const Statement& st, Open open) {
    if (!st.dropped) {
        Leaf leaf = leafAt(open.context, st.where);
        if (st.module == Module::LinearExtrude) leaf.primitive = linearExtrude(st.args, st.where);
        else if (st.module == Module::RotateExtrude) leaf.primitive = rotateExtrude(st.args, st.where);
        else leaf.primitive = FlatSlab{};
        pending_.push_back(PendingFlat{std::move(leaf), FlatTree{}});
        open.ownsFlat = true;
        open.shape = true;
        if (std::holds_alternative<FlatSlab>(pending().leaf.primitive)) {
            pending().tree.root = flatStatement(st, open, false);
        } else {
            open.flat = true;
            FlatNode root;
            root.where = st.where;
            open.flatNode = pending().tree.root = pending().tree.add(std::move(root));
        }
    }
    enterBlock(st, std::move(open));
}

// ---- Flat (2D) statements ----

bool Parser::isFlatShape(Module module, const std::vector<CsgArgument>& args) const {
    if (isFlatShapeModule(module)) return true;
    if (module != Module::Import) return false;
    const CsgArgument* file = find(args, "file", 0);
    return file != nullptr && file->value.type == CsgValue::Type::String && isFlatImportPath(file->value.string);
}

// Adds the statement to the pending flat tree (unless dropped) and sets up
// its block; returns the new node, or -1. The caller links it to its parent.
int Parser::flatStatement(const Statement& st, Open& open, bool dropped) {
    const std::vector<CsgArgument>& args = st.args;
    const SourceLocation& where = st.where;
    open.flat = true;
    open.flatNode = -1;
    FlatNode node;
    node.where = where;
    bool container = true;
    switch (st.module) {
        case Module::Group:
        case Module::Union:
        case Module::Render:
        case Module::Assign:
        case Module::Color:
            node.op = FlatOp::Union;
            if (st.module == Module::Color && !dropped) color(args, where);  // checked, though a colour means nothing in 2D
            break;
        case Module::Intersection: node.op = FlatOp::Intersection; break;
        case Module::Difference: node.op = FlatOp::Difference; break;
        case Module::Multmatrix:
            node.op = FlatOp::Transform;
            if (!dropped) node.matrix = multmatrix(args, where);
            break;
        case Module::Offset:
            node.op = FlatOp::Offset;
            if (!dropped) node.offset = offset(args, where);
            break;
        case Module::Resize:
            node.op = FlatOp::Resize;
            if (!dropped) {
                const Resize r = resizeArguments(args);
                node.newsize = {r.newsize.x, r.newsize.y};
                node.autosize = {r.autosize[0], r.autosize[1]};
            }
            break;
        case Module::Hull: node.op = FlatOp::Hull; break;
        case Module::Minkowski: node.op = FlatOp::Minkowski; break;
        case Module::Square:
        case Module::Circle:
        case Module::Polygon:
        case Module::Text:
        case Module::Import:
            if (isFlatShape(st.module, args)) {
                node.op = FlatOp::Shape;
                container = false;
                if (!dropped) {
                    node.shape = static_cast<int>(pending().tree.shapes.size());
                    pending().tree.shapes.push_back(flatShape(st.module, args, where));
                }
                break;
            }
            [[fallthrough]];  // an import of a solid
        case Module::Cube:
        case Module::Sphere:
        case Module::Cylinder:
        case Module::Polyhedron:
        case Module::Surface:
        case Module::LinearExtrude:
        case Module::RotateExtrude: {
            node.op = FlatOp::Empty;
            container = false;
            const CsgArgument* file = st.module == Module::Import ? find(args, "file", 0) : nullptr;
            if (dropped) {
            } else if (file != nullptr && file->value.type == CsgValue::Type::String && file->value.string.empty()) {
                warnOnce("empty-import", where, "import has an empty file name; left out");
            } else {
                warnOnce("3d-in-2d", where,
                         "'" + st.name + "' is a 3D object inside a 2D operation; it is ignored, as OpenSCAD ignores it");
            }
            break;
        }
        case Module::Unsupported:
            node.op = FlatOp::Empty;
            container = false;
            if (!dropped) unsupported(st.name, where);
            break;
        case Module::Projection:  // read by statement() before any 2D statement
        case Module::Unknown: lex_.failAt(where, "unknown module '" + st.name + "'");
    }
    if (dropped) return -1;
    const int index = pending().tree.add(std::move(node));
    if (container) open.flatNode = index;
    return index;
}

// The pending flat tree becomes its leaf; returns the leaf's node.
int Parser::finishFlat() {
    PendingFlat pending = std::move(pending_.back());
    pending_.pop_back();
    std::visit(
        [&](auto& p) {
            using T = std::decay_t<decltype(p)>;
            if constexpr (std::is_same_v<T, LinearExtrude> || std::is_same_v<T, RotateExtrude> ||
                          std::is_same_v<T, FlatSlab>) {
                p.shape = std::move(pending.tree);
            }
        },
        pending.leaf.primitive);
    return tree_.addLeaf(std::move(pending.leaf));
}


// A union, intersection or difference whose children are all flat slabs is a
// 2D boolean in OpenSCAD: it becomes one slab of the combined flat tree (each
// child under its own transform), shown as its children are when they agree.
// A hull, minkowski or resize makes one new shape, shown as the node itself
// (`shownAs`), whatever its children's colours. Returns the new leaf's node,
// or -1.
int Parser::mergeFlatChildren(int node, std::optional<FlatOp> op, const glm::dmat4& placement, const Context* shownAs) {
    const Node& n = tree_.nodes[static_cast<std::size_t>(node)];
    if (n.kind == NodeKind::Leaf || n.children.empty() || !flatChildren(node)) return -1;
    const Leaf* first = &tree_.leaves[static_cast<std::size_t>(tree_.nodes[static_cast<std::size_t>(n.children[0])].leaf)];
    for (int c : n.children) {
        const Leaf& leaf = tree_.leaves[static_cast<std::size_t>(tree_.nodes[static_cast<std::size_t>(c)].leaf)];
        if (!keepsPlane(leaf.transform)) return -1;
        if (shownAs == nullptr && (leaf.display != first->display || leaf.color != first->color)) return -1;
    }
    FlatTree merged;
    FlatNode root;
    root.op = op ? *op : flatOpOf(n.kind);
    root.where = n.where;
    merged.root = merged.add(std::move(root));
    for (int c : n.children) {
        Leaf& leaf = tree_.leaves[static_cast<std::size_t>(tree_.nodes[static_cast<std::size_t>(c)].leaf)];
        FlatTree& sub = std::get<FlatSlab>(leaf.primitive).shape;
        FlatNode place;
        place.op = FlatOp::Transform;
        place.matrix = leaf.transform;
        place.where = leaf.where;
        const int placed = merged.add(std::move(place));
        merged.nodes[static_cast<std::size_t>(merged.root)].children.push_back(placed);
        const int nodeOffset = static_cast<int>(merged.nodes.size());
        const int shapeOffset = static_cast<int>(merged.shapes.size());
        for (FlatNode& f : sub.nodes) {
            for (int& k : f.children) k += nodeOffset;
            if (f.shape >= 0) f.shape += shapeOffset;
            merged.nodes.push_back(std::move(f));
        }
        for (FlatPrimitive& p : sub.shapes) merged.shapes.push_back(std::move(p));
        if (sub.root >= 0) merged.nodes[static_cast<std::size_t>(placed)].children.push_back(sub.root + nodeOffset);
        sub = FlatTree{};
    }
    Leaf leaf;
    if (shownAs != nullptr) {
        leaf = leafAt(*shownAs, n.where);
    } else {
        leaf.color = first->color;
        leaf.display = first->display;
        leaf.where = n.where;
    }
    leaf.primitive = FlatSlab{std::move(merged)};
    leaf.transform = placement;
    leaf.steps = nullptr;
    return tree_.addLeaf(std::move(leaf));
}

// What a node holds once closed: 2 for a flat slab leaf or a node of them
// (a 2D operation), 0 for a node with no children (nothing, which has no
// dimension), 3 for anything else.
int Parser::dimensionOf(int node) const {
    const Node& n = tree_.nodes[static_cast<std::size_t>(node)];
    if (n.kind == NodeKind::Leaf) {
        return std::holds_alternative<FlatSlab>(tree_.leaves[static_cast<std::size_t>(n.leaf)].primitive) ? 2 : 3;
    }
    if (n.children.empty()) return 0;
    return flatChildren(node) ? 2 : 3;
}

// A union, intersection or difference is a 3D or a 2D operation by its
// first child with a dimension, and OpenSCAD's exact evaluation (F6) takes
// a child of the other dimension as empty, with a warning: it drops from a
// union and from a difference's subtrahends, and empties an intersection.
// Children of the other dimension are left out of `node` here; returns
// `node`, or an empty node in its place for such an intersection.
// (OpenSCAD's preview draws a 2D child among solids as a thin slab; the
// exact result, and the export, have none.)
int Parser::keepOneDimension(int node) {
    Node& n = tree_.nodes[static_cast<std::size_t>(node)];
    if (n.kind == NodeKind::Leaf || n.children.size() < 2) return node;
    int dimension = 0;
    bool mixed = false;
    for (int c : n.children) {
        const int d = dimensionOf(c);
        if (d == 0) continue;
        if (dimension == 0) dimension = d;
        mixed = mixed || d != dimension;
    }
    if (!mixed) return node;
    const std::string op = n.kind == NodeKind::Intersection ? "an intersection"
                           : n.kind == NodeKind::Difference ? "a difference"
                                                            : "a union";
    std::vector<int> kept;
    for (int c : n.children) {
        const int d = dimensionOf(c);
        if (d == 0 || d == dimension) {
            kept.push_back(c);
            continue;
        }
        const Node& child = tree_.nodes[static_cast<std::size_t>(c)];
        const SourceLocation& at =
            child.kind == NodeKind::Leaf ? tree_.leaves[static_cast<std::size_t>(child.leaf)].where : child.where;
        warnOnce(dimension == 3 ? "2d-in-3d" : "3d-in-2d", at,
                 dimension == 3 ? "a 2D object in " + op + " of solids is ignored, as OpenSCAD ignores it"
                                : "a solid in " + op + " of 2D objects is ignored, as OpenSCAD ignores it");
    }
    if (n.kind == NodeKind::Intersection) return emptyNode(n.where);
    n.children = std::move(kept);
    return node;
}

// Whether every child of `node` is a flat slab leaf: a 2D operation in OpenSCAD.
bool Parser::flatChildren(int node) const {
    for (int c : tree_.nodes[static_cast<std::size_t>(node)].children) {
        const Node& child = tree_.nodes[static_cast<std::size_t>(c)];
        if (child.kind != NodeKind::Leaf ||
            !std::holds_alternative<FlatSlab>(tree_.leaves[static_cast<std::size_t>(child.leaf)].primitive)) {
            return false;
        }
    }
    return true;
}

FlatPrimitive Parser::flatShape(Module module, const std::vector<CsgArgument>& args, const SourceLocation& where) {
    switch (module) {
        case Module::Square: return square(args);
        case Module::Circle: return circle(args, where);
        case Module::Polygon: return polygon(args, where);
        case Module::Text: return text(args, where);
        default: return flatImport(args, where);
    }
}

Square Parser::square(const std::vector<CsgArgument>& args) {
    Square sq;
    const CsgArgument* size = find(args, "size", 0);
    if (size != nullptr && size->value.type != CsgValue::Type::Undef) {
        if (size->value.type == CsgValue::Type::Number) {
            sq.size = glm::dvec2(number(*size, "size"));
        } else if (size->value.type == CsgValue::Type::Numbers && size->value.numbers.size() == 2) {
            sq.size = {size->value.numbers[0], size->value.numbers[1]};
            if (!std::isfinite(sq.size.x) || !std::isfinite(sq.size.y)) lex_.failAt(size->where, "size must be finite");
        } else {
            lex_.failAt(size->where, "size must be a number or a vector of 2 numbers");
        }
        if (sq.size.x < 0 || sq.size.y < 0) lex_.failAt(size->where, "size must not be negative");
    }
    sq.center = boolean(args, "center", 1, false);
    return sq;
}

Circle Parser::circle(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Circle c;
    c.r = radius(args, "r", "d", 1.0, 0);
    c.fragments = fragments(args, where);
    return c;
}

Polygon Parser::polygon(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Polygon p;
    const CsgArgument* points = find(args, "points", 0);
    if (points == nullptr) lex_.failAt(where, "polygon has no points");
    const CsgValue& pv = points->value;
    if (pv.type == CsgValue::Type::Undef || (pv.type == CsgValue::Type::Numbers && pv.numbers.empty())) return p;
    if (pv.type != CsgValue::Type::Rows) lex_.failAt(points->where, "points must be a vector of 2-vectors of numbers");
    p.points.reserve(pv.rowCount());
    for (std::size_t r = 0; r < pv.rowCount(); ++r) {
        const std::size_t b = pv.rowBegin(r);
        if (pv.rowEnds[r] - b != 2) lex_.failAt(points->where, "point " + std::to_string(r) + " does not have 2 coordinates");
        const glm::dvec2 q(pv.numbers[b], pv.numbers[b + 1]);
        if (!std::isfinite(q.x) || !std::isfinite(q.y)) lex_.failAt(points->where, "point " + std::to_string(r) + " is not finite");
        p.points.push_back(q);
    }
    const CsgArgument* paths = find(args, "paths", 1);
    if (paths == nullptr || paths->value.type == CsgValue::Type::Undef) return p;
    const CsgValue& fv = paths->value;
    if (fv.type == CsgValue::Type::Numbers && fv.numbers.empty()) return p;
    if (fv.type != CsgValue::Type::Rows) lex_.failAt(paths->where, "paths must be a vector of vectors of point indices");
    bool outOfRange = false;
    for (std::size_t r = 0; r < fv.rowCount(); ++r) {
        std::vector<int> path;
        for (std::size_t k = fv.rowBegin(r); k < fv.rowEnds[r]; ++k) {
            // OpenSCAD truncates an index to an unsigned integer and skips those past the points.
            const double idx = fv.numbers[k];
            if (idx >= 0 && idx < static_cast<double>(p.points.size())) path.push_back(static_cast<int>(idx));
            else outOfRange = true;
        }
        p.paths.push_back(std::move(path));
    }
    if (outOfRange) warnOnce("polygon-index", paths->where, "polygon path index out of bounds; the point is skipped");
    return p;
}

Text Parser::text(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Text t;
    const CsgArgument* str = find(args, "text", 0);
    if (str != nullptr && str->value.type == CsgValue::Type::Number) {
        std::ostringstream out;
        out << str->value.number;
        t.text = out.str();
    } else {
        t.text = string(args, "text", 0, "");
    }
    t.size = number(args, "size", 1, 10.0);
    t.spacing = number(args, "spacing", -1, 1.0);
    t.font = string(args, "font", 2, "");
    t.direction = string(args, "direction", -1, "ltr");
    t.language = string(args, "language", -1, "en");
    t.script = string(args, "script", -1, "Latn");
    t.halign = string(args, "halign", -1, "left");
    t.valign = string(args, "valign", -1, "baseline");
    if (t.halign == "default") t.halign = "left";        // the newer dialect's spelling of the default
    if (t.valign == "default") t.valign = "baseline";
    t.fragments = fragments(args, where);
    return t;
}

FlatImport Parser::flatImport(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    FlatImport imp;
    const CsgArgument* file = find(args, "file", 0);
    imp.path = resolvePath(*file, "import");
    imp.layer = string(args, "layer", -1, "");
    const CsgArgument* origin = find(args, "origin", -1);
    if (origin != nullptr && origin->value.type == CsgValue::Type::Numbers && origin->value.numbers.size() == 2) {
        imp.origin = {origin->value.numbers[0], origin->value.numbers[1]};
        if (!std::isfinite(imp.origin.x) || !std::isfinite(imp.origin.y)) lex_.failAt(origin->where, "origin must be finite");
    }
    imp.scale = number(args, "scale", -1, 1.0);
    imp.center = boolean(args, "center", -1, false);
    imp.dpi = number(args, "dpi", -1, 72.0);
    if (!(imp.dpi > 0)) imp.dpi = 72.0;
    imp.fragments = fragments(args, where);
    return imp;
}

Offset Parser::offset(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Offset o;
    const CsgArgument* r = find(args, "r", 0);
    const CsgArgument* delta = find(args, "delta", -1);
    if (r != nullptr && r->value.type == CsgValue::Type::Number) {
        o.amount = number(*r, "r");
    } else if (delta != nullptr && delta->value.type == CsgValue::Type::Number) {
        o.amount = number(*delta, "delta");
        o.join = boolean(args, "chamfer", -1, false) ? Offset::Join::Square : Offset::Join::Miter;
    }
    o.fragments = fragments(args, where);
    return o;
}

LinearExtrude Parser::linearExtrude(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    LinearExtrude e;
    if (find(args, "file", -1) != nullptr) unsupported("linear_extrude(file)", where);
    e.height = number(args, "height", 0, 100.0);
    const CsgArgument* v = find(args, "v", -1);
    if (v != nullptr && v->value.type != CsgValue::Type::Undef) {
        // The newer dialect's slanted extrusion: `height` is its length along v.
        if (v->value.type != CsgValue::Type::Numbers || v->value.numbers.size() != 3) {
            lex_.failAt(v->where, "v must be a vector of 3 numbers");
        }
        const glm::dvec3 d(v->value.numbers[0], v->value.numbers[1], v->value.numbers[2]);
        const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        if (!std::isfinite(length)) lex_.failAt(v->where, "v must be finite");
        if (length > 0) e.direction = d / length;
    }
    if (number(args, "segments", -1, 0.0) > 0) {
        warnOnce("extrude-segments", where, "linear_extrude's segments is not supported yet; ignored");
    }
    if (!(e.height > 0) || !(e.direction.z > 0)) e.height = 0;  // nothing upward: OpenSCAD makes nothing
    e.center = boolean(args, "center", -1, false);
    e.twist = number(args, "twist", -1, 0.0);
    e.hasTwist = e.twist != 0.0;
    const double slices = number(args, "slices", -1, 0.0);
    e.hasSlices = slices >= 1;
    if (e.hasSlices) {
        if (slices > options_.maxFragments) {
            warnOnce("slices-clamp", where, "slices = " + std::to_string(slices) + " is clamped to " +
                                                std::to_string(static_cast<int>(options_.maxFragments)));
        }
        e.slices = static_cast<int>(std::min(slices, options_.maxFragments));
    }
    const CsgArgument* scale = find(args, "scale", -1);
    if (scale != nullptr && scale->value.type == CsgValue::Type::Number) {
        e.scale = glm::dvec2(number(*scale, "scale"));
    } else if (scale != nullptr && scale->value.type == CsgValue::Type::Numbers && scale->value.numbers.size() == 2) {
        e.scale = {scale->value.numbers[0], scale->value.numbers[1]};
        if (!std::isfinite(e.scale.x) || !std::isfinite(e.scale.y)) lex_.failAt(scale->where, "scale must be finite");
    } else if (scale != nullptr && scale->value.type != CsgValue::Type::Undef) {
        lex_.failAt(scale->where, "scale must be a number or a vector of 2 numbers");
    }
    e.scale = glm::max(e.scale, glm::dvec2(0.0));
    e.fragments = fragments(args, where);
    return e;
}

RotateExtrude Parser::rotateExtrude(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    RotateExtrude e;
    if (find(args, "file", -1) != nullptr) unsupported("rotate_extrude(file)", where);
    e.angle = number(args, "angle", -1, 360.0);
    if (e.angle <= -360 || e.angle > 360) e.angle = 360;
    const CsgArgument* start = find(args, "start", -1);
    if (start != nullptr && start->value.type != CsgValue::Type::Undef) {
        e.start = number(*start, "start");
        e.hasStart = true;
    }
    e.fragments = fragments(args, where);
    return e;
}

}  // namespace strata::scene::detail
