#include "parser.hpp"

#include "pdeface/core/text.hpp"

#include <array>
#include <utility>

namespace pdeface::vrml::detail {
namespace {

bool closes(TokenKind opener, TokenKind closer) {
  return (opener == TokenKind::OpenBrace && closer == TokenKind::CloseBrace) ||
         (opener == TokenKind::OpenBracket && closer == TokenKind::CloseBracket);
}

std::string at_text(const Position& at) { return fmt::format("{}:{}", at.line, at.column); }

//! Units named after "units:" in an info string, as our writer states them.
std::optional<Units> units_named(std::string_view text) {
  constexpr std::string_view key = "units:";
  if (!text.starts_with(key)) return std::nullopt;
  text.remove_prefix(key.size());
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t'))
    text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t'))
    text.remove_suffix(1);
  return units_from_string(text);
}

} // namespace

std::string describe(const Token& token) {
  switch (token.kind) {
  case TokenKind::End: return "the end of the file";
  case TokenKind::String: return fmt::format("the string \"{}\"", excerpt(token.text));
  case TokenKind::BadString: return "an unterminated string";
  default: return fmt::format("'{}'", excerpt(token.text));
  }
}

std::string unescape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) ++i;
    out += text[i];
  }
  return out;
}

// --- tokens ------------------------------------------------------------------------------------------------

Token Parser::lex() {
  const Token t = lexer_.next();
  switch (t.kind) {
  case TokenKind::OpenBrace:
  case TokenKind::OpenBracket:
    if (open_.size() >= kMaxDepth)
      fail(ErrorCode::Malformed, t.at, fmt::format("nesting deeper than {} levels", kMaxDepth));
    open_.push_back(t);
    break;
  case TokenKind::CloseBrace:
  case TokenKind::CloseBracket:
    if (open_.empty())
      fail(ErrorCode::Malformed, t.at, fmt::format("'{}' closes nothing: no bracket is open", t.text));
    if (!closes(open_.back().kind, t.kind))
      fail(ErrorCode::Malformed, t.at,
           fmt::format("'{}' does not close the '{}' opened at {}", t.text, open_.back().text,
                       at_text(open_.back().at)));
    open_.pop_back();
    break;
  case TokenKind::BadString:
    fail(ErrorCode::Truncated, t.at, "the file ends inside this string (no closing '\"')");
  case TokenKind::End:
  case TokenKind::Word:
  case TokenKind::String: break;
  }
  return t;
}

Token Parser::next() {
  if (peeked_) return *std::exchange(peeked_, std::nullopt);
  return lex();
}

const Token& Parser::peek() {
  if (!peeked_) peeked_ = lex();
  return *peeked_;
}

Token Parser::next_required(std::string_view expected) {
  Token t = next();
  if (t.kind != TokenKind::End) return t;
  if (open_.empty())
    fail(ErrorCode::Truncated, t.at, fmt::format("unexpected end of the file: expected {}", expected));
  const Token& open = open_.back();
  fail(ErrorCode::Truncated, open.at,
       fmt::format("the file ends (at {}) before this '{}' is closed", at_text(t.at), open.text));
}

void Parser::fail_expected(std::string_view expected, const Token& found) const {
  fail(ErrorCode::Malformed, found.at, fmt::format("expected {}, found {}", expected, describe(found)));
}

// --- statements and nodes ----------------------------------------------------------------------------------

Scene Parser::parse() {
  for (Token t = next(); t.kind != TokenKind::End; t = next()) {
    if (other_statement(t)) continue;
    if (NodePtr node = node_statement(t)) scene_.roots.push_back(std::move(node));
  }
  return std::move(scene_);
}

bool Parser::starts_node(const Token& word) {
  return word.kind == TokenKind::Word &&
         (word.text == "DEF" || word.text == "USE" || peek().kind == TokenKind::OpenBrace);
}

NodePtr Parser::node_statement(const Token& first) {
  if (first.kind != TokenKind::Word) fail_expected("a node", first);
  if (first.text == "NULL") return nullptr;
  if (first.text == "DEF") {
    const Token name = next_required("a name after DEF");
    if (name.kind != TokenKind::Word) fail_expected("a name after DEF", name);
    NodePtr node = parse_node(next_required("a node type"));
    defs_[name.text] = node; // only now: a node cannot USE itself, so the graph has no cycles
    return node;
  }
  if (first.text == "USE") {
    const Token name = next_required("a name after USE");
    if (name.kind != TokenKind::Word) fail_expected("a name after USE", name);
    const auto found = defs_.find(name.text);
    if (found == defs_.end())
      fail(ErrorCode::UndefinedName, name.at,
           fmt::format("USE {}: no node was defined with DEF {} before this point", excerpt(name.text),
                       excerpt(name.text)));
    return found->second;
  }
  return parse_node(first);
}

