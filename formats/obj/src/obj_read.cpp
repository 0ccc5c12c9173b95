// OBJ in one pass over the bytes: every statement we read checked, with its line and column, as it is
// read; numbers parsed exactly (fast_float, then rounded to float), faces' corners resolved to indices
// (relative ones against the counts so far). This was a validator in front of tinyobjloader, which then
// read the faces; the faces are now the validator's own, the same ones (third_party_notes/tinyobjloader.md
// says why tinyobjloader went).

#include "pdeface/obj/obj.hpp"

#include "pdeface/core/image.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace pdeface::obj {
namespace {

using text::Scanner;
using text::Token;

constexpr std::size_t kMaxIgnoredNamed = 8; // kinds of statement a note names
constexpr std::size_t kMaxCorners = 255;    // as tinyobjloader read them (a corner count in an unsigned char)

enum Kind { Vertex, Texcoord, Normal };
constexpr std::array<std::string_view, 3> kKindNames{"vertex", "texture coordinate", "normal"};

constexpr std::array<float, 3> kWhite{1.0F, 1.0F, 1.0F}; // a vertex without r g b

// One face corner: 0-based indices of its vertex, texture coordinate and normal (-1: none).
struct Corner {
  std::int32_t v = -1, vt = -1, vn = -1;
};

// What the validator learnt about the document.
struct Survey {
  // The values of the v (x y z, and r g b), vt (u v) and vn (x y z) statements, in order.
  std::vector<float> positions, colors, texcoords, normals;
  std::array<std::int64_t, 3> counts{}; // v, vt, vn statements
  std::size_t colored = 0;              // v statements with r g b
  std::size_t short_faces = 0;          // faces with fewer than 3 corners (skipped)
  std::vector<Corner> corners;          // of the faces of 3 or more corners, in order
  std::vector<std::uint8_t> face_sizes; // their corner counts
  Units units = Units::Unknown;
  std::string name;                 // of the first 'o'
  std::vector<std::string> ignored; // the first kMaxIgnoredNamed kinds of statement not read
  std::size_t more_ignored = 0;     // statements of other kinds not read
  std::string mtllib;               // the first material library named
  Location mtllib_at;
  std::vector<std::string> materials; // the names `usemtl` gives, the first kMaxIgnoredNamed of them
  std::size_t more_materials = 0;
};

class Validator {
public:
  Validator(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  // Reads and checks every statement.
  Result<Survey> run() {
    if (const void* found = std::memchr(text_.data(), '\0', text_.size()); found != nullptr) {
      const auto nul = static_cast<std::size_t>(static_cast<const char*>(found) - text_.data());
      Scanner scan(text_.substr(0, nul));
      while (!scan.next().empty()) {
      }
      return fail(ErrorCode::Malformed, scan.here(), "a NUL byte: this is binary data, not an OBJ text");
    }
    std::size_t begin = 0;
    next_hash_ = find('#', 0);
    for (std::uint64_t line = 1; begin < text_.size(); ++line) {
      const void* newline = std::memchr(text_.data() + begin, '\n', text_.size() - begin);
      const std::size_t end = newline != nullptr
                                  ? static_cast<std::size_t>(static_cast<const char*>(newline) - text_.data())
                                  : text_.size();
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

  // The first `c` at or after `from`, or the end.
  [[nodiscard]] std::size_t find(char c, std::size_t from) const {
    const void* found = std::memchr(text_.data() + from, c, text_.size() - from);
    return found != nullptr ? static_cast<std::size_t>(static_cast<const char*>(found) - text_.data())
                            : text_.size();
  }

  // A statement ends at its line's end or at a '#', where a comment starts.
  Result<void> statement(std::size_t begin, std::size_t line_end, std::uint64_t line) {
    std::size_t end = line_end;
    if (next_hash_ < begin) next_hash_ = find('#', begin); // one search for the whole text when no '#'
    if (next_hash_ < line_end) {
      const std::size_t hash = next_hash_;
      if (auto units = text::units_from_comment(text_.substr(hash + 1, line_end - hash - 1)))
        survey_.units = *units;
      end = hash;
    }
    Scanner scan(text_.substr(0, end), begin, line);
    const Token keyword = scan.next_on_line();
    const std::string_view word = keyword.text;
    const char* rest = text_.data() + scan.offset();
    const char* stop = text_.data() + end;
    if (word == "v") return quick_numbers(rest, stop, 3, 6, Vertex) ? Result<void>() : vertex(scan, keyword);
    if (word == "vt")
      return quick_numbers(rest, stop, 1, 3, Texcoord) ? Result<void>()
                                                       : counted(numbers(scan, keyword, 1, 3, Texcoord));
    if (word == "vn")
      return quick_numbers(rest, stop, 3, 3, Normal) ? Result<void>()
                                                     : counted(numbers(scan, keyword, 3, 3, Normal));
    if (word == "f") return quick_face(rest, stop, begin, line) ? Result<void>() : face(scan, keyword);
    if (word == "o" && survey_.name.empty()) {
      const Token name = scan.next_on_line();
      survey_.name = text_.substr(name.offset, end - name.offset);
      // CR, VT and FF inside a name are blanks like the others.
      std::ranges::replace_if(
          survey_.name, [](char c) { return c == '\r' || c == '\v' || c == '\f'; }, ' ');
      while (!survey_.name.empty() && std::isspace(static_cast<unsigned char>(survey_.name.back())))
        survey_.name.pop_back();
    }
    if (word == "mtllib" || word == "usemtl") {
      const Token first = scan.next_on_line();
      std::string_view argument =
          first.empty() ? std::string_view() : text_.substr(first.offset, end - first.offset);
      while (!argument.empty() && std::isspace(static_cast<unsigned char>(argument.back())))
        argument.remove_suffix(1);
      if (word == "mtllib" && survey_.mtllib.empty() && !argument.empty()) {
        survey_.mtllib = argument;
        survey_.mtllib_at = keyword.location();
      } else if (word == "usemtl" && !argument.empty() &&
                 std::ranges::find(survey_.materials, argument) == survey_.materials.end()) {
        if (survey_.materials.size() < kMaxIgnoredNamed)
          survey_.materials.emplace_back(argument);
        else
          ++survey_.more_materials;
      }
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

  static bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  // The common statements without a Scanner: `numbers` and `face` for what they accept without a message
  // (the same values, kept the same way); false, having changed nothing, for anything else, which the
  // slow path then reads or refuses with its message.
  bool quick_numbers(const char* p, const char* end, std::size_t least, std::size_t most, int kind) {
    std::array<float, 6> values{};
    std::size_t count = 0;
    for (;;) {
      while (p != end && blank(*p))
        ++p;
      if (p == end) break;
      if (count == values.size()) return false;
      const char* from = (*p == '+' && p + 1 != end && p[1] != '-') ? p + 1 : p;
      double v = 0;
      const auto [next, ec] = fast_float::from_chars(from, end, v);
      if (ec != std::errc() || (next != end && !blank(*next))) return false;
      if (!std::isfinite(v) || std::abs(v) > FLT_MAX) return false;
      values[count++] = static_cast<float>(v);
      p = next;
    }
    if (count < least || count > most || (kind == Vertex && count == 5)) return false;
    keep(values, count, kind);
    return true;
  }

  // An index of up to 9 digits, optionally negative.
  static bool quick_index(const char*& p, const char* end, std::int64_t& value) {
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    const char* digits = p;
    std::int64_t v = 0;
    while (p != end && static_cast<unsigned>(*p - '0') < 10U && p - digits < 10)
      v = v * 10 + (*p++ - '0');
    if (p == digits || p - digits >= 10 || v == 0) return false; // none, too long, or 0 (an error)
    value = negative ? -v : v;
    return true;
  }

  bool quick_face(const char* p, const char* end, std::size_t line_begin, std::uint64_t line) {
    const std::size_t first = survey_.corners.size();
    // The highest index of each kind so far and the token that gave it on this face (its place is only
    // made into a Location, and highest_ only written, for a face that is kept: copying highest_'s three
    // Locations in and out was over half of this function's time).
    std::array<std::int64_t, 3> top{highest_[Vertex].index, highest_[Texcoord].index, highest_[Normal].index};
    std::array<const char*, 3> top_at{};
    std::size_t corners = 0;
    for (;; ++corners) {
      while (p != end && blank(*p))
        ++p;
      if (p == end) break;
      const char* token = p;
      std::array<std::int64_t, 3> index{}; // 0: absent
      bool ok = quick_index(p, end, index[0]);
      if (ok && p != end && *p == '/') {
        ++p;
        if (p != end && *p == '/') {
          ++p;
          ok = quick_index(p, end, index[2]);
        } else {
          ok = quick_index(p, end, index[1]);
          if (ok && p != end && *p == '/') {
            ++p;
            ok = quick_index(p, end, index[2]);
          }
        }
      }
      if (!ok || (p != end && !blank(*p))) {
        survey_.corners.resize(first);
        return false;
      }
      Corner& resolved = survey_.corners.emplace_back();
      for (int kind : {Vertex, Texcoord, Normal}) {
        const std::int64_t i = index[kind];
        if (i == 0) continue;
        if (i < 0 && -i > survey_.counts[kind]) {
          survey_.corners.resize(first);
          return false;
        }
        if (i > top[kind]) {
          top[kind] = i;
          top_at[kind] = token;
        }
        (kind == Vertex     ? resolved.v
         : kind == Texcoord ? resolved.vt
                            : resolved.vn) =
            static_cast<std::int32_t>(i > 0 ? i - 1 : survey_.counts[kind] + i);
      }
    }
    if (corners < 3 || corners > kMaxCorners) {
      survey_.corners.resize(first);
      return false;
    }
    survey_.face_sizes.push_back(static_cast<std::uint8_t>(corners));
    for (int kind : {Vertex, Texcoord, Normal})
      if (top_at[kind] != nullptr)
        highest_[kind] = {top[kind],
                          Location::at_line(line, static_cast<std::uint64_t>(top_at[kind] - text_.data()) -
                                                      line_begin + 1)};
    return true;
  }

  // A v, vt or vn statement's `count` values, which have passed every check, kept.
  void keep(const std::array<float, 6>& values, std::size_t count, int kind) {
    ++survey_.counts[kind];
    std::vector<float>& out = kind == Vertex   ? survey_.positions
                              : kind == Normal ? survey_.normals
                                               : survey_.texcoords;
    const std::size_t width = kind == Texcoord ? 2 : 3; // u v (v = 0 when absent), or x y z
    out.insert(out.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(width));
    if (kind == Vertex) { // r g b, or white
      survey_.colors.insert(survey_.colors.end(), count == 6 ? values.begin() + 3 : kWhite.begin(),
                            count == 6 ? values.end() : kWhite.end());
      if (count == 6) ++survey_.colored;
    }
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
    if (kind == Vertex && count == 5) return count; // refused by `vertex`
    keep(values, count, kind);
    return count;
  }

  // x y z, x y z w, or x y z r g b (the common vertex-colour extension).
  Result<void> vertex(Scanner& scan, const Token& keyword) {
    Result<std::size_t> count = numbers(scan, keyword, 3, 6, Vertex);
    if (!count) return std::move(count).error();
    if (*count == 5)
      return fail(ErrorCode::Malformed, keyword.location(),
                  "v needs x y z, x y z w or x y z r g b; found 5 numbers");
    return {};
  }

  Result<void> face(Scanner& scan, const Token& keyword) {
    std::size_t corners = 0;
    const std::size_t first = survey_.corners.size();
    for (Token t = scan.next_on_line(); !t.empty(); t = scan.next_on_line(), ++corners)
      if (Result<void> ok = corner(t); !ok) return ok;
    if (corners > kMaxCorners)
      return fail(ErrorCode::UnsupportedFormat, keyword.location(),
                  fmt::format("a face of {} corners: tinyobjloader reads at most {}", corners, kMaxCorners));
    if (corners < 3) {
      ++survey_.short_faces;
      survey_.corners.resize(first);
    } else {
      survey_.face_sizes.push_back(static_cast<std::uint8_t>(corners));
    }
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
    Corner& resolved = survey_.corners.emplace_back();
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
      // From 1, or from the end of the list so far; in range once every index is checked (`run`).
      const std::int64_t zero_based = *index > 0 ? *index - 1 : survey_.counts[kind] + *index;
      (kind == Vertex     ? resolved.v
       : kind == Texcoord ? resolved.vt
                          : resolved.vn) =
          static_cast<std::int32_t>(std::clamp<std::int64_t>(zero_based, -1, INT32_MAX));
    }
    return {};
  }

  Error bad_corner(const Token& t) const {
    return fail(ErrorCode::Malformed, t.location(),
                fmt::format("expected v, v/vt, v//vn or v/vt/vn, found '{}'", excerpt(t.text)));
  }

  std::string_view text_;
  std::string_view source_;
  std::size_t next_hash_ = 0; // the first '#' not before the current line
  Survey survey_;
  std::array<Highest, 3> highest_{};
};

// One value per vertex from per-corner indices, if every corner of a vertex gives the same value.
class CornerAttribute {
public:
  CornerAttribute(const std::vector<float>& values, int width, std::size_t vertices)
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
  // Whether corners disagree, every corner having a value: a texture's seams.
  [[nodiscard]] bool seams() const { return conflicts_ != 0 && missing_ == 0; }
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
  const std::vector<float>& values_;
  int width_;
  std::vector<int> slot_;
  std::size_t conflicts_ = 0;
  std::size_t missing_ = 0;
};

// A material library's `map_Kd` options (before the file name) and how many values each takes at most.
constexpr std::array<std::pair<std::string_view, int>, 12> kMapOptions{{{"-blendu", 1},
                                                                        {"-blendv", 1},
                                                                        {"-bm", 1},
                                                                        {"-boost", 1},
                                                                        {"-cc", 1},
                                                                        {"-clamp", 1},
                                                                        {"-imfchan", 1},
                                                                        {"-mm", 2},
                                                                        {"-o", 3},
                                                                        {"-s", 3},
                                                                        {"-t", 3},
                                                                        {"-texres", 1}}};

// The file name after `map_Kd` and its options: the rest of the line.
std::string_view map_file(std::string_view rest) {
  auto token = [&rest]() {
    while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.front())))
      rest.remove_prefix(1);
    const std::size_t end = std::min(rest.size(), rest.find_first_of(" \t\r\v\f"));
    return rest.substr(0, end);
  };
  for (;;) {
    const std::string_view saved = rest;
    const std::string_view word = token();
    const auto* option = std::ranges::find(kMapOptions, word, &std::pair<std::string_view, int>::first);
    if (option == kMapOptions.end()) {
      rest = saved;
      break;
    }
    rest.remove_prefix(word.size());
    for (int k = 0; k < option->second; ++k) {
      const std::string_view before = rest;
      const std::string_view value = token();
      if (value != "on" && value != "off" && !text::parse_double(value)) {
        rest = before;
        break;
      }
      rest.remove_prefix(value.size());
    }
  }
  while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.front())))
    rest.remove_prefix(1);
  while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.back())))
    rest.remove_suffix(1);
  return rest;
}

