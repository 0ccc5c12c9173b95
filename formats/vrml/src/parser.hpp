#pragma once
// The parts of the VRML 1.0 and 2.0 parsers that are the same: statements (DEF, USE), node bodies, the
// generic skipping of everything the reader does not need, field values, and the bookkeeping that makes
// errors exact (every `{`/`[` is remembered until it is closed, so an unbalanced file names the bracket
// that was never closed, or the stray closer).
//
// Skipping is structural, not a search for the next '}': a skipped node's body is read item by item (words,
// strings, bracketed lists, nested `Type { ... }` nodes), and nested nodes are parsed like any other, so a
// `DEF` inside something skipped (a `Switch` choice, an unknown node) can still be `USE`d later.

#include "context.hpp"
#include "lexer.hpp"
#include "numbers.hpp"
#include "scene.hpp"

#include "pdeface/core/text.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace pdeface::vrml::detail {

class Parser {
public:
  Parser(Context& context, Position start) : context_(context), lexer_(context.bytes(), start) {}
  virtual ~Parser() = default;
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

  //! Reads every statement to the end of the input.
  [[nodiscard]] Scene parse();

protected:
  //! Reads the body of a node of type `type.text` whose '{' was just read, up to and including its '}'.
  virtual NodeData parse_body(const Token& type) = 0;
  //! Statements other than nodes (VRML 2.0: PROTO, EXTERNPROTO, ROUTE); true if `word` began one.
  virtual bool other_statement(const Token& /*word*/) { return false; }

  // --- tokens --------------------------------------------------------------------------------------
  //! The next token, End at the end of the input.
  Token next();
  //! The next token; at the end of the input, fails naming what was `expected` (or the unclosed bracket).
  Token next_required(std::string_view expected);
  const Token& peek();
  [[noreturn]] void fail(ErrorCode code, const Position& at, std::string message) const {
    context_.fail(code, at, std::move(message));
  }
  [[noreturn]] void fail_expected(std::string_view expected, const Token& found) const;

  // --- nodes -----------------------------------------------------------------------------------------
  //! True if `word` starts a node here: DEF, USE, or a type name followed by '{'.
  bool starts_node(const Token& word);
  //! A node statement starting with `first`: `DEF n Type {}`, `USE n`, `Type {}`, or NULL (nullptr).
  NodePtr node_statement(const Token& first);
  //! A node of type `type` (the '{' still to come).
  NodePtr parse_node(const Token& type);
  //! Reads the fields of the node being parsed to its '}': `handle(name)` reads a field it knows and
  //! returns true; anything else is skipped.
  template <class Handler> void fields(Handler&& handle) {
    for (;;) {
      const Token t = next_required("a field name or '}'");
      if (t.kind == TokenKind::CloseBrace) return;
      if (t.kind == TokenKind::Word && handle(t)) continue;
      skip_item(t);
    }
  }
  //! Reads the fields of the node being parsed to its '}': `read()` reads the one named `field`; every
  //! other field is skipped.
  template <class Read> void only_field(std::string_view field, Read&& read) {
    fields([&](const Token& name) {
      if (name.text != field) return false;
      read();
      return true;
    });
  }
  //! Reads `name` into `f` if it is one of a transform's fields (the scale's is `scale_name`:
  //! scaleFactor in VRML 1.0, scale in 2.0); false if it is not.
  bool transform_field(std::string_view name, std::string_view scale_name, TransformFields& f);
  //! Skips the rest of a node body we do not read.
  void skip_body() {
    fields([](const Token&) { return false; });
  }
  //! Skips one item of a node body: a word, a string, a bracketed list, a nested node or a statement.
  void skip_item(const Token& t);
  //! Skips tokens up to the closer of the bracket just read, without interpreting them (PROTO
  //! interfaces and bodies, whose names are the PROTO's own).
  void skip_balanced();
  //! Reads the items of a list whose '[' was just read, to its ']': `item(token)` for each; `expected`
  //! names what may come next in errors.
  template <class Item> void list_items(std::string_view expected, Item&& item) {
    for (Token t = next_required(expected); t.kind != TokenKind::CloseBracket; t = next_required(expected))
      item(t);
  }
  //! A value that is one item, or a bracketed list of them: `item(token)` for each. `expected` names what
  //! may come first, `expected_in_list` what may come inside the list.
  template <class Item>
  void one_or_list(std::string_view expected, std::string_view expected_in_list, Item&& item) {
    const Token first = next_required(expected);
    if (first.kind == TokenKind::OpenBracket)
      list_items(expected_in_list, item);
    else
      item(first);
  }

