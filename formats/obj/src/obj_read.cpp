// OBJ through tinyobjloader (thread-safe: no global state), after a validator. tinyobjloader reads a word,
// "nan", "1.5.5" or a missing coordinate as a number without complaint, passes relative indices that reach
// before the first vertex, fails on a comment after a face, and counts a face's corners in an unsigned
// char (third_party_notes/tinyobjloader.md). The validator checks every statement we read and gives its
// line and column, and keeps every value it parsed (exactly, with fast_float: tinyobjloader reads "0e801"
// as a NaN); tinyobjloader then reads the faces.

#include "pdeface/obj/obj.hpp"

#include "pdeface/core/text.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

namespace pdeface::obj {
namespace {

using text::Scanner;
using text::Token;

constexpr std::size_t kMaxIgnoredNamed = 8; // kinds of statement a note names
constexpr std::size_t kMaxCorners = 255;    // tinyobjloader stores a face's corner count in an unsigned char

enum Kind { Vertex, Texcoord, Normal };
constexpr std::array<std::string_view, 3> kKindNames{"vertex", "texture coordinate", "normal"};

constexpr std::array<float, 3> kWhite{1.0F, 1.0F, 1.0F}; // a vertex without r g b, as tinyobjloader has it

// What the validator learnt about the document.
struct Survey {
  // The values of the v (x y z, and r g b), vt (u v) and vn (x y z) statements, in order.
  std::vector<float> positions, colors, texcoords, normals;
  std::array<std::int64_t, 3> counts{}; // v, vt, vn statements
  std::size_t colored = 0;              // v statements with r g b
  std::size_t short_faces = 0;          // faces with fewer than 3 corners (tinyobjloader skips them)
  Units units = Units::Unknown;
  std::string name;                 // of the first 'o'
  std::vector<std::string> ignored; // the first kMaxIgnoredNamed kinds of statement not read
  std::size_t more_ignored = 0;     // statements of other kinds not read
};

class Validator {
public:
  Validator(std::string& text, std::string_view source) : text_(text), source_(source) {}

  // Checks every statement; blanks comments in `text` (tinyobjloader fails on "f 1 2 3 # note").
  Result<Survey> run() {
    if (const std::size_t nul = text_.find('\0'); nul != std::string::npos) {
      Scanner scan(std::string_view(text_).substr(0, nul));
      while (!scan.next().empty()) {
      }
      return fail(ErrorCode::Malformed, scan.here(), "a NUL byte: this is binary data, not an OBJ text");
    }
    std::size_t begin = 0;
    for (std::uint64_t line = 1; begin < text_.size(); ++line) {
      const std::size_t end = std::min(text_.find('\n', begin), text_.size());
      if (Result<void> ok = statement(begin, end, line); !ok) return std::move(ok).error();
      begin = end + 1;
    }
    for (int kind : {Vertex, Texcoord, Normal})
      if (highest_[kind].index > survey_.counts[kind])
        return fail(ErrorCode::IndexOutOfRange, highest_[kind].where,
                    fmt::format("a face refers to {} {}, but there are {}", kKindNames[kind],
                                highest_[kind].index, survey_.counts[kind]));
    return std::move(survey_);
  }

private:
  struct Highest {
    std::int64_t index = 0;
    Location where;
  };

  Error fail(ErrorCode code, Location where, std::string message) const {
    return make_error(code, std::move(message), std::string(source_), where);
  }

