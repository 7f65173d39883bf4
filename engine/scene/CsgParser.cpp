#include "strata/scene/CsgParser.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>
#include <variant>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "CsgLexer.h"
#include "CsgModules.h"
#include "strata/core/InputFile.h"
#include "strata/scene/ImportFormats.h"
#include "CsgValue.h"

namespace strata::scene {

namespace {

constexpr int kMaxVectorNesting = 64;

// Everything a statement passes to its children.
struct Context {
    glm::dmat4 transform{1.0};
    std::shared_ptr<const TransformStep> steps;  // the multmatrix() chain `transform` is the product of
    // What `transform` is relative to: identity, except below a hull,
    // minkowski or resize, whose children are placed relative to the node.
    glm::dmat4 frame{1.0};
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
    bool flat = false;      // its statements are 2D: they go to the pending flat tree
    int flatNode = -1;      // the flat node collecting children, -1 when they are dropped
    bool ownsFlat = false;  // closing it turns the pending flat tree into a leaf
    enum class Gather { None, Hull, Minkowski, Resize, Projection };
    Gather gather = Gather::None;  // hull() or minkowski() of solids: its children become one or more hull leaves
    glm::dmat4 placement{1.0};     // hull() or minkowski(): its own transform, which places its result
    std::size_t resizesBefore = 0; // hull() or minkowski(): Tree::resizes when it opened (later ones are inside it)
    Resize resize;                 // resize(): its arguments and placement, filled in when it closes
    bool cut = false;              // projection(cut = ...)
    int flatParent = -1;           // projection() in a flat tree: the flat node its shape joins
    Context outside;               // projection() among solids: where its slab goes
    bool shape = false;            // reads its children into a shape of its own (ParseOptions::maxNestedShapes)
};

// A leaf whose flat tree is being read: an extrusion, or a 2D shape outside one.
struct PendingFlat {
    Leaf leaf;        // its primitive's FlatTree is filled in when the block closes
    FlatTree tree;
};

bool isFlatImportPath(const std::string& file) { return isImportPath(file, ImportKind::Drawing); }

class Parser {
public:
    Parser(std::istream& in, const std::string& name, std::string baseDir, const ParseOptions& options)
        : lex_(in, name, options.locate), baseDir_(std::move(baseDir)), options_(options) {
        tree_.source = name;
    }

    Tree parse();

private:
    // Statements
    // One statement: its head, then what its name makes of it.
    struct Statement {
        std::string name;
        Module module = Module::Unknown;  // what the name is (CsgModules.h)
        std::vector<CsgArgument> args;
        SourceLocation where;  // the name's position
        bool background = false, highlight = false, root = false, disabled = false;  // % # ! *
        bool dropped = false;  // under a dropped parent, or '*'
        bool hasBlock = false, braces = false;
    };
    void statement();
    Statement statementHead();
    Open openFor(const Statement& st, const Open& parent) const;
    void enterBlock(const Statement& st, Open open);
    void openProjection(const Statement& st, Open open, const Open& parent);
    void openFlatLeaf(const Statement& st, Open open);
    void leafStatement(const Statement& st, Open open, const Open& parent);
    void operationStatement(const Statement& st, Open open);
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

