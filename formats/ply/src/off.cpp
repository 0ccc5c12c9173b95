// OFF through OpenMesh, after a validator: OpenMesh's OFF reader crashes on a lying count, reads words and
// "nan" as garbage, knows no comments, and misreads values after a face's indices
// (third_party_notes/openmesh.md).

#include "pdeface/ply/ply.hpp"

#include "openmesh_io.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace pdeface::off {
namespace {

using text::Scanner;
using text::Token;

constexpr std::int64_t kMaxCount = std::numeric_limits<std::int32_t>::max(); // OpenMesh handles are int
constexpr std::uint64_t kMinVertexBytes = 6;                                 // "0 0 0\n"
constexpr std::uint64_t kMinFaceBytes = 2;                                   // "0\n"

// OFF comments run from '#' to the end of the line. OpenMesh does not know them, so they are blanked in
// our copy (lines and columns stay). Returns the units a "# units mm" comment states.
Units blank_comments(std::string& text) {
  Units units = Units::Unknown;
  for (std::size_t hash = text.find('#'); hash != std::string::npos; hash = text.find('#', hash)) {
    const std::size_t end = std::min(text.find('\n', hash), text.size());
    if (auto stated = text::units_from_comment(std::string_view(text).substr(hash + 1, end - hash - 1)))
      units = *stated;
    std::fill(text.begin() + static_cast<std::ptrdiff_t>(hash),
              text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    hash = end;
  }
  return units;
}

// Values after the mandatory ones on a line: [begin, end) and how many.
struct Rest {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t count = 0;
  std::optional<Token> not_number;
};

class Validator {
public:
  Validator(std::string& text, std::string_view source, Notes* notes)
      : text_(text), scan_(text), source_(source), notes_(notes) {}

  // Checks the whole document; rewrites in `text` what OpenMesh would misread.
  Result<void> run() {
    if (Result<void> ok = magic(); !ok) return ok;
    Result<std::int64_t> vertices = count("vertex", kMinVertexBytes);
    if (!vertices) return std::move(vertices).error();
    Result<std::int64_t> faces = count("face", kMinFaceBytes);
    if (!faces) return std::move(faces).error();
    Result<std::int64_t> edges = count("edge", 0);
    if (!edges) return std::move(edges).error();
    // OpenMesh reads the first vertex right after the third count: nothing may come between.
    if (const Token extra = scan_.next_on_line(); !extra.empty())
      return fail(ErrorCode::Malformed, extra.location(),
                  fmt::format("unexpected '{}' after the counts", extra.text));
    for (std::int64_t i = 0; i < *vertices; ++i)
      if (Result<void> ok = vertex(i, *vertices); !ok) return ok;
    for (std::int64_t i = 0; i < *faces; ++i)
      if (Result<void> ok = face(i, *faces, *vertices); !ok) return ok;
    if (notes_ && !scan_.at_end())
      notes_->push_back(fmt::format("{}:{}: data after the last face ignored", source_, scan_.here().line));
    return {};
  }

private:
  Error fail(ErrorCode code, Location where, std::string message) const {
    return make_error(code, std::move(message), std::string(source_), where);
  }
  void note_once(bool& noted, std::uint64_t line, std::string_view what) {
    if (notes_ && !noted)
      notes_->push_back(fmt::format("{}:{}: {} ignored (here and on later lines)", source_, line, what));
    noted = true;
  }

  // [ST][C][N]OFF alone on the first line: OpenMesh reads that whole line as the header.
  Result<void> magic() {
    const Token word = scan_.next();
    if (word.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source_));
    std::string_view kind = word.text;
    if (kind.starts_with("ST"))
      return fail(ErrorCode::UnsupportedFormat, word.location(),
                  "STOFF texture coordinates are not supported");
    colors_ = kind.starts_with("C");
    if (colors_) kind.remove_prefix(1);
    normals_ = kind.starts_with("N");
    if (normals_) kind.remove_prefix(1);
    if (word.line != 1 || word.column != 1 || !kind.ends_with("OFF"))
      return fail(ErrorCode::BadMagic, word.location(),
                  "not an OFF file: expected OFF, COFF, NOFF or CNOFF at the start");
    if (kind != "OFF")
      return fail(ErrorCode::UnsupportedFormat, word.location(),
                  fmt::format("{} (4D or n-D OFF) is not supported", word.text));
    if (const Token next = scan_.next_on_line(); !next.empty())
      return fail(ErrorCode::UnsupportedFormat, next.location(),
                  next.text == "BINARY" ? std::string("binary OFF is not supported")
                                        : fmt::format("'{}' after {}: the counts must be on the next line",
                                                      next.text, word.text));
    return {};
  }

  Result<std::int64_t> count(std::string_view what, std::uint64_t min_bytes) {
    const Token token = scan_.next();
    if (token.empty())
      return fail(ErrorCode::Truncated, scan_.here(), fmt::format("the file ends before the {} count", what));
    const std::optional<std::int64_t> n = text::parse_integer(token.text);
    if (!n || *n < 0)
      return fail(ErrorCode::Malformed, token.location(),
                  fmt::format("expected the {} count, found '{}'", what, token.text));
    if (*n > kMaxCount || static_cast<std::uint64_t>(*n) * min_bytes > text_.size())
      return fail(ErrorCode::CountTooLarge, token.location(),
                  fmt::format("{} {}s declared, but the whole file has {} bytes", *n, what, text_.size()));
    return *n;
  }

  Result<Token> token(std::string_view what, std::int64_t index, std::string_view element,
                      std::int64_t total) {
    Token t = scan_.next();
    if (t.empty())
      return fail(
          ErrorCode::Truncated, scan_.here(),
          fmt::format("the file ends inside {} {} of {}, before its {}", element, index, total, what));
    return t;
  }

  // OpenMesh reads coordinates into floats with operator>>: anything else silently becomes garbage.
  Result<void> coordinate(std::string_view what, std::int64_t index, std::int64_t total) {
    Result<Token> t = token(what, index, "vertex", total);
    if (!t) return std::move(t).error();
    const std::optional<double> v = text::parse_double(t->text);
    if (!v)
      return fail(ErrorCode::Malformed, t->location(),
                  fmt::format("expected a number for {} of vertex {}, found '{}'", what, index, t->text));
    if (!std::isfinite(*v) || std::abs(*v) > FLT_MAX)
      return fail(ErrorCode::NonFinite, t->location(),
                  fmt::format("{} of vertex {} is {}, not a finite float", what, index, t->text));
    return {};
  }

  Rest rest_of_line() {
    Rest rest;
    for (Token t = scan_.next_on_line(); !t.empty(); t = scan_.next_on_line()) {
      if (rest.count++ == 0) rest.begin = t.offset;
      rest.end = t.offset + t.text.size();
      const std::optional<double> v = text::parse_double(t.text);
      if (!rest.not_number && (!v || !std::isfinite(*v))) rest.not_number = t;
    }
    return rest;
  }

  // COFF colours: OpenMesh takes 3 or 4 values (ints, or floats when the first has a '.'), ignores 1 or 2,
  // counts them by splitting on single spaces, and prints to stderr on more.
  Result<void> colour(const Rest& rest, std::uint64_t line) {
    if (rest.not_number)
      return fail(ErrorCode::Malformed, rest.not_number->location(),
                  fmt::format("expected a colour value, found '{}'", rest.not_number->text));
    if (rest.count > 4)
      return fail(ErrorCode::Malformed, Location::at_line(line),
                  fmt::format("{} colour values (expected 3 or 4)", rest.count));
    respace(rest);
    return {};
  }

  // Rewrites the values one space apart, padding with blanks to the old end.
  void respace(const Rest& rest) {
    std::string joined;
    Scanner values(std::string_view(text_).substr(0, rest.end), rest.begin);
    for (Token t = values.next_on_line(); !t.empty(); t = values.next_on_line()) {
      if (!joined.empty()) joined += ' ';
      joined += t.text;
    }
    std::copy(joined.begin(), joined.end(), text_.begin() + static_cast<std::ptrdiff_t>(rest.begin));
    std::fill(text_.begin() + static_cast<std::ptrdiff_t>(rest.begin + joined.size()),
              text_.begin() + static_cast<std::ptrdiff_t>(rest.end), ' ');
  }

  Result<void> vertex(std::int64_t index, std::int64_t total) {
    for (std::string_view axis : {"x", "y", "z"})
      if (Result<void> ok = coordinate(axis, index, total); !ok) return ok;
    if (normals_)
      for (std::string_view axis : {"nx", "ny", "nz"})
        if (Result<void> ok = coordinate(axis, index, total); !ok) return ok;
    const std::uint64_t line = scan_.here().line;
    const Rest rest = rest_of_line();
    if (colors_) return colour(rest, line);
    if (rest.count != 0) note_once(noted_vertex_extras_, line, "values after vertex coordinates");
    return {};
  }

  Result<void> face(std::int64_t index, std::int64_t total, std::int64_t vertices) {
    Result<Token> size = token("number of corners", index, "face", total);
    if (!size) return std::move(size).error();
    const std::optional<std::int64_t> corners = text::parse_integer(size->text);
    if (!corners || *corners < 0)
      return fail(ErrorCode::Malformed, size->location(),
                  fmt::format("expected the number of corners of face {}, found '{}'", index, size->text));
    for (std::int64_t k = 0; k < *corners; ++k) {
      Result<Token> corner = token("corners", index, "face", total);
      if (!corner) return std::move(corner).error();
      const std::optional<std::int64_t> v = text::parse_integer(corner->text);
      if (!v)
        return fail(ErrorCode::Malformed, corner->location(),
                    fmt::format("expected a vertex index in face {}, found '{}'", index, corner->text));
      if (*v < 0 || *v >= vertices)
        return fail(
            ErrorCode::IndexOutOfRange, corner->location(),
            fmt::format("face {} refers to vertex {}, but there are {} vertices", index, *v, vertices));
    }
    const std::uint64_t line = scan_.here().line;
    const Rest rest = rest_of_line();
    if (colors_) return colour(rest, line);
    if (rest.count == 0) return {};
    // Without 'C' OpenMesh would read these values as the next face: blank them.
    std::fill(text_.begin() + static_cast<std::ptrdiff_t>(rest.begin),
              text_.begin() + static_cast<std::ptrdiff_t>(rest.end), ' ');
    note_once(noted_face_extras_, line, "values after face indices (face colours?)");
    return {};
  }

  std::string& text_;
  Scanner scan_;
  std::string_view source_;
  Notes* notes_;
  bool colors_ = false;
  bool normals_ = false;
  bool noted_vertex_extras_ = false;
  bool noted_face_extras_ = false;
};

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
  std::string text(bytes);
  const Units units = blank_comments(text);
  if (Result<void> ok = Validator(text, source, notes).run(); !ok) return std::move(ok).error();
  Result<Mesh> mesh = ply::detail::read_openmesh(std::move(text), {.extension = "off"}, source, notes);
  if (mesh) mesh->units = units;
  return mesh;
}

Result<std::string> write(const Mesh& mesh, Notes* notes) {
  if (Result<void> valid = validate(mesh, mesh.name); !valid) return std::move(valid).error();
  Result<std::string> bytes =
      ply::detail::write_openmesh(mesh, {.extension = "off", .binary = false}, "OFF", notes);
  if (!bytes || mesh.units == Units::Unknown) return bytes;
  // A comment after the OFF line states the units; our reader finds it, other readers skip it.
  bytes->insert(bytes->find('\n') + 1, fmt::format("# units {}\n", to_string(mesh.units)));
  return bytes;
}

} // namespace pdeface::off