  Result<void> statement(std::size_t begin, std::size_t end, std::uint64_t line) {
    if (const std::size_t found = std::string_view(text_).substr(begin, end - begin).find('#');
        found != std::string_view::npos) {
      const std::size_t hash = begin + found;
      if (auto units = text::units_from_comment(std::string_view(text_).substr(hash + 1, end - hash - 1)))
        survey_.units = *units;
      std::fill(text_.begin() + static_cast<std::ptrdiff_t>(hash),
                text_.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    }
    Scanner scan(std::string_view(text_).substr(0, end), begin, line);
    const Token keyword = scan.next_on_line();
    const std::string_view word = keyword.text;
    if (word == "v") return vertex(scan, keyword);
    if (word == "vt") return counted(numbers(scan, keyword, 1, 3, Texcoord));
    if (word == "vn") return counted(numbers(scan, keyword, 3, 3, Normal));
    if (word == "f") return face(scan, keyword);
    if (word == "o" && survey_.name.empty()) {
      const Token name = scan.next_on_line();
      survey_.name = std::string_view(text_).substr(name.offset, end - name.offset);
      while (!survey_.name.empty() && std::isspace(static_cast<unsigned char>(survey_.name.back())))
        survey_.name.pop_back();
    }
    const bool known =
        word.empty() || word == "o" || word == "g" || word == "s" || word == "usemtl" || word == "mtllib";
    if (!known && std::ranges::find(survey_.ignored, word) == survey_.ignored.end()) {
      if (survey_.ignored.size() < kMaxIgnoredNamed)
        survey_.ignored.emplace_back(word);
      else
        ++survey_.more_ignored;
    }
    return {};
  }

  static Result<void> counted(Result<std::size_t> result) {
    if (!result) return std::move(result).error();
    return {};
  }

  // The numbers after `keyword` up to the end of the line: between `least` and `most` of them, each finite
  // and within float range; kept in the survey as floats (what tinyobjloader would store, but parsed
  // exactly: its own parser reads "0e801" as 0 x inf, a NaN).
  Result<std::size_t> numbers(Scanner& scan, const Token& keyword, std::size_t least, std::size_t most,
                              int kind) {
    std::size_t count = 0;
    std::array<float, 6> values{};
    for (Token t = scan.next_on_line(); !t.empty(); t = scan.next_on_line(), ++count) {
      const std::optional<double> v = text::parse_double(t.text);
      if (!v)
        return fail(ErrorCode::Malformed, t.location(),
                    fmt::format("expected a number after {}, found '{}'", keyword.text, excerpt(t.text)));
      if (!std::isfinite(*v) || std::abs(*v) > FLT_MAX)
        return fail(ErrorCode::NonFinite, t.location(),
                    fmt::format("{} is not a finite float", excerpt(t.text)));
      if (count < values.size()) values[count] = static_cast<float>(*v);
    }
    if (count < least || count > most)
      return fail(ErrorCode::Malformed, keyword.location(),
                  least == most
                      ? fmt::format("{} needs {} numbers, found {}", keyword.text, least, count)
                      : fmt::format("{} needs {} to {} numbers, found {}", keyword.text, least, most, count));
    ++survey_.counts[kind];
    std::vector<float>& out = kind == Vertex   ? survey_.positions
                              : kind == Normal ? survey_.normals
                                               : survey_.texcoords;
    const std::size_t width = kind == Texcoord ? 2 : 3; // u v (v = 0 when absent), or x y z
    out.insert(out.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(width));
    if (kind == Vertex) // r g b, or white
      survey_.colors.insert(survey_.colors.end(), count == 6 ? values.begin() + 3 : kWhite.begin(),
                            count == 6 ? values.end() : kWhite.end());
    return count;
  }

  // x y z, x y z w, or x y z r g b (the common vertex-colour extension).
  Result<void> vertex(Scanner& scan, const Token& keyword) {
    Result<std::size_t> count = numbers(scan, keyword, 3, 6, Vertex);
    if (!count) return std::move(count).error();
    if (*count == 5)
      return fail(ErrorCode::Malformed, keyword.location(),
                  "v needs x y z, x y z w or x y z r g b; found 5 numbers");
    if (*count == 6) ++survey_.colored;
    return {};
  }

  Result<void> face(Scanner& scan, const Token& keyword) {
    std::size_t corners = 0;
    for (Token t = scan.next_on_line(); !t.empty(); t = scan.next_on_line(), ++corners)
      if (Result<void> ok = corner(t); !ok) return ok;
    if (corners > kMaxCorners)
      return fail(ErrorCode::UnsupportedFormat, keyword.location(),
                  fmt::format("a face of {} corners: tinyobjloader reads at most {}", corners, kMaxCorners));
    if (corners < 3) ++survey_.short_faces;
    return {};
  }

  // v, v/vt, v//vn or v/vt/vn; indices from 1, or negative: relative to the end of the list so far.
  Result<void> corner(const Token& t) {
    std::array<std::string_view, 3> parts{};
    std::size_t n = 0;
    for (std::string_view rest = t.text;; ++n) {
      const std::size_t slash = rest.find('/');
      if (n == parts.size()) return bad_corner(t);
      parts[n] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    if (parts[0].empty() || (n == 1 && parts[1].empty()) || (n == 2 && parts[2].empty()))
      return bad_corner(t);
    for (int kind : {Vertex, Texcoord, Normal}) {
      if (parts[kind].empty()) continue;
      const std::optional<std::int64_t> index = text::parse_integer(parts[kind]);
      if (!index) return bad_corner(t);
      if (*index == 0)
        return fail(ErrorCode::Malformed, t.location(), "index 0 in a face: OBJ counts from 1");
      if (*index < 0 && -*index > survey_.counts[kind])
        return fail(ErrorCode::IndexOutOfRange, t.location(),
                    fmt::format("relative {} index {} reaches before the first of the {} so far",
                                kKindNames[kind], *index, survey_.counts[kind]));
      if (*index > highest_[kind].index) highest_[kind] = {*index, t.location()};
    }
    return {};
  }

  Error bad_corner(const Token& t) const {
    return fail(ErrorCode::Malformed, t.location(),
                fmt::format("expected v, v/vt, v//vn or v/vt/vn, found '{}'", excerpt(t.text)));
  }

  std::string& text_;
  std::string_view source_;
  Survey survey_;
  std::array<Highest, 3> highest_{};
};

// One value per vertex from per-corner indices, if every corner of a vertex gives the same value.
class CornerAttribute {
public:
  CornerAttribute(const std::vector<tinyobj::real_t>& values, int width, std::size_t vertices)
      : values_(values), width_(width), slot_(vertices, -1) {}

  // Vertex i takes value i: for point clouds with as many vn (or vt) as v.
  void by_order() {
    for (std::size_t i = 0; i < slot_.size(); ++i)
      slot_[i] = static_cast<int>(i);
  }
  void add(int vertex, int index) {
    if (index < 0) {
      ++missing_;
    } else if (int& slot = slot_[static_cast<std::size_t>(vertex)]; slot < 0) {
      slot = index;
    } else if (slot != index && !same(slot, index)) {
      ++conflicts_;
    }
  }
  // Whether every vertex has one value and no corner disagrees.
  [[nodiscard]] bool consistent() const {
    return conflicts_ == 0 && missing_ == 0 && std::ranges::any_of(slot_, [](int s) { return s >= 0; });
  }
  // Why not, for a note.
  [[nodiscard]] std::string why_not() const {
    if (conflicts_ != 0)
      return fmt::format(
          "{} face corners give their vertex a different one than another corner does (seams; keeping "
          "them would split vertices)",
          conflicts_);
    if (missing_ != 0) return fmt::format("{} face corners have none", missing_);
    return "they match no vertex (no faces, and not one per vertex)";
  }
  // The value of component `k` for a vertex (0 for vertices on no face).
  [[nodiscard]] float at(std::size_t vertex, int k) const {
    const int slot = slot_[vertex];
    return slot < 0 ? 0.0f : values_[index(slot, k)];
  }

private:
  [[nodiscard]] std::size_t index(int slot, int k) const {
    return static_cast<std::size_t>(slot) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(k);
  }
  [[nodiscard]] bool same(int a, int b) const {
    for (int k = 0; k < width_; ++k)
      if (values_[index(a, k)] != values_[index(b, k)]) return false;
    return true;
  }
  const std::vector<tinyobj::real_t>& values_;
  int width_;
  std::vector<int> slot_;
  std::size_t conflicts_ = 0;
  std::size_t missing_ = 0;
};

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
  std::string text(bytes);
  // tinyobjloader's blanks are space and tab, and it ends a line at CR: the other blanks the validator
  // knows (CR, VT, FF) become spaces, so that both read the same statements ("v\v1 0 0" is no vertex to
  // tinyobjloader). Lines and columns do not move.
  std::ranges::replace_if(
      text, [](char c) { return c == '\r' || c == '\v' || c == '\f'; }, ' ');
  Result<Survey> survey = Validator(text, source).run();
  if (!survey) return std::move(survey).error();
  if (survey->counts[Vertex] == 0)
    return make_error(ErrorCode::Empty, "no vertices (v statements) in the file", std::string(source));

  tinyobj::ObjReaderConfig config;
  config.triangulate = false; // we fan-triangulate, as for every other format
  config.vertex_color = true;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, /*mtl_text=*/"", config)) { // materials: never opened
    std::string message = reader.Error();
    std::ranges::replace(message, '\n', ' ');
    return make_error(ErrorCode::Malformed, fmt::format("tinyobjloader: {}", excerpt(message, 200)),
                      std::string(source));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t vertices = survey->positions.size() / 3;
  // tinyobjloader gives the faces; the values are the validator's, read exactly. Both saw the same v, vt
  // and vn statements, so the faces' indices refer to them.
  if (attrib.vertices.size() != survey->positions.size() || attrib.normals.size() != survey->normals.size() ||
      attrib.texcoords.size() != survey->texcoords.size())
    return make_error(ErrorCode::Malformed,
                      fmt::format("tinyobjloader read {} vertices where the file has {}",
                                  attrib.vertices.size() / 3, vertices),
                      std::string(source));
  const std::vector<float>& xyz = survey->positions;
  Mesh mesh;
  mesh.name = survey->name;
  mesh.units = survey->units;
  mesh.positions.reserve(vertices);
  for (std::size_t i = 0; i < vertices; ++i)
    mesh.positions.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  CornerAttribute normals(survey->normals, 3, vertices);
  CornerAttribute texcoords(survey->texcoords, 2, vertices);
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t first = 0;
    for (const unsigned char corners : shape.mesh.num_face_vertices) {
      const tinyobj::index_t* c = &shape.mesh.indices[first];
      for (std::size_t k = 0; k < corners; ++k) {
        normals.add(c[k].vertex_index, c[k].normal_index);
        texcoords.add(c[k].vertex_index, c[k].texcoord_index);
      }
      for (std::size_t k = 1; k + 1 < corners; ++k)
        mesh.triangles.push_back({static_cast<std::uint32_t>(c[0].vertex_index),
                                  static_cast<std::uint32_t>(c[k].vertex_index),
                                  static_cast<std::uint32_t>(c[k + 1].vertex_index)});
      first += corners;
    }
  }

