// OFF through OpenMesh, after a validator: OpenMesh's OFF reader crashes on a lying count, reads words and
// "nan" as garbage, knows no comments, misreads values after a face's indices, and - reading a stream -
// cannot see what the header line announces (COFF, NOFF), so it reads every stream as plain OFF
// (third_party_notes/openmesh.md).

#include "pdeface/off/off.hpp"

#include "pdeface/core/text.hpp"
#include "pdeface/openmesh_io/openmesh_io.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
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

class Validator {
public:
  Validator(std::string& text, std::string_view source, Notes* notes)
      : text_(text), scan_(text), source_(source), notes_(notes) {}

  // Checks the whole document; blanks in `text` what OpenMesh would misread.
  Result<void> run() {
    if (Result<void> ok = magic(); !ok) return ok;
    Result<std::int64_t> vertices = count("vertices", kMinVertexBytes);
    if (!vertices) return std::move(vertices).error();
    Result<std::int64_t> faces = count("faces", kMinFaceBytes);
    if (!faces) return std::move(faces).error();
    Result<std::int64_t> edges = count("edges", 0);
    if (!edges) return std::move(edges).error();
    // OpenMesh reads the first vertex right after the third count: nothing may come between.
    if (const Token extra = scan_.next_on_line(); !extra.empty())
      return fail(ErrorCode::Malformed, extra.location(),
                  fmt::format("unexpected '{}' after the counts", excerpt(extra.text)));
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
  void note(std::string message) const {
    if (notes_) notes_->push_back(fmt::format("{}: {}", source_, message));
  }

  // [C][N]OFF alone on the first line. OpenMesh skips that line: reading a stream, it cannot see what the
  // header announces, so COFF colours and NOFF normals stay unread.
  Result<void> magic() {
    const Token word = scan_.next();
    if (word.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source_));
    std::string_view kind = word.text;
    if (kind.starts_with("ST"))
      return fail(ErrorCode::UnsupportedFormat, word.location(),
                  "STOFF texture coordinates are not supported");
    const bool colors = kind.starts_with("C");
    if (colors) kind.remove_prefix(1);
    const bool normals = kind.starts_with("N");
    if (normals) kind.remove_prefix(1);
    if (word.line != 1 || word.column != 1 || !kind.ends_with("OFF"))
      return fail(ErrorCode::BadMagic, word.location(),
                  "not an OFF file: expected OFF, COFF, NOFF or CNOFF at the start");
    if (kind != "OFF")
      return fail(ErrorCode::UnsupportedFormat, word.location(),
                  fmt::format("{} (4D or n-D OFF) is not supported", excerpt(word.text)));
    if (const Token next = scan_.next_on_line(); !next.empty())
      return fail(ErrorCode::UnsupportedFormat, next.location(),
                  next.text == "BINARY" ? std::string("binary OFF is not supported")
                                        : fmt::format("'{}' after {}: the counts must be on the next line",
                                                      excerpt(next.text), excerpt(word.text)));
    colors_ = colors; // read here: OpenMesh reads the stream as plain OFF
    normals_ = normals;
    if (normals) note("NOFF normals dropped (OpenMesh reads OFF streams as plain OFF)");
    return {};
  }

  Result<std::int64_t> count(std::string_view what, std::uint64_t min_bytes) {
    const Token token = scan_.next();
    if (token.empty())
      return fail(ErrorCode::Truncated, scan_.here(),
                  fmt::format("the file ends before the number of {}", what));
    const std::optional<std::int64_t> n = text::parse_integer(token.text);
    if (!n || *n < 0)
      return fail(ErrorCode::Malformed, token.location(),
                  fmt::format("expected the number of {}, found '{}'", what, excerpt(token.text)));
    if (*n > kMaxCount || static_cast<std::uint64_t>(*n) * min_bytes > text_.size())
      return fail(ErrorCode::CountTooLarge, token.location(),
                  fmt::format("{} {} declared, but the whole file has {} bytes", *n, what, text_.size()));
    return *n;
  }

  Result<Token> token(std::string_view element, std::int64_t index, std::int64_t total,
                      std::string_view what) {
    Token t = scan_.next();
    if (t.empty())
      return fail(
          ErrorCode::Truncated, scan_.here(),
          fmt::format("the file ends inside {} {} of {}, before its {}", element, index, total, what));
    return t;
  }