    // Flat (2D) statements
    int flatStatement(const Statement& st, Open& open, bool dropped);
    int finishFlat();
    Leaf leafAt(const Context& ctx, const SourceLocation& where) const;
    int mergeFlatChildren(int node, std::optional<FlatOp> op = std::nullopt, const glm::dmat4& placement = glm::dmat4(1.0),
                          const Context* shownAs = nullptr);
    Resize resizeArguments(const std::vector<CsgArgument>& args) const;
    int finishResize(const Open& open);
    int finishProjection(const Open& open);
    std::shared_ptr<Tree> extractSolid(int root);
    void exactify(int root);
    void exactifyResized(int node, std::size_t first);
    int finishGather(const Open& open);
    int emptyNode(SourceLocation where);  // by value: `where` may lie in the nodes it adds to
    bool flatChildren(int node) const;
    int dimensionOf(int node) const;
    int keepOneDimension(int node);
    bool isFlatShape(Module module, const std::vector<CsgArgument>& args) const;
    FlatPrimitive flatShape(Module module, const std::vector<CsgArgument>& args, const SourceLocation& where);
    Square square(const std::vector<CsgArgument>& args);
    Circle circle(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Polygon polygon(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Text text(const std::vector<CsgArgument>& args, const SourceLocation& where);
    FlatImport flatImport(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Offset offset(const std::vector<CsgArgument>& args, const SourceLocation& where);
    LinearExtrude linearExtrude(const std::vector<CsgArgument>& args, const SourceLocation& where);
    RotateExtrude rotateExtrude(const std::vector<CsgArgument>& args, const SourceLocation& where);
    Surface surface(const std::vector<CsgArgument>& args, const SourceLocation& where);
    std::string resolvePath(const CsgArgument& file, const char* node) const;
    std::string string(const std::vector<CsgArgument>& args, const char* name, int position, const std::string& fallback) const;
    double radius(const std::vector<CsgArgument>& args, const char* rname, const char* dname, double fallback,
                  int position) const;

    // Nodes
    int makeLeaf(Module module, const std::vector<CsgArgument>& args, const Context& ctx, const SourceLocation& where);
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
    // Flat trees being read, innermost last: a projection() inside an
    // extrusion reads solids again, which may hold extrusions of their own.
    std::vector<PendingFlat> pending_;
    PendingFlat& pending() { return pending_.back(); }
    bool sawStatement_ = false;
    int openShapes_ = 0;     // blocks on stack_ with Open::shape
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
    // The top level is a union like any other: one dimension, then flat
    // objects side by side are one flat result, as in OpenSCAD.
    keepOneDimension(top.node);
    const bool severalAtTop = tree_.nodes[static_cast<std::size_t>(top.node)].children.size() > 1;
    if (const int merged = severalAtTop ? mergeFlatChildren(top.node) : -1; merged >= 0) {
        tree_.nodes[static_cast<std::size_t>(top.node)].children = {merged};
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
    Statement st = statementHead();
    const Open& parent = stack_.back();
    st.dropped = parent.node < 0 || st.disabled;
    Open open = openFor(st, parent);
    if (st.module == Module::Projection) return openProjection(st, std::move(open), parent);
    if (parent.flat) {
        const int parentFlatNode = parent.flatNode;
        const int index = flatStatement(st, open, parentFlatNode < 0 || st.disabled || st.background);
        if (index >= 0) pending().tree.nodes[static_cast<std::size_t>(parentFlatNode)].children.push_back(index);
        return enterBlock(st, std::move(open));
    }
    if (st.module == Module::LinearExtrude || st.module == Module::RotateExtrude || st.module == Module::Offset ||
        isFlatShape(st.module, st.args)) {
        return openFlatLeaf(st, std::move(open));
    }
    if (isSolidModule(st.module) || st.module == Module::Import) return leafStatement(st, std::move(open), parent);
    operationStatement(st, std::move(open));
}

// The statement up to its body: modifiers, name, arguments, and whether a
// block ('{' or a single child statement) follows.
Parser::Statement Parser::statementHead() {
    Statement st;
    while (lex_.token() == Token::Punct &&
           (lex_.punct() == '%' || lex_.punct() == '#' || lex_.punct() == '!' || lex_.punct() == '*')) {
        switch (lex_.punct()) {
            case '%': st.background = true; break;
            case '#': st.highlight = true; break;
            case '!': st.root = true; break;
            default: st.disabled = true; break;
        }
        lex_.next();
    }
    if (lex_.token() != Token::Identifier) {
        if (lex_.token() == Token::End) lex_.fail("unexpected end of file: expected a statement");
        lex_.fail("expected a module name");
    }
    st.name = lex_.text();
    st.module = moduleNamed(st.name);
    // Modifiers are written at column 0 before the tabs; the node is where its name is.
    st.where = lex_.where();
    lex_.next();
    expectPunct('(', ("after '" + st.name + "'").c_str());
    st.args = arguments();
    sawStatement_ = true;
    st.hasBlock = !(lex_.token() == Token::Punct && lex_.punct() == ';');
    if (!st.hasBlock) {
        lex_.next();
    } else if (lex_.token() == Token::Punct && lex_.punct() == '{') {
        st.braces = true;
        lex_.next();
    } else if (lex_.token() == Token::End) {
        lex_.fail("unexpected end of file after '" + st.name + "(...)': expected ';' or '{'");
    }
    return st;
}

// The block a statement opens, with the context its modifiers make.
Open Parser::openFor(const Statement& st, const Open& parent) const {
    Context ctx = parent.context;
    if (st.background) {
        ctx.display = Display::Background;
        if (parent.context.display != Display::Background) {
            // A '%' subtree is drawn on its own, so it is placed in the world
            // even below a node that places its children relative to itself.
            ctx.transform = ctx.frame * ctx.transform;
            ctx.steps = std::make_shared<const TransformStep>(TransformStep{ctx.transform, nullptr});
            ctx.frame = glm::dmat4(1.0);
        }
    } else if (st.highlight && ctx.display == Display::Normal) {
        ctx.display = Display::Highlight;
    }
    if (st.root && rootNode_ < 0 && !st.dropped) {
        ctx = Context{};  // '!' makes this subtree the whole scene, without its ancestors' transforms
        if (st.highlight) ctx.display = Display::Highlight;
    }
    Open open;
    open.braces = st.braces;
    open.context = ctx;
    open.isBackgroundRoot = st.background && parent.context.display != Display::Background;
    open.isRoot = st.root && rootNode_ < 0 && !st.dropped;
    return open;
}

// Pushes the statement's block; a statement without one closes at once.
void Parser::enterBlock(const Statement& st, Open open) {
    pushBlock(std::move(open), st.where);
    if (!st.hasBlock) closeBlock();
}

// projection(): solids again below it, whatever the context, read as a tree of their own.
void Parser::openProjection(const Statement& st, Open open, const Open& parent) {
    const bool off = parent.flat ? (parent.flatNode < 0 || st.disabled || st.background) : st.dropped;
    open.gather = Open::Gather::Projection;
    open.cut = boolean(st.args, "cut", 0, false);
    open.flat = false;
    open.flatParent = parent.flat ? parent.flatNode : -1;
    open.outside = open.context;
    open.context = Context{};
    open.shape = !off;
    if (!off) {
        open.node = tree_.addNode(NodeKind::Union, {});
        tree_.nodes[static_cast<std::size_t>(open.node)].where = st.where;
    }
    enterBlock(st, std::move(open));
}

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

// stack_ holds the top level besides the blocks: the new block is block
// number stack_.size().
void Parser::pushBlock(Open open, const SourceLocation& where) {
    if (stack_.size() > static_cast<std::size_t>(std::max(options_.maxNesting, 0))) {
        lex_.failAt(where, "nesting too deep (more than " + std::to_string(options_.maxNesting) + " blocks)");
    }
    if (open.shape && openShapes_ >= options_.maxNestedShapes) {
        lex_.failAt(where, "nesting too deep (more than " + std::to_string(options_.maxNestedShapes) +
                               " hull, minkowski, resize, projection or extrusion levels)");
    }
    if (open.shape) ++openShapes_;
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
    if (open.shape) --openShapes_;
    int node = -1;
    if (open.ownsFlat) {
        node = finishFlat();
    } else if (open.node >= 0 && open.gather != Open::Gather::None) {
        node = finishGather(open);
    } else if (open.node >= 0) {
        node = keepOneDimension(open.node);
        if (node == open.node) {
            const Node& n = tree_.nodes[static_cast<std::size_t>(node)];
            if (open.collapsible && n.children.size() == 1) node = n.children.front();
            else if (const int merged = mergeFlatChildren(node); merged >= 0) node = merged;
        }
    }
    if (node >= 0) {
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

// A number, a sign, or the words inf and nan (which OpenSCAD writes for
// non-finite numbers): what a flat vector of numbers holds.
bool Parser::isNumberStart() const {
    return lex_.token() == Token::Number || isSign() ||
           (lex_.token() == Token::Identifier && (lex_.text() == "inf" || lex_.text() == "nan"));
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

// The file argument resolved against the .csg's folder; it must be a regular file.
std::string Parser::resolvePath(const CsgArgument& file, const char* node) const {
    if (file.value.string.find('\0') != std::string::npos) {
        std::string shown;
        for (char c : file.value.string) shown += c == '\0' ? std::string("\\0") : std::string(1, c);
        lex_.failAt(file.where, std::string(node) + " file name holds a NUL byte: '" + shown + "'");
    }
    std::filesystem::path path(file.value.string);
    if (path.is_relative() && !baseDir_.empty()) path = std::filesystem::path(baseDir_) / path;
    const std::string why = unreadableReason(path.string());
    if (why == "no such file") lex_.failAt(file.where, std::string(node) + " file not found: " + path.string());
    if (!why.empty()) lex_.failAt(file.where, std::string(node) + " cannot read '" + path.string() + "': " + why);
    return path.lexically_normal().string();
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

namespace {

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

namespace {

// Leaves whose solid is convex by construction: a Minkowski sum with them is
// the hull of vertex sums.
bool convexByConstruction(const Primitive& p) {
    return std::holds_alternative<Cube>(p) || std::holds_alternative<Sphere>(p) || std::holds_alternative<Cylinder>(p) ||
           std::holds_alternative<Hull>(p);
}

// Leaves whose parameters make no solid (a cube with a side of 0, a sphere
// of radius 0, a cylinder of no height or no radius): OpenSCAD makes them
// empty, and geometry::tessellate makes no mesh for them.
bool emptyByParameters(const Primitive& p) {
    if (const auto* c = std::get_if<Cube>(&p)) {
        const glm::dvec3 s = c->size;
        return !(s.x > 0 && s.y > 0 && s.z > 0) || std::isinf(s.x) || std::isinf(s.y) || std::isinf(s.z);
    }
    if (const auto* s = std::get_if<Sphere>(&p)) return !(s->r > 0) || std::isinf(s->r);
    if (const auto* c = std::get_if<Cylinder>(&p)) {
        return !(c->h > 0) || std::isinf(c->h) || !(c->r1 >= 0) || !(c->r2 >= 0) || !(c->r1 > 0 || c->r2 > 0) ||
               std::isinf(c->r1) || std::isinf(c->r2);
    }
    return false;
}

constexpr std::size_t kMaxMinkowskiParts = 4096;

}  // namespace

// resize(newsize = [x, y, z], auto = [0, 0, 0] | true): a size of 0 keeps an axis.
Resize Parser::resizeArguments(const std::vector<CsgArgument>& args) const {
    Resize r;
    const CsgArgument* size = find(args, "newsize", 0);
    if (size != nullptr && size->value.type == CsgValue::Type::Numbers) {
        const std::vector<double>& v = size->value.numbers;
        if (v.size() > 3) lex_.failAt(size->where, "newsize must be a vector of up to 3 numbers");
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (!std::isfinite(v[i])) lex_.failAt(size->where, "newsize must be finite");
            r.newsize[static_cast<int>(i)] = v[i];
        }
    } else if (size != nullptr && size->value.type == CsgValue::Type::Number) {
        r.newsize = glm::dvec3(number(*size, "newsize"));
    } else if (size != nullptr && size->value.type != CsgValue::Type::Undef) {
        lex_.failAt(size->where, "newsize must be a vector of numbers");
    }
    const CsgArgument* autosize = find(args, "auto", 1);
    if (autosize != nullptr) {
        const CsgValue& v = autosize->value;
        if (v.type == CsgValue::Type::Bool) {
            r.autosize = {v.boolean, v.boolean, v.boolean};
        } else if (v.type == CsgValue::Type::Numbers) {
            for (std::size_t i = 0; i < v.numbers.size() && i < 3; ++i) r.autosize[i] = v.numbers[i] != 0.0;
        } else if (v.type == CsgValue::Type::List) {
            for (std::size_t i = 0; i < v.items.size() && i < 3; ++i) {
                const CsgValue& item = v.items[i];
                r.autosize[i] = item.type == CsgValue::Type::Bool ? item.boolean
                                : item.type == CsgValue::Type::Number ? item.number != 0.0
                                                                      : false;
            }
        }
    }
    return r;
}

// resize() closes: its leaves (placed relative to it) become a resize group
// that buildModel scales once their meshes are known; flat children become
// one flat result, resized as OpenSCAD resizes a Polygon2d.
int Parser::finishResize(const Open& open) {
    const Node& n = tree_.nodes[static_cast<std::size_t>(open.node)];
    if (n.children.empty()) return emptyNode(n.where);
    if (flatChildren(open.node)) {
        const int merged = mergeFlatChildren(open.node, FlatOp::Resize, open.resize.outer, &open.context);
        if (merged < 0) return -1;
        FlatTree& shape = std::get<FlatSlab>(tree_.leaves[static_cast<std::size_t>(tree_.nodes[static_cast<std::size_t>(merged)].leaf)].primitive).shape;
        FlatNode& root = shape.nodes[static_cast<std::size_t>(shape.root)];
        root.newsize = {open.resize.newsize.x, open.resize.newsize.y};
        root.autosize = {open.resize.autosize[0], open.resize.autosize[1]};
        return merged;
    }
    Resize resize = open.resize;
    exactify(open.node);  // the box of a difference or intersection is its exact result's
    resize.leaves = tree_.leavesUnder(open.node);
    tree_.resizes.push_back(std::move(resize));
    const std::vector<int>& children = tree_.nodes[static_cast<std::size_t>(open.node)].children;
    return children.size() == 1 ? children.front() : open.node;
}

// The subtree under `root`, moved into a tree of its own (nodes parent
// first, its leaves and the resize groups wholly inside it); what stays
// behind is unreachable and dropped by compact().
std::shared_ptr<Tree> Parser::extractSolid(int root) {
    auto solid = std::make_shared<Tree>();
    solid->source = tree_.source;
    std::unordered_map<int, int> nodeMap, leafMap;
    std::vector<int> order{root}, todo{root};
    nodeMap[root] = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        for (int c : tree_.nodes[static_cast<std::size_t>(order[i])].children) {
            if (nodeMap.emplace(c, static_cast<int>(order.size())).second) order.push_back(c);
        }
    }
    for (int n : order) {
        Node node = tree_.nodes[static_cast<std::size_t>(n)];
        for (int& c : node.children) c = nodeMap.at(c);
        if (node.kind == NodeKind::Leaf) {
            auto [it, added] = leafMap.emplace(node.leaf, static_cast<int>(solid->leaves.size()));
            if (added) solid->leaves.push_back(std::move(tree_.leaves[static_cast<std::size_t>(node.leaf)]));
            node.leaf = it->second;
        }
        solid->nodes.push_back(std::move(node));
    }
    for (const Resize& r : tree_.resizes) {
        Resize inside = r;
        bool all = true;
        for (int& l : inside.leaves) {
            const auto it = leafMap.find(l);
            if (it == leafMap.end()) {
                all = false;
                break;
            }
            l = it->second;
        }
        if (all) solid->resizes.push_back(std::move(inside));
    }
    solid->root = 0;
    return solid;
}

// Every difference or intersection reached from `root` through unions
// becomes one Exact leaf holding its subtree, so that the leaves under
// `root` make its result (for the nodes that need that result's geometry).
void Parser::exactify(int root) {
    std::vector<int> todo{root};
    while (!todo.empty()) {
        const int at = todo.back();
        todo.pop_back();
        if (tree_.nodes[static_cast<std::size_t>(at)].kind != NodeKind::Union) continue;
        for (std::size_t i = 0; i < tree_.nodes[static_cast<std::size_t>(at)].children.size(); ++i) {
            const int c = tree_.nodes[static_cast<std::size_t>(at)].children[i];
            const NodeKind kind = tree_.nodes[static_cast<std::size_t>(c)].kind;
            if (kind == NodeKind::Union) {
                todo.push_back(c);
            } else if (kind == NodeKind::Difference || kind == NodeKind::Intersection) {
                const SourceLocation where = tree_.nodes[static_cast<std::size_t>(c)].where;
                Leaf leaf;
                leaf.where = where;
                Exact exact{extractSolid(c)};
                // The result shows as its first solid does.
                if (!exact.solid->leaves.empty()) {
                    leaf.color = exact.solid->leaves.front().color;
                    leaf.display = exact.solid->leaves.front().display;
                }
                leaf.primitive = std::move(exact);
                const int node = tree_.addLeaf(std::move(leaf));
                tree_.nodes[static_cast<std::size_t>(at)].children[i] = node;
            }
        }
    }
}

// Every child of `node` that holds a resize() becomes one Exact leaf holding
// its subtree (with the resize group, which extractSolid keeps): a hull or
// Minkowski sum copies its leaves, and a copy would not be resized. Only the
// resizes from `first` on can be inside it.
void Parser::exactifyResized(int node, std::size_t first) {
    std::unordered_set<int> resized;
    for (std::size_t i = first; i < tree_.resizes.size(); ++i) {
        resized.insert(tree_.resizes[i].leaves.begin(), tree_.resizes[i].leaves.end());
    }
    if (resized.empty()) return;
    for (std::size_t i = 0; i < tree_.nodes[static_cast<std::size_t>(node)].children.size(); ++i) {
        const int c = tree_.nodes[static_cast<std::size_t>(node)].children[i];
        const std::vector<int> under = tree_.leavesUnder(c);
        if (std::none_of(under.begin(), under.end(), [&](int l) { return resized.count(l) != 0; })) continue;
        Leaf leaf;
        leaf.where = tree_.nodes[static_cast<std::size_t>(c)].where;
        Exact exact{extractSolid(c)};
        if (!exact.solid->leaves.empty()) {
            leaf.color = exact.solid->leaves.front().color;
            leaf.display = exact.solid->leaves.front().display;
        }
        leaf.primitive = std::move(exact);
        const int replacement = tree_.addLeaf(std::move(leaf));
        tree_.nodes[static_cast<std::size_t>(node)].children[i] = replacement;
    }
}

// projection() closes: its solids become a Projection shape, joined to the
// flat tree it stands in, or shown as a slab of its own among solids.
int Parser::finishProjection(const Open& open) {
    const SourceLocation where = tree_.nodes[static_cast<std::size_t>(open.node)].where;
    // The shadow of a difference or intersection needs its exact result.
    if (!open.cut) exactify(open.node);
    Projection projection;
    projection.cut = open.cut;
    projection.solid = extractSolid(open.node);
    FlatNode shape;
    shape.op = FlatOp::Shape;
    shape.where = where;
    if (open.flatParent >= 0) {
        FlatTree& flat = pending().tree;
        shape.shape = static_cast<int>(flat.shapes.size());
        flat.shapes.push_back(std::move(projection));
        const int index = flat.add(std::move(shape));
        flat.nodes[static_cast<std::size_t>(open.flatParent)].children.push_back(index);
        return -1;
    }
    FlatTree flat;
    shape.shape = 0;
    flat.shapes.push_back(std::move(projection));
    flat.root = flat.add(std::move(shape));
    Leaf leaf = leafAt(open.outside, where);
    leaf.primitive = FlatSlab{std::move(flat)};
    return tree_.addLeaf(std::move(leaf));
}

// A node that stands for the empty solid where a statement makes nothing
// (a hull or minkowski of no solid): it takes part in the CSG as the empty
// set, as OpenSCAD's empty result does (an intersection with it is empty).
int Parser::emptyNode(SourceLocation where) {
    const int node = tree_.addNode(NodeKind::Union, {});
    tree_.nodes[static_cast<std::size_t>(node)].where = std::move(where);
    return node;
}

// hull() and minkowski() close: their children become hull leaves (a
// minkowski of unions of convex leaves, one hull per choice of a part from
// each child, under a union), or one flat result when the children are flat;
// all of them placed by the node's own transform. A child without a solid is
// left out (OpenSCAD's minkowski skips empty children), and without any the
// node is the empty solid. Returns the node that replaces the statement, or
// -1 when strata cannot make it yet (counted and warned, the subtree left out).
int Parser::finishGather(const Open& open) {
    if (open.gather == Open::Gather::Resize) return finishResize(open);
    if (open.gather == Open::Gather::Projection) return finishProjection(open);
    const bool hull = open.gather == Open::Gather::Hull;
    const char* name = hull ? "hull" : "minkowski";
    const Node& n = tree_.nodes[static_cast<std::size_t>(open.node)];
    const SourceLocation where = n.where;
    if (n.children.empty()) return emptyNode(where);
    if (flatChildren(open.node)) {
        return mergeFlatChildren(open.node, hull ? FlatOp::Hull : FlatOp::Minkowski, open.placement, &open.context);
    }

    // Each child's solid leaves (a hull takes them all as one set of points);
    // a difference or intersection among them, or a resize, is evaluated
    // exactly.
    exactify(open.node);
    exactifyResized(open.node, open.resizesBefore);
    std::vector<std::vector<int>> children;
    std::vector<int> solidChildren;  // the children with a solid in them
    bool convex = true;              // every solid leaf convex by construction
    for (int c : tree_.nodes[static_cast<std::size_t>(open.node)].children) {
        std::vector<int> solid;
        for (int l : tree_.leavesUnder(c)) {
            const Primitive& p = tree_.leaves[static_cast<std::size_t>(l)].primitive;
            if (std::holds_alternative<FlatSlab>(p)) {
                warnOnce("2d-in-3d", tree_.leaves[static_cast<std::size_t>(l)].where,
                         std::string("a 2D object inside ") + name + " of solids is ignored, as OpenSCAD ignores it");
                continue;
            }
            // Adds no point to a hull and no part to its child's union.
            if (emptyByParameters(p)) continue;
            convex = convex && convexByConstruction(p);
            solid.push_back(l);
        }
        if (!solid.empty()) {
            children.push_back(std::move(solid));
            solidChildren.push_back(c);
        }
    }
    if (children.empty()) return emptyNode(where);
    if (!hull && !convex) {
        // Other solids are split into convex parts once their meshes are known.
        MinkowskiSum sum;
        for (int c : solidChildren) sum.operands.push_back(extractSolid(c));
        Leaf leaf = leafAt(open.context, where);
        leaf.transform = open.placement;  // the operands are placed relative to the node
        leaf.primitive = std::move(sum);
        return tree_.addLeaf(std::move(leaf));
    }
    auto leafCopy = [&](int l) { return tree_.leaves[static_cast<std::size_t>(l)]; };
    auto hullLeaf = [&](Hull h) {
        Leaf leaf = leafAt(open.context, where);
        leaf.transform = open.placement;  // the parts are placed relative to the node
        leaf.primitive = std::move(h);
        return tree_.addLeaf(std::move(leaf));
    };
    if (hull) {
        // Each leaf is taken once, and the node it was under is left behind:
        // moved, not copied, so that hulls inside one another cost their
        // leaves once, not once for every hull around them.
        Hull h;
        for (const auto& child : children)
            for (int l : child) h.parts.push_back(std::move(tree_.leaves[static_cast<std::size_t>(l)]));
        return hullLeaf(std::move(h));
    }
    // minkowski: one hull per choice of a part from each child.
    std::size_t combinations = 1;
    for (const auto& child : children) {
        combinations *= child.size();
        if (combinations > kMaxMinkowskiParts) {
            unsupported("minkowski of more than " + std::to_string(kMaxMinkowskiParts) + " part combinations", where);
            return -1;
        }
    }
    // A part of child c goes into combinations / (its child's parts) sums:
    // copied into all but the last, moved into that one, so that sums inside
    // one another (each a hull leaf holding the sum inside it) cost their
    // leaves once, not once for every sum around them.
    std::unordered_map<int, std::size_t> usesLeft;
    for (const auto& child : children)
        for (int l : child) usesLeft[l] += combinations / child.size();
    auto take = [&](int l) {
        return --usesLeft[l] == 0 ? std::move(tree_.leaves[static_cast<std::size_t>(l)]) : leafCopy(l);
    };
    std::vector<int> sums;
    std::vector<std::size_t> choice(children.size(), 0);
    for (std::size_t k = 0; k < combinations; ++k) {
        Hull h;
        h.parts.push_back(take(children[0][choice[0]]));
        for (std::size_t c = 1; c < children.size(); ++c) h.summands.push_back(take(children[c][choice[c]]));
        sums.push_back(hullLeaf(std::move(h)));
        for (std::size_t c = 0; c < children.size() && ++choice[c] == children[c].size(); ++c) choice[c] = 0;
    }
    if (sums.size() == 1) return sums.front();
    const int u = tree_.addNode(NodeKind::Union, std::move(sums));
    tree_.nodes[static_cast<std::size_t>(u)].where = where;
    return u;
}

std::string Parser::string(const std::vector<CsgArgument>& args, const char* name, int position,
                           const std::string& fallback) const {
    const CsgArgument* a = find(args, name, position);
    if (a == nullptr || a->value.type == CsgValue::Type::Undef) return fallback;
    if (a->value.type != CsgValue::Type::String) {
        lex_.failAt(a->where, std::string(name) + " must be a string, not a " + typeName(a->value.type));
    }
    return a->value.string;
}

// A radius given as `rname` (or positional), else as the diameter `dname`
// halved, else `fallback`; neither may be negative (sphere, cylinder, circle).
double Parser::radius(const std::vector<CsgArgument>& args, const char* rname, const char* dname, double fallback,
                      int position) const {
    const CsgArgument* r = find(args, rname, position);
    if (r != nullptr && r->value.type != CsgValue::Type::Undef) {
        const double v = number(*r, rname);
        if (v < 0) lex_.failAt(r->where, std::string(rname) + " must not be negative");
        return v;
    }
    const CsgArgument* d = find(args, dname, -1);
    if (d != nullptr && d->value.type != CsgValue::Type::Undef) {
        const double v = number(*d, dname) / 2.0;
        if (v < 0) lex_.failAt(d->where, std::string(dname) + " must not be negative");
        return v;
    }
    return fallback;
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

// Keeps only nodes reachable from the root and the background roots, in
// depth-first order, so consumers can walk `nodes` without orphans.
void Parser::compact() {
    std::vector<int> remap(tree_.nodes.size(), -1);
    std::vector<Node> kept;
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
    // Exactly as many as are kept: a million leaves under their own
    // multmatrix() leave half the nodes behind.
    kept.reserve(order.size());
    for (int n : order) {
        Node node = std::move(tree_.nodes[static_cast<std::size_t>(n)]);
        for (int& c : node.children) c = remap[static_cast<std::size_t>(c)];
        kept.push_back(std::move(node));
    }
    // Leaves no node refers to (e.g. under a later '!' root) are dropped too.
    std::vector<int> leafRemap(tree_.leaves.size(), -1);
    std::vector<Leaf> leaves;
    leaves.reserve(static_cast<std::size_t>(
        std::count_if(kept.begin(), kept.end(), [](const Node& node) { return node.kind == NodeKind::Leaf; })));
    for (Node& node : kept) {
        if (node.kind != NodeKind::Leaf) continue;
        int& mapped = leafRemap[static_cast<std::size_t>(node.leaf)];
        if (mapped < 0) {
            mapped = static_cast<int>(leaves.size());
            leaves.push_back(std::move(tree_.leaves[static_cast<std::size_t>(node.leaf)]));
        }
        node.leaf = mapped;
    }
    std::vector<Resize> resizes;
    for (Resize& r : tree_.resizes) {
        std::vector<int> kept;
        for (int l : r.leaves) {
            const int mapped = leafRemap[static_cast<std::size_t>(l)];
            if (mapped >= 0) kept.push_back(mapped);
        }
        if (kept.empty()) continue;
        r.leaves = std::move(kept);
        resizes.push_back(std::move(r));
    }
    tree_.resizes = std::move(resizes);
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
    const std::string why = unreadableReason(path);
    if (!why.empty()) throw Error(SourceLocation{path, 0, 0}, "cannot read (" + why + ")");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(SourceLocation{path, 0, 0}, "cannot open file");
    std::string baseDir = std::filesystem::path(path).parent_path().string();
    return parseCsg(in, path, baseDir, options);
}

}  // namespace strata::scene
