#include "strata/scene/CsgParser.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <unordered_set>
#include <utility>

#include "CsgLexer.h"
#include "CsgValue.h"

namespace strata::scene {

namespace {

constexpr int kMaxVectorNesting = 64;
constexpr int kMaxBlockNesting = 100000;

// OpenSCAD modules strata knows but does not render yet: their subtree is left
// out with one warning per name.
const std::unordered_set<std::string>& unsupportedNames() {
    static const std::unordered_set<std::string> names = {
        "linear_extrude", "rotate_extrude", "hull", "minkowski", "text", "offset", "surface",
        "projection", "square", "circle", "polygon", "resize", "roof", "fill", "import_dxf",
        "import_stl", "import_off", "dxf_linear_extrude", "dxf_rotate_extrude", "child",
        "children", "parent_module", "intersection_for", "for", "let", "each", "echo", "assert",
        "textmetrics", "fontmetrics", "virtual", "wrap",
    };
    return names;
}

// Everything a statement passes to its children.
struct Context {
    glm::dmat4 transform{1.0};
    glm::dvec4 color{-1.0, -1.0, -1.0, -1.0};  // per component: < 0 is unset
    Display display = Display::Normal;
};

// A block ({ ... } or a single child statement) being filled with children.
struct Open {
    int node = -1;          // the node collecting children, -1 when they are dropped
    Context context;
    bool braces = true;     // false: ends after one child statement
    bool collapsible = false;  // group-like: a single child may replace it
    bool isBackgroundRoot = false;
    bool isRoot = false;    // opened by '!'
};

class Parser {
public:
    Parser(std::istream& in, const std::string& name, std::string baseDir, const ParseOptions& options)
        : lex_(in, name), baseDir_(std::move(baseDir)), options_(options) {
        tree_.source = name;
    }

    Tree parse();

private:
    // Statements
    void statement();
    void closeBlock();
    void closeOne();
    void pushBlock(Open open, const SourceLocation& where);
    void statementFinished();
    void attach(int child, const Open& parent);
    std::vector<CsgArgument> arguments();
    CsgValue value(int depth);
    void vectorRest(CsgValue& v, int depth);
    static bool keywordValue(const std::string& word, CsgValue& out);
    bool isSign() const;
    bool isNumberStart() const;
    double signedNumber();