  // --- field values (the field's name was just read; `field` names it in errors) -----------------------
  double read_double(std::string_view field) { return number<double>(next_required("a number"), field); }
  std::int32_t read_int32(std::string_view field);
  bool read_bool(std::string_view field);
  Vec3 read_vec3(std::string_view field);
  Eigen::AngleAxisd read_rotation(std::string_view field);
  std::string_view read_word(std::string_view field);
  //! MFVec3f, MFVec2f, MFColor, ... : N numbers per value, in brackets or a single value without.
  template <class Vector> std::vector<Vector> read_vectors(std::string_view field);
  IndexList read_index_list(std::string_view field);
  std::vector<std::string_view> read_strings(std::string_view field);
  NodePtr read_sfnode() { return node_statement(next_required("a node or NULL")); }
  std::vector<NodePtr> read_mfnode();
  //! The body of a node that holds one list field (`Coordinate { point [...] }`), other fields skipped.
  template <class Data, class Vector>
  NodeData list_node(std::string_view field, std::vector<Vector> Data::*list);

  template <class T> T number(const Token& t, std::string_view field) const;
  //! The next number of a bracketed list, or false at its ']' (then at `closer`). Takes the lexer's
  //! fast path when it can, the token path (which reports errors exactly) when it cannot.
  template <class T> bool list_number(T& value, std::string_view field, Position& closer);
  bool list_index(std::int32_t& value, std::string_view field, Position& closer);

  //! Records the units an info string states ("units: mm"), as our writer puts them in WorldInfo.
  void take_info(const std::vector<std::string_view>& strings);
  //! An SFNode field that must hold a `type` node (`Data` once parsed). NULL, and instances of PROTOs
  //! (which the reader does not expand), give nullptr; a node of any other type is an error.
  template <class Data> NodePtr read_node_of(std::string_view field, std::string_view type);

  Context& context_;
  Scene scene_;
  std::unordered_set<std::string_view> protos_; // names declared by PROTO and EXTERNPROTO

private:
  Token lex();

  Lexer lexer_;
  std::optional<Token> peeked_;
  std::vector<Token> open_; // the '{' and '[' not closed yet, innermost last
  std::unordered_map<std::string_view, NodePtr> defs_;
};

//! A string's characters with `\"` and `\\` resolved.
[[nodiscard]] std::string unescape(std::string_view text);

// --- templates ---------------------------------------------------------------------------------------------

template <class T> T Parser::number(const Token& t, std::string_view field) const {
  T value{};
  if (t.kind != TokenKind::Word || !parse_float(t.text, value))
    fail_expected(fmt::format("a number for {}", field), t);
  if (!std::isfinite(value))
    fail(ErrorCode::NonFinite, t.at, fmt::format("{}: '{}' is not a finite number", field, excerpt(t.text)));
  return value;
}

template <class T> bool Parser::list_number(T& value, std::string_view field, Position& closer) {
  if (!peeked_ && lexer_.number(value)) return true;
  const Token t = next_required("a number or ']'");
  if (t.kind == TokenKind::CloseBracket) {
    closer = t.at;
    return false;
  }
  value = number<T>(t, field);
  return true;
}

template <class Vector> std::vector<Vector> Parser::read_vectors(std::string_view field) {
  using Scalar = typename Vector::Scalar;
  constexpr int n = Vector::RowsAtCompileTime;
  std::vector<Vector> out;
  Vector v;
  if (peek().kind != TokenKind::OpenBracket) { // a single value without brackets
    for (int i = 0; i < n; ++i)
      v[i] = number<Scalar>(next_required("a number"), field);
    out.push_back(v);
    return out;
  }
  (void)next();
  Position closer;
  while (list_number(v[0], field, closer)) {
    for (int i = 1; i < n; ++i)
      if (!list_number(v[i], field, closer))
        fail(ErrorCode::Malformed, closer,
             fmt::format("{}: the list ends inside a value ({} of its {} numbers given)", field, i, n));
    out.push_back(v);
  }
  return out;
}

template <class Data, class Vector>
NodeData Parser::list_node(std::string_view field, std::vector<Vector> Data::*list) {
  Data data;
  only_field(field, [&] { data.*list = read_vectors<Vector>(field); });
  return data;
}

template <class Data> NodePtr Parser::read_node_of(std::string_view field, std::string_view type) {
  const Position at = peek().at;
  NodePtr node = read_sfnode();
  if (!node || std::holds_alternative<Data>(node->data)) return node;
  if (protos_.contains(node->type)) return nullptr; // noted where the instance was parsed
  fail(ErrorCode::Malformed, at,
       fmt::format("{} must be a {} node, found {}", field, type, excerpt(node->type)));
}

} // namespace pdeface::vrml::detail
