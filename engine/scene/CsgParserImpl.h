#pragma once
// The parser of OpenSCAD's CSG export, for its own files. The grammar
// (statements, blocks, argument values, the tree's final shape) is
// CsgParser.cpp; what each statement makes is its module's family
// (CsgModules.h): CsgSolids.cpp (the leaves), CsgFlat.cpp (2D shapes,
// offsets and extrusions, and the flat trees they read), CsgOperations.cpp
// (booleans, transforms and colours) and CsgGather.cpp (hull, minkowski,
// resize and projection, whose children become other leaves).

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
#include "CsgValue.h"
#include "strata/scene/CsgParser.h"

namespace strata::scene::detail {

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

}  // namespace strata::scene::detail