  auto note = [&](std::string message) {
    if (notes) notes->push_back(fmt::format("{}: {}", source, std::move(message)));
  };
  auto keep = [&](CornerAttribute& attribute, Kind kind, std::string_view what) {
    const auto in_file = static_cast<std::size_t>(survey->counts[kind]);
    if (in_file == 0) return false;
    if (mesh.triangles.empty() && in_file == vertices) attribute.by_order();
    if (attribute.consistent()) return true;
    note(fmt::format("{} dropped: {}", what, attribute.why_not()));
    return false;
  };
  if (keep(normals, Normal, "normals"))
    for (std::size_t i = 0; i < vertices; ++i)
      mesh.normals.emplace_back(normals.at(i, 0), normals.at(i, 1), normals.at(i, 2));
  if (keep(texcoords, Texcoord, "texture coordinates"))
    for (std::size_t i = 0; i < vertices; ++i)
      mesh.texcoords.emplace_back(texcoords.at(i, 0), texcoords.at(i, 1));
  if (survey->colored == vertices) {
    for (std::size_t i = 0; i < vertices; ++i)
      mesh.colors.emplace_back(survey->colors[3 * i], survey->colors[3 * i + 1], survey->colors[3 * i + 2],
                               1.0f);
  } else if (survey->colored != 0) {
    note(fmt::format("vertex colours dropped: only {} of {} vertices have them", survey->colored, vertices));
  }
  if (survey->short_faces != 0)
    note(fmt::format("{} faces with fewer than 3 corners skipped", survey->short_faces));
  if (!survey->ignored.empty())
    note(fmt::format(
        "statements not read: {}{}", excerpt_list(survey->ignored),
        survey->more_ignored == 0 ? "" : fmt::format(" and {} more statements", survey->more_ignored)));
  if (Result<void> valid = validate(mesh, source); !valid) return std::move(valid).error();
  return mesh;
}

} // namespace pdeface::obj