NodePtr Parser::parse_node(const Token& type) {
  if (type.kind != TokenKind::Word) fail_expected("a node type", type);
  const Token open = next_required("'{'");
  if (open.kind != TokenKind::OpenBrace)
    fail_expected(fmt::format("'{{' after the node type {}", excerpt(type.text)), open);
  return std::make_shared<const Node>(Node{type.text, type.at, parse_body(type)});
}

void Parser::skip_item(const Token& t) {
  switch (t.kind) {
  case TokenKind::OpenBracket: list_items("']'", [this](const Token& item) { skip_item(item); }); return;
  case TokenKind::OpenBrace: skip_body(); return; // not VRML, but balanced: read past it
  case TokenKind::Word:
    if (other_statement(t)) return;
    if (starts_node(t)) (void)node_statement(t);
    return;
  default: return; // strings; closers never reach here (the callers' loops end on them)
  }
}

void Parser::skip_balanced() {
  const std::size_t depth = open_.size();
  while (open_.size() >= depth)
    (void)next_required("a closing bracket");
}

bool Parser::transform_field(std::string_view name, std::string_view scale_name, TransformFields& f) {
  if (name == "translation")
    f.translation = read_vec3(name);
  else if (name == "rotation")
    f.rotation = read_rotation(name);
  else if (name == scale_name)
    f.scale = read_vec3(name);
  else if (name == "scaleOrientation")
    f.scale_orientation = read_rotation(name);
  else if (name == "center")
    f.center = read_vec3(name);
  else
    return false;
  return true;
}

// --- field values ------------------------------------------------------------------------------------------

std::int32_t Parser::read_int32(std::string_view field) {
  const Token t = next_required("an integer");
  std::int32_t value = 0;
  if (t.kind != TokenKind::Word || !parse_int32(t.text, value))
    fail_expected(fmt::format("an integer for {}", field), t);
  return value;
}

bool Parser::read_bool(std::string_view field) {
  const Token t = next_required("TRUE or FALSE");
  if (t.kind == TokenKind::Word && (t.text == "TRUE" || t.text == "1")) return true;
  if (t.kind == TokenKind::Word && (t.text == "FALSE" || t.text == "0")) return false;
  fail_expected(fmt::format("TRUE or FALSE for {}", field), t);
}

Vec3 Parser::read_vec3(std::string_view field) {
  Vec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = read_double(field);
  return v;
}

Eigen::AngleAxisd Parser::read_rotation(std::string_view field) {
  const Vec3 axis = read_vec3(field);
  const double angle = read_double(field);
  const double length = axis.norm();
  // A zero axis has no direction; the rotation is then the identity whatever the angle.
  if (length == 0.0) return Eigen::AngleAxisd(0.0, Vec3::UnitZ());
  return Eigen::AngleAxisd(angle, axis / length);
}

std::string_view Parser::read_word(std::string_view field) {
  const Token t = next_required("a word");
  if (t.kind != TokenKind::Word) fail_expected(fmt::format("a name for {}", field), t);
  return t.text;
}

bool Parser::list_index(std::int32_t& value, std::string_view field, Position& closer) {
  if (!peeked_ && lexer_.number(value)) return true;
  const Token t = next_required("an integer or ']'");
  if (t.kind == TokenKind::CloseBracket) {
    closer = t.at;
    return false;
  }
  if (t.kind != TokenKind::Word || !parse_int32(t.text, value))
    fail_expected(fmt::format("an integer in {}", field), t);
  return true;
}

IndexList Parser::read_index_list(std::string_view field) {
  IndexList list;
  list.at = peek().at;
  if (peek().kind != TokenKind::OpenBracket) { // a single value without brackets
    list.values.push_back(read_int32(field));
    return list;
  }
  (void)next();
  Position closer;
  for (std::int32_t value = 0; list_index(value, field, closer);)
    list.values.push_back(value);
  return list;
}

std::vector<std::string_view> Parser::read_strings(std::string_view field) {
  std::vector<std::string_view> strings;
  one_or_list("a string", "a string or ']'", [&](const Token& t) {
    if (t.kind != TokenKind::String) fail_expected(fmt::format("a string in {}", field), t);
    strings.push_back(t.text);
  });
  return strings;
}

std::vector<NodePtr> Parser::read_mfnode() {
  std::vector<NodePtr> out;
  one_or_list("a node or '['", "a node or ']'", [&](const Token& t) {
    if (NodePtr node = node_statement(t)) out.push_back(std::move(node));
  });
  return out;
}

void Parser::take_info(const std::vector<std::string_view>& strings) {
  for (std::string_view s : strings) {
    const std::optional<Units> units = units_named(unescape(s));
    if (!units) continue;
    if (scene_.units == Units::Unknown)
      scene_.units = *units;
    else if (scene_.units != *units)
      context_.note(fmt::format("the file states two units ({} and {}); the first is kept",
                                to_string(scene_.units), to_string(*units)));
  }
}

} // namespace pdeface::vrml::detail