// Material `wanted` (the first when empty) of the library `mtllib`, obtained through `resolve`: its `Kd`
// (as the base colour when it has no `map_Kd`: a viewer shows the photo, not the photo times Kd), `d` and
// `map_Kd` (relative to the library's folder). A library or image that cannot be read is a note.
Result<std::optional<Material>> read_material(const Resolver& resolve, std::string_view mtllib,
                                              std::string_view wanted, std::string_view source,
                                              Notes* notes) {
  auto note = [&](std::string message) {
    if (notes) notes->push_back(std::move(message));
  };
  if (!resolve) {
    note(fmt::format("{}: material library '{}' not read: reading from memory, no folder to find it in",
                     source, excerpt(mtllib)));
    return std::optional<Material>();
  }
  Result<std::string> library = resolve(mtllib);
  if (!library) {
    note(fmt::format("{}: material library '{}' not read ({}): no material", source, excerpt(mtllib),
                     library.error().message));
    return std::optional<Material>();
  }
  const std::string library_name = clean_name(mtllib);
  std::optional<Material> material;
  std::optional<Vec3f> kd;
  std::string map;
  float alpha = 1.0F;
  bool in_wanted = false, done = false;
  std::string_view rest = *library;
  for (std::uint64_t line = 1; !rest.empty() && !done; ++line) {
    const std::size_t newline = std::min(rest.size(), rest.find('\n'));
    std::string_view statement = rest.substr(0, newline);
    rest.remove_prefix(std::min(rest.size(), newline + 1));
    statement = statement.substr(0, std::min(statement.size(), statement.find('#')));
    Scanner scan(statement, 0, line);
    const Token keyword = scan.next_on_line();
    if (keyword.text == "newmtl") {
      const Token name = scan.next_on_line();
      if (in_wanted) {
        done = true;
        break;
      }
      in_wanted = wanted.empty() || name.text == wanted;
      if (in_wanted) material.emplace().name = name.text;
      continue;
    }
    if (!in_wanted) continue;
    if (keyword.text == "Kd" || keyword.text == "d") {
      std::array<float, 3> v{};
      std::size_t count = 0;
      for (Token t = scan.next_on_line(); !t.empty() && count < 3; t = scan.next_on_line()) {
        const std::optional<double> x = text::parse_double(t.text);
        if (!x || !std::isfinite(*x)) {
          count = 0;
          break;
        }
        v[count++] = static_cast<float>(std::clamp(*x, 0.0, 1.0));
      }
      if (keyword.text == "Kd" && count == 3)
        kd = Vec3f(v[0], v[1], v[2]);
      else if (keyword.text == "d" && count == 1)
        alpha = v[0];
      else
        note(fmt::format("{}:{}: {} ignored: expected {} numbers", library_name, line, keyword.text,
                         keyword.text == "Kd" ? 3 : 1));
    } else if (keyword.text == "map_Kd") {
      map = map_file(statement.substr(std::min(statement.size(), keyword.offset + keyword.text.size())));
    }
  }
  if (!material) {
    note(fmt::format("{}: material '{}' not found in '{}': no material", source, excerpt(wanted),
                     library_name));
    return material;
  }
  material->base_color = Vec4f(1.0F, 1.0F, 1.0F, alpha);
  if (kd && map.empty()) material->base_color.head<3>() = *kd;
  if (!map.empty()) {
    // Relative to the library's folder, as the reference to the library is to the OBJ's.
    const std::string reference =
        (std::filesystem::path(std::string(mtllib)).parent_path() / std::string(map))
            .lexically_normal()
            .generic_string();
    Result<Image> image = resolve_image(resolve, reference, library_name, notes);
    if (!image) return std::move(image).error();
    material->base_color_image = std::move(image).value();
  }
  return material;
}

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes, const Resolver& resolve) {
  Result<Survey> survey = Validator(bytes, source).run();
  if (!survey) return std::move(survey).error();
  if (survey->counts[Vertex] == 0)
    return make_error(ErrorCode::Empty, "no vertices (v statements) in the file", std::string(source));

  const std::size_t vertices = survey->positions.size() / 3;
  const std::vector<float>& xyz = survey->positions;
  Mesh mesh;
  mesh.name = survey->name;
  mesh.units = survey->units;
  mesh.positions.resize(vertices);
  for (std::size_t i = 0; i < vertices; ++i)
    mesh.positions[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  CornerAttribute normals(survey->normals, 3, vertices);
  CornerAttribute texcoords(survey->texcoords, 2, vertices);
  const bool with_normals = survey->counts[Normal] != 0;
  const bool with_texcoords = survey->counts[Texcoord] != 0;
  std::size_t triangles = 0;
  for (const std::uint8_t corners : survey->face_sizes)
    triangles += corners - 2U;
  mesh.triangles.reserve(triangles);
  const Corner* c = survey->corners.data(); // NOLINT(misc-const-correctness): walked again below
  for (const std::uint8_t corners : survey->face_sizes) {
    for (std::size_t k = 0; k < corners; ++k) {
      if (with_normals) normals.add(c[k].v, c[k].vn);
      if (with_texcoords) texcoords.add(c[k].v, c[k].vt);
    }
    for (std::size_t k = 1; k + 1 < corners; ++k)
      mesh.triangles.push_back({static_cast<std::uint32_t>(c[0].v), static_cast<std::uint32_t>(c[k].v),
                                static_cast<std::uint32_t>(c[k + 1].v)});
    c += corners;
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
  if (const auto in_file = static_cast<std::size_t>(survey->counts[Texcoord]);
      texcoords.seams() && !mesh.triangles.empty()) {
    // Seams: the texture coordinates stay per corner, the vertices whole.
    mesh.texcoords.resize(in_file);
    for (std::size_t i = 0; i < in_file; ++i)
      mesh.texcoords[i] = Vec2f(survey->texcoords[2 * i], survey->texcoords[2 * i + 1]);
    mesh.texcoord_triangles.reserve(mesh.triangles.size());
    c = survey->corners.data();
    for (const std::uint8_t corners : survey->face_sizes) {
      for (std::size_t k = 1; k + 1 < corners; ++k)
        mesh.texcoord_triangles.push_back({static_cast<std::uint32_t>(c[0].vt),
                                           static_cast<std::uint32_t>(c[k].vt),
                                           static_cast<std::uint32_t>(c[k + 1].vt)});
      c += corners;
    }
  } else if (keep(texcoords, Texcoord, "texture coordinates")) {
    for (std::size_t i = 0; i < vertices; ++i)
      mesh.texcoords.emplace_back(texcoords.at(i, 0), texcoords.at(i, 1));
  }
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
  if (!survey->mtllib.empty()) {
    if (survey->materials.size() > 1 || survey->more_materials != 0)
      note(fmt::format("materials after the first ({}) not used: a mesh holds one",
                       excerpt_list(std::span(survey->materials).subspan(1))));
    Result<std::optional<Material>> material = read_material(
        resolve, survey->mtllib, survey->materials.empty() ? "" : survey->materials.front(), source, notes);
    if (!material) return std::move(material).error();
    mesh.material = std::move(material).value();
  }
  return mesh;
}

} // namespace pdeface::obj
