#include "strata/scene/CsgParser.h"

#include "CsgParserImpl.h"
#include "strata/core/InputFile.h"

namespace strata::scene::detail {

namespace {

constexpr int kMaxVectorNesting = 64;

}  // namespace

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

}  // namespace strata::scene::detail

namespace strata::scene {

using detail::Parser;

Tree parseCsg(std::istream& in, const std::string& name, const std::string& baseDir, const ParseOptions& options) {
    Parser parser(in, name, baseDir, options);
    return parser.parse();
}

Tree parseCsgFile(const std::string& path, const ParseOptions& options) {
    requireReadable(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(SourceLocation{path, 0, 0}, "cannot open file");
    std::string baseDir = std::filesystem::path(path).parent_path().string();
    return parseCsg(in, path, baseDir, options);
}

}  // namespace strata::scene