  // Blanks the values left on this line; says so once. Returns whether there were any.
  bool blank_rest_of_line() {
    const Token first = scan_.next_on_line();
    if (first.empty()) return false;
    std::size_t end = first.offset + first.text.size();
    for (Token t = scan_.next_on_line(); !t.empty(); t = scan_.next_on_line())
      end = t.offset + t.text.size();
    std::fill(text_.begin() + static_cast<std::ptrdiff_t>(first.offset),
              text_.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    return true;
  }

  // OpenMesh reads x, y, z into floats with operator>> (anything else silently becomes garbage), then
  // skips the rest of the line.
  Result<void> vertex(std::int64_t index, std::int64_t total) {
    for (std::string_view axis : {"x", "y", "z"}) {
      Result<Token> t = token("vertex", index, total, axis);
      if (!t) return std::move(t).error();
      const std::optional<double> v = text::parse_double(t->text);
      if (!v)
        return fail(
            ErrorCode::Malformed, t->location(),
            fmt::format("expected a number for {} of vertex {}, found '{}'", axis, index, excerpt(t->text)));
      if (!std::isfinite(*v) || std::abs(*v) > FLT_MAX)
        return fail(ErrorCode::NonFinite, t->location(),
                    fmt::format("{} of vertex {} is {}, not a finite float", axis, index, excerpt(t->text)));
    }
    const std::uint64_t line = scan_.here().line;
    if (colors_)
      if (Result<void> ok = color(index); !ok) return ok;
    if (blank_rest_of_line() && !noted_vertex_extras_ && !colors_) {
      note(fmt::format("values after the vertex coordinates ignored (line {} and later)", line));
      noted_vertex_extras_ = true;
    }
    return {};
  }

  // COFF: r g b [a] after the coordinates, integers 0..255 or reals 0..1 (Geomview's rule: a value with a
  // '.' or an exponent is real). The scanner stays before them: they are blanked with the rest of the line.
  Result<void> color(std::int64_t index) {
    Scanner look = scan_;
    if (normals_) // NOFF: nx ny nz come first
      for (int k = 0; k < 3; ++k)
        if (look.next_on_line().empty())
          return fail(ErrorCode::Malformed, look.here(),
                      fmt::format("CNOFF vertex {}: expected nx ny nz r g b [a] after x y z", index));
    std::array<float, 4> c{0, 0, 0, 1};
    std::size_t count = 0;
    Location where = look.here();
    for (Token t = look.next_on_line(); !t.empty(); t = look.next_on_line(), ++count) {
      if (count == 0) where = t.location();
      const std::optional<double> v = text::parse_double(t.text);
      if (!v || !std::isfinite(*v) || count == 4)
        return fail(ErrorCode::Malformed, t.location(),
                    fmt::format("COFF vertex {}: expected r g b [a] after x y z, found '{}'", index,
                                excerpt(t.text)));
      const bool real = t.text.find_first_of(".eE") != std::string_view::npos;
      c[count] = static_cast<float>(std::clamp(real ? *v : *v / 255.0, 0.0, 1.0));
    }
    if (count != 3 && count != 4)
      return fail(ErrorCode::Malformed, where,
                  fmt::format("COFF vertex {} has {} colour values: expected r g b [a]", index, count));
    colors_read.emplace_back(c[0], c[1], c[2], c[3]);
    return {};
  }

public:
  std::vector<Vec4f> colors_read; // COFF: one per vertex

private:
  Result<void> face(std::int64_t index, std::int64_t total, std::int64_t vertices) {
    Result<Token> size = token("face", index, total, "number of corners");
    if (!size) return std::move(size).error();
    const std::optional<std::int64_t> corners = text::parse_integer(size->text);
    if (!corners || *corners < 0)
      return fail(
          ErrorCode::Malformed, size->location(),
          fmt::format("expected the number of corners of face {}, found '{}'", index, excerpt(size->text)));
    for (std::int64_t k = 0; k < *corners; ++k) {
      Result<Token> corner = token("face", index, total, "corners");
      if (!corner) return std::move(corner).error();
      const std::optional<std::int64_t> v = text::parse_integer(corner->text);
      if (!v)
        return fail(
            ErrorCode::Malformed, corner->location(),
            fmt::format("expected a vertex index in face {}, found '{}'", index, excerpt(corner->text)));
      if (*v < 0 || *v >= vertices)
        return fail(
            ErrorCode::IndexOutOfRange, corner->location(),
            fmt::format("face {} refers to vertex {}, but there are {} vertices", index, *v, vertices));
    }
    // OpenMesh would read these values as the next face.
    const std::uint64_t line = scan_.here().line;
    if (blank_rest_of_line() && !noted_face_extras_) {
      note(fmt::format("values after face indices (face colours?) ignored (line {} and later)", line));
      noted_face_extras_ = true;
    }
    return {};
  }

  std::string& text_;
  Scanner scan_;
  std::string_view source_;
  Notes* notes_;
  bool noted_vertex_extras_ = false;
  bool noted_face_extras_ = false;
  bool colors_ = false;
  bool normals_ = false;
};

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
  std::string text(bytes);
  const Units units = blank_comments(text);
  Validator validator(text, source, notes);
  if (Result<void> ok = validator.run(); !ok) return std::move(ok).error();
  Result<Mesh> mesh = openmesh_io::read_openmesh(std::move(text), {.extension = "off"}, source, notes);
  if (mesh) mesh->units = units;
  if (mesh && !validator.colors_read.empty() && validator.colors_read.size() == mesh->vertex_count())
    mesh->colors = std::move(validator.colors_read);
  return mesh;
}

Result<std::string> write(const Mesh& mesh, Notes* notes) {
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  Mesh plain = mesh; // colours are ours to write (COFF), the rest OpenMesh's
  plain.colors.clear();
  Result<std::string> bytes =
      openmesh_io::write_openmesh(plain, {.extension = "off", .binary = false}, "OFF", notes);
  if (bytes && mesh.has_colors()) {
    // "COFF", the counts, then each vertex line with r g b a as integers 0..255.
    std::string out = "C";
    std::size_t at = bytes->find('\n');
    at = bytes->find('\n', at + 1);
    out.append(*bytes, 0, at + 1);
    for (const Vec4f& c : mesh.colors) {
      const std::size_t end = bytes->find('\n', at + 1);
      out.append(*bytes, at + 1, end - at - 1);
      const auto byte = [](float x) { return std::lround(std::clamp(x, 0.0F, 1.0F) * 255.0F); };
      out += fmt::format(" {} {} {} {}\n", byte(c[0]), byte(c[1]), byte(c[2]), byte(c[3]));
      at = end;
    }
    out.append(*bytes, at + 1);
    *bytes = std::move(out);
  }
  if (!bytes || mesh.units == Units::Unknown) return bytes;
  // A comment after the OFF line states the units; our reader finds it, other readers skip it.
  bytes->insert(bytes->find('\n') + 1, fmt::format("# units {}\n", to_string(mesh.units)));
  return bytes;
}

} // namespace pdeface::off