    // Nodes
    int makeLeaf(const std::string& name, const std::vector<CsgArgument>& args, const Context& ctx,
                 const SourceLocation& where);
    Cube cube(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Sphere sphere(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Cylinder cylinder(const std::vector<CsgArgument>& args, const SourceLocation& where);
    std::optional<Polyhedron> polyhedron(const std::vector<CsgArgument>& args, const SourceLocation& where);
    std::optional<Import> import(const std::vector<CsgArgument>& args, const SourceLocation& where);
    glm::dmat4 multmatrix(const std::vector<CsgArgument>& args, const SourceLocation& where);
    glm::dvec4 color(const std::vector<CsgArgument>& args, const SourceLocation& where);

    // Arguments
    const CsgArgument* find(const std::vector<CsgArgument>& args, const char* name, int position) const;
    double number(const CsgArgument& a, const char* what) const;
    double number(const std::vector<CsgArgument>& args, const char* name, int position, double fallback) const;
    bool boolean(const std::vector<CsgArgument>& args, const char* name, int position, bool fallback) const;
    Fragments fragments(const std::vector<CsgArgument>& args, const SourceLocation& where);
    void warnOnce(const std::string& key, const SourceLocation& where, const std::string& message);
    void unsupported(const std::string& name, const SourceLocation& where);

    void expectPunct(char c, const char* context);
    void compact();

    CsgLexer lex_;
    std::string baseDir_;
    ParseOptions options_;
    Tree tree_;
    std::vector<Open> stack_;
    std::set<std::string> warned_;
    int rootNode_ = -1;      // node of the first '!' subtree, if any
    bool sawStatement_ = false;
};

Tree Parser::parse() {
    Open top;
    top.node = tree_.addNode(NodeKind::Union, {});
    top.braces = true;
    tree_.nodes[static_cast<std::size_t>(top.node)].where = SourceLocation{tree_.source, 1, 1};
    stack_.push_back(top);
    lex_.next();
    for (;;) {
        if (lex_.token() == Token::End) {
            if (stack_.size() > 1) {
                if (!stack_.back().braces) lex_.fail("unexpected end of file: expected ';' or a child statement");
                lex_.fail("unexpected end of file: missing '}'");
            }
            break;
        }
        if (lex_.token() == Token::Punct && lex_.punct() == '}') {
            if (stack_.size() > 1 && !stack_.back().braces) lex_.fail("expected ';' or a child statement before '}'");
            if (stack_.size() == 1) lex_.fail("unexpected '}'");
            lex_.next();
            closeBlock();
            continue;
        }
        statement();
    }
    if (lex_.bytesRead() == 0) lex_.fail("empty file");
    if (!sawStatement_) {
        // OpenSCAD exports a model with no geometry (e.g. only echo()) as a
        // blank line: an empty scene, not an error.
        tree_.warnings.push_back(Warning{tree_.source + ": warning: the scene has no statements; nothing to draw"});
    }
    tree_.root = rootNode_ >= 0 ? rootNode_ : top.node;
    const Node& topNode = tree_.nodes[static_cast<std::size_t>(top.node)];
    if (tree_.root == top.node && topNode.children.size() == 1) tree_.root = topNode.children.front();
    compact();
    return std::move(tree_);
}

void Parser::expectPunct(char c, const char* context) {
    if (lex_.token() != Token::Punct || lex_.punct() != c) {
        std::string got;
        switch (lex_.token()) {
            case Token::End: got = "end of file"; break;
            case Token::Identifier: got = "'" + lex_.text() + "'"; break;
            case Token::Number: got = "a number"; break;
            case Token::String: got = "a string"; break;
            case Token::Punct: got = std::string("'") + lex_.punct() + "'"; break;
        }
        lex_.fail(std::string("expected '") + c + "' " + context + ", got " + got);
    }
    lex_.next();
}

// modifier* name ( args ) ( ';' | '{' | statement )
void Parser::statement() {
    if (lex_.token() == Token::Punct && lex_.punct() == ';') {  // empty statement
        lex_.next();
        statementFinished();
        return;
    }
    SourceLocation where = lex_.where();
    bool background = false, highlight = false, root = false, disabled = false;
    while (lex_.token() == Token::Punct &&
           (lex_.punct() == '%' || lex_.punct() == '#' || lex_.punct() == '!' || lex_.punct() == '*')) {
        switch (lex_.punct()) {
            case '%': background = true; break;
            case '#': highlight = true; break;
            case '!': root = true; break;
            default: disabled = true; break;
        }
        lex_.next();
    }
    if (lex_.token() != Token::Identifier) {
        if (lex_.token() == Token::End) lex_.fail("unexpected end of file: expected a statement");
        lex_.fail("expected a module name");
    }
    std::string name = lex_.text();
    SourceLocation nameWhere = lex_.where();
    // Modifiers are written at column 0 before the tabs; the node is where its name is.
    where = nameWhere;
    lex_.next();
    expectPunct('(', ("after '" + name + "'").c_str());
    std::vector<CsgArgument> args = arguments();
    sawStatement_ = true;

    const Open& parent = stack_.back();
    const bool dropped = parent.node < 0 || disabled;
    Context ctx = parent.context;
    if (background) ctx.display = Display::Background;
    else if (highlight && ctx.display == Display::Normal) ctx.display = Display::Highlight;
    if (root && rootNode_ < 0 && !dropped) {
        ctx = Context{};  // '!' makes this subtree the whole scene, without its ancestors' transforms
        if (highlight) ctx.display = Display::Highlight;
    }

    const bool hasBlock = !(lex_.token() == Token::Punct && lex_.punct() == ';');
    bool braces = false;
    if (!hasBlock) {
        lex_.next();
    } else if (lex_.token() == Token::Punct && lex_.punct() == '{') {
        braces = true;
        lex_.next();
    } else if (lex_.token() == Token::End) {
        lex_.fail("unexpected end of file after '" + name + "(...)': expected ';' or '{'");
    }

    Open open;
    open.braces = braces;
    open.context = ctx;
    open.isBackgroundRoot = background && parent.context.display != Display::Background;
    open.isRoot = root && rootNode_ < 0 && !dropped;

    int leafNode = -1;
    NodeKind kind = NodeKind::Union;
    bool known = true;
    bool leafLike = false;
    if (name == "group" || name == "union" || name == "render" || name == "assign") {
        kind = NodeKind::Union;
        open.collapsible = true;
    } else if (name == "intersection") {
        kind = NodeKind::Intersection;
    } else if (name == "difference") {
        kind = NodeKind::Difference;
    } else if (name == "multmatrix") {
        if (!dropped) open.context.transform = ctx.transform * multmatrix(args, where);
        open.collapsible = true;
    } else if (name == "color") {
        if (!dropped) {
            glm::dvec4 c = color(args, where);
            for (int i = 0; i < 4; ++i) {
                if (open.context.color[i] < 0.0) open.context.color[i] = c[i];  // outermost wins
            }
        }
        open.collapsible = true;
    } else if (name == "cube" || name == "sphere" || name == "cylinder" || name == "polyhedron" ||
               name == "import") {
        leafLike = true;
        if (!dropped) leafNode = makeLeaf(name, args, ctx, where);
    } else if (unsupportedNames().count(name) != 0) {
        known = false;
        if (!dropped) unsupported(name, where);
    } else {
        lex_.failAt(where, "unknown module '" + name + "'");
    }

    if (leafLike) {
        if (leafNode >= 0) {
            if (open.isRoot) rootNode_ = leafNode;
            else if (open.isBackgroundRoot) tree_.background.push_back(leafNode);
            else attach(leafNode, parent);
        }
        if (!hasBlock) {
            statementFinished();
        } else {
            // A primitive with children: OpenSCAD ignores them; so do we, but parse them.
            open.node = -1;
            pushBlock(std::move(open), where);
        }
        return;
    }

    if (!known || dropped) {
        open.node = -1;
    } else {
        open.node = tree_.addNode(kind, {});
        tree_.nodes[static_cast<std::size_t>(open.node)].where = where;
    }
    pushBlock(std::move(open), where);
    // No children at all: an empty group, difference or intersection.
    if (!hasBlock) closeBlock();
}

void Parser::pushBlock(Open open, const SourceLocation& where) {
    if (stack_.size() >= static_cast<std::size_t>(kMaxBlockNesting)) lex_.failAt(where, "nesting too deep");
    stack_.push_back(std::move(open));
}

// Closes the innermost block, then every brace-less block that it ends.
void Parser::closeBlock() {
    closeOne();
    statementFinished();
}

// Pops the innermost block and hands its node to the parent block.
void Parser::closeOne() {
    Open open = std::move(stack_.back());
    stack_.pop_back();
    if (open.node >= 0) {
        int node = open.node;
        Node& n = tree_.nodes[static_cast<std::size_t>(node)];
        if (open.collapsible && n.children.size() == 1) node = n.children.front();
        if (open.isRoot) rootNode_ = node;
        else if (open.isBackgroundRoot) tree_.background.push_back(node);
        else attach(node, stack_.back());
    }
}

// A statement just ended: blocks written without braces (`name(args) child;`)
// end with their one child.
void Parser::statementFinished() {
    while (stack_.size() > 1 && !stack_.back().braces) closeOne();
}

void Parser::attach(int child, const Open& parent) {
    if (parent.node < 0) return;
    tree_.nodes[static_cast<std::size_t>(parent.node)].children.push_back(child);
}

std::vector<CsgArgument> Parser::arguments() {
    std::vector<CsgArgument> args;
    if (lex_.token() == Token::Punct && lex_.punct() == ')') {
        lex_.next();
        return args;
    }
    for (;;) {
        CsgArgument a;
        a.where = lex_.where();
        if (lex_.token() == Token::Identifier) {
            // name = value, or a bare identifier value (true/false/undef/inf/nan)
            std::string word = lex_.text();
            lex_.next();
            if (lex_.token() == Token::Punct && lex_.punct() == '=') {
                lex_.next();
                a.name = std::move(word);
                a.where = lex_.where();
                a.value = value(0);
            } else {
                // Re-interpret the identifier as a value.
                if (!keywordValue(word, a.value))
                    lex_.failAt(a.where, "unexpected identifier '" + word + "' in arguments");
            }
        } else {
            a.value = value(0);
        }
        args.push_back(std::move(a));
        if (lex_.token() == Token::Punct && lex_.punct() == ',') {
            lex_.next();
            continue;
        }
        expectPunct(')', "to close the argument list");
        return args;
    }
}

CsgValue Parser::value(int depth) {
    CsgValue v;
    if (lex_.token() == Token::Number) {
        v.type = CsgValue::Type::Number;
        v.number = lex_.number();
        lex_.next();
        return v;
    }
    if (isSign()) {
        v.type = CsgValue::Type::Number;
        v.number = signedNumber();
        return v;
    }
    if (lex_.token() == Token::String) {
        v.type = CsgValue::Type::String;
        v.string = lex_.text();
        lex_.next();
        return v;
    }
    if (lex_.token() == Token::Identifier) {
        const std::string& w = lex_.text();
        if (!keywordValue(w, v)) lex_.fail("unexpected identifier '" + w + "' in a value");
        lex_.next();
        return v;
    }
    if (lex_.token() == Token::Punct && lex_.punct() == '[') {
        if (depth >= kMaxVectorNesting) lex_.fail("vector nested too deeply");
        lex_.next();
        v.type = CsgValue::Type::Numbers;  // empty vector until the first element decides
        vectorRest(v, depth);
        return v;
    }
    if (lex_.token() == Token::End) lex_.fail("unexpected end of file in a value");
    lex_.fail("expected a value");
}

// The values written as words: true, false, undef, inf, nan. False for any other word.
bool Parser::keywordValue(const std::string& word, CsgValue& out) {
    if (word == "true" || word == "false") {
        out.type = CsgValue::Type::Bool;
        out.boolean = word == "true";
    } else if (word == "undef") {
        out.type = CsgValue::Type::Undef;
    } else if (word == "inf" || word == "nan") {
        out.type = CsgValue::Type::Number;
        out.number = word == "inf" ? HUGE_VAL : std::nan("");
    } else {
        return false;
    }
    return true;
}

bool Parser::isSign() const {
    return lex_.token() == Token::Punct && (lex_.punct() == '-' || lex_.punct() == '+');
}

bool Parser::isNumberStart() const {
    return lex_.token() == Token::Number || isSign();
}

// A number with any run of signs before it, folded in a loop so that a
// million '-' cost no stack. Also takes inf and nan after a sign.
double Parser::signedNumber() {
    bool negate = false;
    SourceLocation at = lex_.where();
    while (isSign()) {
        if (lex_.punct() == '-') negate = !negate;
        lex_.next();
    }
    double x;
    if (lex_.token() == Token::Number) {
        x = lex_.number();
    } else if (lex_.token() == Token::Identifier && (lex_.text() == "inf" || lex_.text() == "nan")) {
        x = lex_.text() == "inf" ? HUGE_VAL : std::nan("");
    } else {
        lex_.failAt(at, "unary sign before a non-number");
    }
    lex_.next();
    return negate ? -x : x;
}

// Parses the elements of a vector whose '[' is consumed, up to and including
// its ']'. Numbers and rows of numbers (points, faces, matrices) go straight
// into the flat arrays: no temporary value per element.
void Parser::vectorRest(CsgValue& v, int depth) {
    if (lex_.token() == Token::Punct && lex_.punct() == ']') {
        lex_.next();
        return;
    }
    for (;;) {
        const bool flatNumbers = v.type == CsgValue::Type::Numbers;
        const bool flatRows = v.type == CsgValue::Type::Rows || (flatNumbers && v.numbers.empty());
        if (flatNumbers && isNumberStart()) {
            v.numbers.push_back(signedNumber());
        } else if (flatRows && lex_.token() == Token::Punct && lex_.punct() == '[') {
            if (depth + 1 >= kMaxVectorNesting) lex_.fail("vector nested too deeply");
            lex_.next();
            const std::size_t rowStart = v.numbers.size();
            bool atElement = true;  // false once a number was not followed by ','
            while (isNumberStart()) {
                v.numbers.push_back(signedNumber());
                atElement = lex_.token() == Token::Punct && lex_.punct() == ',';
                if (!atElement) break;
                lex_.next();
            }
            if (lex_.token() == Token::Punct && lex_.punct() == ']') {
                lex_.next();
                v.type = CsgValue::Type::Rows;
                v.rowEnds.push_back(static_cast<std::uint32_t>(v.numbers.size()));
            } else if (!atElement) {
                expectPunct(']', "to close the vector");
            } else {
                // Not a row of numbers after all: finish it as a general vector.
                CsgValue row;
                row.type = CsgValue::Type::Numbers;
                row.numbers.assign(v.numbers.begin() + static_cast<std::ptrdiff_t>(rowStart), v.numbers.end());
                v.numbers.resize(rowStart);
                if (v.rowEnds.empty()) v.type = CsgValue::Type::Numbers;  // nothing flat yet
                if (!row.numbers.empty()) row.toList();  // the next element is not a number
                vectorRest(row, depth + 1);
                v.append(std::move(row));
            }
        } else {
            v.append(value(depth + 1));
        }
        if (lex_.token() == Token::Punct && lex_.punct() == ',') {
            lex_.next();
            continue;
        }
        expectPunct(']', "to close the vector");
        return;
    }
}

const CsgArgument* Parser::find(const std::vector<CsgArgument>& args, const char* name, int position) const {
    for (const CsgArgument& a : args) {
        if (!a.name.empty() && a.name == name) return &a;
    }
    int p = 0;
    for (const CsgArgument& a : args) {
        if (!a.name.empty()) continue;
        if (p == position) return &a;
        ++p;
    }
    return nullptr;
}

double Parser::number(const CsgArgument& a, const char* what) const {
    if (a.value.type != CsgValue::Type::Number) {
        lex_.failAt(a.where, std::string(what) + " must be a number, not a " + typeName(a.value.type));
    }
    if (!std::isfinite(a.value.number)) {
        lex_.failAt(a.where, std::string(what) + " must be finite, not " + (std::isnan(a.value.number) ? "nan" : "inf"));
    }
    return a.value.number;
}

double Parser::number(const std::vector<CsgArgument>& args, const char* name, int position, double fallback) const {
    const CsgArgument* a = find(args, name, position);
    if (a == nullptr || a->value.type == CsgValue::Type::Undef) return fallback;
    return number(*a, name);
}

bool Parser::boolean(const std::vector<CsgArgument>& args, const char* name, int position, bool fallback) const {
    const CsgArgument* a = find(args, name, position);
    if (a == nullptr || a->value.type == CsgValue::Type::Undef) return fallback;
    if (a->value.type == CsgValue::Type::Bool) return a->value.boolean;
    if (a->value.type == CsgValue::Type::Number) return a->value.number != 0.0;
    lex_.failAt(a->where, std::string(name) + " must be true or false, not a " + typeName(a->value.type));
}

void Parser::warnOnce(const std::string& key, const SourceLocation& where, const std::string& message) {
    if (!warned_.insert(key).second) return;
    tree_.warnings.push_back(Warning{where.str() + ": warning: " + message});
}

void Parser::unsupported(const std::string& name, const SourceLocation& where) {
    ++tree_.unsupported[name];
    warnOnce("unsupported:" + name, where,
             "'" + name + "' is not supported yet; its subtree is left out (further '" + name +
                 "' nodes are counted, not reported)");
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
    const CsgArgument* r = find(args, "r", 0);
    const CsgArgument* d = find(args, "d", -1);
    if (r != nullptr && r->value.type != CsgValue::Type::Undef) {
        s.r = number(*r, "r");
        if (s.r < 0) lex_.failAt(r->where, "r must not be negative");
    } else if (d != nullptr && d->value.type != CsgValue::Type::Undef) {
        s.r = number(*d, "d") / 2.0;
        if (s.r < 0) lex_.failAt(d->where, "d must not be negative");
    }
    s.fragments = fragments(args, where);
    return s;
}

Cylinder Parser::cylinder(const std::vector<CsgArgument>& args, const SourceLocation& where) {
    Cylinder c;
    auto radius = [&](const char* rname, const char* dname, double fallback, int position) {
        const CsgArgument* r = find(args, rname, position);
        if (r != nullptr && r->value.type != CsgValue::Type::Undef) {
            double v = number(*r, rname);
            if (v < 0) lex_.failAt(r->where, std::string(rname) + " must not be negative");
            return v;
        }
        const CsgArgument* d = find(args, dname, -1);
        if (d != nullptr && d->value.type != CsgValue::Type::Undef) {
            double v = number(*d, dname) / 2.0;
            if (v < 0) lex_.failAt(d->where, std::string(dname) + " must not be negative");
            return v;
        }
        return fallback;
    };
    const CsgArgument* h = find(args, "h", 0);
    if (h != nullptr && h->value.type != CsgValue::Type::Undef) {
        c.h = number(*h, "h");
        if (c.h < 0) lex_.failAt(h->where, "h must not be negative");
    }
    double r = radius("r", "d", 1.0, 1);
    c.r1 = radius("r1", "d1", r, 2);
    c.r2 = radius("r2", "d2", r, 3);
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
    std::filesystem::path path(file->value.string);
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".stl" && ext != ".off" && ext != ".obj" && ext != ".ply") {
        unsupported("import" + (ext.empty() ? std::string() : "(" + ext + ")"), where);
        return std::nullopt;
    }
    if (path.is_relative() && !baseDir_.empty()) path = std::filesystem::path(baseDir_) / path;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        lex_.failAt(file->where, "import file not found: " + path.string());
    }
    return Import{path.lexically_normal().string()};
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

int Parser::makeLeaf(const std::string& name, const std::vector<CsgArgument>& args, const Context& ctx,
                     const SourceLocation& where) {
    Leaf leaf;
    if (name == "cube") leaf.primitive = cube(args, where);
    else if (name == "sphere") leaf.primitive = sphere(args, where);
    else if (name == "cylinder") leaf.primitive = cylinder(args, where);
    else if (name == "polyhedron") {
        std::optional<Polyhedron> p = polyhedron(args, where);
        if (!p) return -1;
        leaf.primitive = std::move(*p);
    } else {
        std::optional<Import> imported = import(args, where);
        if (!imported) return -1;
        leaf.primitive = std::move(*imported);
    }
    leaf.transform = ctx.transform;
    if (ctx.color.r >= 0.0 || ctx.color.g >= 0.0 || ctx.color.b >= 0.0 || ctx.color.a >= 0.0) leaf.color = ctx.color;
    leaf.display = ctx.display;
    leaf.where = where;
    return tree_.addLeaf(std::move(leaf));
}

// Keeps only nodes reachable from the root and the background roots, in
// depth-first order, so consumers can walk `nodes` without orphans.
void Parser::compact() {
    std::vector<int> remap(tree_.nodes.size(), -1);
    std::vector<Node> kept;
    kept.reserve(tree_.nodes.size());
    std::vector<int> order;
    std::vector<int> todo;
    auto visit = [&](int start) {
        todo.push_back(start);
        while (!todo.empty()) {
            int n = todo.back();
            todo.pop_back();
            if (remap[static_cast<std::size_t>(n)] >= 0) continue;
            remap[static_cast<std::size_t>(n)] = static_cast<int>(order.size());
            order.push_back(n);
            const auto& children = tree_.nodes[static_cast<std::size_t>(n)].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it) todo.push_back(*it);
        }
    };
    if (tree_.root >= 0) visit(tree_.root);
    for (int b : tree_.background) visit(b);
    for (int n : order) {
        Node node = std::move(tree_.nodes[static_cast<std::size_t>(n)]);
        for (int& c : node.children) c = remap[static_cast<std::size_t>(c)];
        kept.push_back(std::move(node));
    }
    // Leaves no node refers to (e.g. under a later '!' root) are dropped too.
    std::vector<int> leafRemap(tree_.leaves.size(), -1);
    std::vector<Leaf> leaves;
    for (Node& node : kept) {
        if (node.kind != NodeKind::Leaf) continue;
        int& mapped = leafRemap[static_cast<std::size_t>(node.leaf)];
        if (mapped < 0) {
            mapped = static_cast<int>(leaves.size());
            leaves.push_back(std::move(tree_.leaves[static_cast<std::size_t>(node.leaf)]));
        }
        node.leaf = mapped;
    }
    tree_.root = tree_.root >= 0 ? remap[static_cast<std::size_t>(tree_.root)] : -1;
    for (int& b : tree_.background) b = remap[static_cast<std::size_t>(b)];
    tree_.nodes = std::move(kept);
    tree_.leaves = std::move(leaves);
}

}  // namespace

Tree parseCsg(std::istream& in, const std::string& name, const std::string& baseDir, const ParseOptions& options) {
    Parser parser(in, name, baseDir, options);
    return parser.parse();
}

Tree parseCsgFile(const std::string& path, const ParseOptions& options) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(SourceLocation{path, 0, 0}, "is a directory, not a scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(SourceLocation{path, 0, 0}, "cannot open file");
    std::string baseDir = std::filesystem::path(path).parent_path().string();
    return parseCsg(in, path, baseDir, options);
}

}  // namespace strata::scene
