#include "ply_layout.hpp"

#include "pdeface/core/text.hpp"
#include "pdeface/text/scanner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>

namespace pdeface::ply::detail {
namespace {

using text::Scanner;
using text::Token;

// ---- scalar types -------------------------------------------------------------------------------------

struct ScalarName {
  std::string_view name;
  Scalar type;
};
constexpr std::array<ScalarName, 16> kScalarNames{{
    {"char", Scalar::Int8},
    {"int8", Scalar::Int8},
    {"uchar", Scalar::UInt8},
    {"uint8", Scalar::UInt8},
    {"short", Scalar::Int16},
    {"int16", Scalar::Int16},
    {"ushort", Scalar::UInt16},
    {"uint16", Scalar::UInt16},
    {"int", Scalar::Int32},
    {"int32", Scalar::Int32},
    {"uint", Scalar::UInt32},
    {"uint32", Scalar::UInt32},
    {"float", Scalar::Float32},
    {"float32", Scalar::Float32},
    {"double", Scalar::Float64},
    {"float64", Scalar::Float64},
}};

std::optional<Scalar> scalar_from_name(std::string_view name) {
  const auto* it = std::ranges::find(kScalarNames, name, &ScalarName::name);
  if (it == kScalarNames.end()) return std::nullopt;
  return it->type;
}

// The classic PLY spelling, which OpenMesh reads.
std::string_view name_of(Scalar type) {
  switch (type) {
  case Scalar::Int8: return "char";
  case Scalar::UInt8: return "uchar";
  case Scalar::Int16: return "short";
  case Scalar::UInt16: return "ushort";
  case Scalar::Int32: return "int";
  case Scalar::UInt32: return "uint";
  case Scalar::Float32: return "float";
  case Scalar::Float64: return "double";
  }
  return "?";
}

} // namespace

std::size_t size_of(Scalar type) {
  switch (type) {
  case Scalar::Int8:
  case Scalar::UInt8: return 1;
  case Scalar::Int16:
  case Scalar::UInt16: return 2;
  case Scalar::Int32:
  case Scalar::UInt32:
  case Scalar::Float32: return 4;
  case Scalar::Float64: return 8;
  }
  return 0;
}

namespace {

bool is_integer(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

template <class T> bool in_range_of(double v) {
  return v >= static_cast<double>(std::numeric_limits<T>::min()) &&
         v <= static_cast<double>(std::numeric_limits<T>::max());
}

bool in_range(Scalar type, double v) {
  switch (type) {
  case Scalar::Int8: return in_range_of<std::int8_t>(v);
  case Scalar::UInt8: return in_range_of<std::uint8_t>(v);
  case Scalar::Int16: return in_range_of<std::int16_t>(v);
  case Scalar::UInt16: return in_range_of<std::uint16_t>(v);
  case Scalar::Int32: return in_range_of<std::int32_t>(v);
  case Scalar::UInt32: return in_range_of<std::uint32_t>(v);
  case Scalar::Float32:
  case Scalar::Float64: return true;
  }
  return false;
}

template <class T> double load(const unsigned char* raw) {
  T value;
  std::memcpy(&value, raw, sizeof value);
  return static_cast<double>(value);
}

double decode(Scalar type, const char* data, bool big_endian) {
  std::array<unsigned char, 8> raw{};
  const std::size_t size = size_of(type);
  std::memcpy(raw.data(), data, size);
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(raw.begin(), raw.begin() + size);
  switch (type) {
  case Scalar::Int8: return load<std::int8_t>(raw.data());
  case Scalar::UInt8: return load<std::uint8_t>(raw.data());
  case Scalar::Int16: return load<std::int16_t>(raw.data());
  case Scalar::UInt16: return load<std::uint16_t>(raw.data());
  case Scalar::Int32: return load<std::int32_t>(raw.data());
  case Scalar::UInt32: return load<std::uint32_t>(raw.data());
  case Scalar::Float32: return load<float>(raw.data());
  case Scalar::Float64: return load<double>(raw.data());
  }
  return 0.0;
}

// OpenMesh reads coordinates and colours into floats: anything else becomes inf or garbage.
bool fits_float(double v) { return std::isfinite(v) && std::abs(v) <= FLT_MAX; }

// ---- the header ---------------------------------------------------------------------------------------

// OpenMesh handles are int: no element may have more items.
constexpr std::int64_t kMaxCount = std::numeric_limits<std::int32_t>::max();

constexpr std::array<std::string_view, 12> kCoordinateNames{"x", "y", "z", "nx", "ny",        "nz",
                                                            "u", "v", "s", "t",  "texture_u", "texture_v"};
constexpr std::array<std::string_view, 7> kVertexColorNames{
    "red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
constexpr std::array<std::string_view, 4> kFaceColorNames{"red", "green", "blue", "alpha"};

template <std::size_t N> bool one_of(std::string_view name, const std::array<std::string_view, N>& names) {
  return std::ranges::find(names, name) != names.end();
}

// OpenMesh reads texture coordinates named u/v or s/t; MeshLab and VCG write texture_u/texture_v.
std::string_view openmesh_name(std::string_view name) {
  if (name == "texture_u") return "u";
  if (name == "texture_v") return "v";
  return name;
}

class HeaderParser {
public:
  HeaderParser(std::string_view bytes, std::string_view source) : bytes_(bytes), source_(source) {}

  Result<Header> parse() {
    if (bytes_.empty()) return make_error(ErrorCode::Empty, "the file is empty", std::string(source_));
    std::size_t newline = bytes_.find('\n');
    Scanner first(bytes_.substr(0, newline));
    if (!bytes_.starts_with("ply") || first.next_on_line().text != "ply" || !first.next_on_line().empty())
      return fail(ErrorCode::BadMagic, Location::at_line(1, 1),
                  "not a PLY file: expected 'ply' on the first line");
    for (std::uint64_t line = 2; newline != std::string_view::npos; ++line) {
      const std::size_t begin = newline + 1;
      newline = bytes_.find('\n', begin);
      if (newline == std::string_view::npos)
        return fail(ErrorCode::Truncated, Location::at_line(line),
                    "the header ends without an end_header line");
      const std::string_view text = bytes_.substr(0, newline);
      Scanner scan(text, begin, line);
      const Token keyword = scan.next_on_line();
      if (keyword.text == "end_header") {
        if (!have_format_)
          return fail(ErrorCode::Malformed, keyword.location(), "the header has no format line");
        header_.data_offset = newline + 1;
        header_.data_line = line + 1;
        return std::move(header_);
      }
      if (Result<void> ok = statement(keyword, scan, text); !ok) return std::move(ok).error();
    }
    return fail(ErrorCode::Truncated, Location::at_line(1), "the header ends without an end_header line");
  }

private:
  Error fail(ErrorCode code, Location where, std::string message) const {
    return make_error(code, std::move(message), std::string(source_), where);
  }
  Error expected(const Token& token, std::string_view what) const {
    if (token.empty()) return fail(ErrorCode::Malformed, token.location(), fmt::format("expected {}", what));
    return fail(ErrorCode::Malformed, token.location(),
                fmt::format("expected {}, found '{}'", what, excerpt(token.text)));
  }
  Result<void> end_of_line(Scanner& scan) const {
    if (const Token extra = scan.next_on_line(); !extra.empty())
      return fail(ErrorCode::Malformed, extra.location(),
                  fmt::format("unexpected '{}' at the end of the line", excerpt(extra.text)));
    return {};
  }

  Result<void> statement(const Token& keyword, Scanner& scan, std::string_view line_text) {
    if (keyword.empty() || keyword.text == "obj_info") return {};
    if (keyword.text == "comment") {
      if (auto units = text::units_from_comment(line_text.substr(keyword.offset + keyword.text.size())))
        header_.units = *units;
      if (const Token word = scan.next_on_line();
          word.text == "TextureFile" && header_.texture_file.empty()) {
        std::string_view name = line_text.substr(std::min(line_text.size(), word.offset + word.text.size()));
        while (!name.empty() && std::isspace(static_cast<unsigned char>(name.front())))
          name.remove_prefix(1);
        while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back())))
          name.remove_suffix(1);
        header_.texture_file = name;
      }
      return {};
    }
    if (keyword.text == "format") return format(scan);
    if (keyword.text == "element") return element(scan, keyword.line);
    if (keyword.text == "property") return property(scan, keyword);
    return fail(
        ErrorCode::Malformed, keyword.location(),
        fmt::format("unknown header keyword '{}' (expected format, comment, element, property or end_header)",
                    excerpt(keyword.text)));
  }

  Result<void> format(Scanner& scan) {
    const Token encoding = scan.next_on_line();
    if (encoding.text == "ascii")
      header_.encoding = Encoding::Ascii;
    else if (encoding.text == "binary_little_endian")
      header_.encoding = Encoding::BinaryLittleEndian;
    else if (encoding.text == "binary_big_endian")
      header_.encoding = Encoding::BinaryBigEndian;
    else if (encoding.empty())
      return expected(encoding, "ascii, binary_little_endian or binary_big_endian");
    else
      return fail(
          ErrorCode::UnsupportedFormat, encoding.location(),
          fmt::format("unknown PLY format '{}' (expected ascii, binary_little_endian or binary_big_endian)",
                      excerpt(encoding.text)));
    const Token version = scan.next_on_line();
    if (version.empty()) return expected(version, "the version 1.0");
    if (text::parse_double(version.text) != 1.0)
      return fail(ErrorCode::UnsupportedVersion, version.location(),
                  fmt::format("PLY version {} is not supported (expected 1.0)", excerpt(version.text)));
    have_format_ = true;
    return end_of_line(scan);
  }

  Result<void> element(Scanner& scan, std::uint64_t line) {
    const Token name = scan.next_on_line();
    if (name.empty()) return expected(name, "an element name");
    const Token count = scan.next_on_line();
    const std::optional<std::int64_t> n = text::parse_integer(count.text);
    if (!n || *n < 0) return expected(count, fmt::format("the number of '{}' items", excerpt(name.text)));
    if (*n > kMaxCount)
      return fail(ErrorCode::CountTooLarge, count.location(),
                  fmt::format("element {} declares {} items; at most {} are supported", excerpt(name.text),
                              *n, kMaxCount));
    header_.elements.push_back(
        {std::string(name.text), excerpt(name.text), static_cast<std::uint64_t>(*n), {}, line});
    return end_of_line(scan);
  }

  Result<Scalar> type(const Token& token) const {
    if (token.empty()) return expected(token, "a property type");
    const std::optional<Scalar> scalar = scalar_from_name(token.text);
    if (!scalar)
      return fail(
          ErrorCode::Malformed, token.location(),
          fmt::format("unknown property type '{}' (expected char, uchar, short, ushort, int, uint, float, "
                      "double, or int8 ... float64)",
                      excerpt(token.text)));
    return *scalar;
  }

  Result<void> property(Scanner& scan, const Token& keyword) {
    if (header_.elements.empty())
      return fail(ErrorCode::Malformed, keyword.location(), "property declared before any element");
    Property property;
    property.line = keyword.line;
    Token token = scan.next_on_line();
    if (token.text == "list") {
      Result<Scalar> count_type = type(scan.next_on_line());
      if (!count_type) return std::move(count_type).error();
      if (!is_integer(*count_type))
        return fail(ErrorCode::Malformed, keyword.location(),
                    "the length of a list must have an integer type");
      property.count_type = *count_type;
      token = scan.next_on_line();
    }
    Result<Scalar> value_type = type(token);
    if (!value_type) return std::move(value_type).error();
    property.type = *value_type;
    const Token name = scan.next_on_line();
    if (name.empty()) return expected(name, "a property name");
    property.name = name.text;
    property.label = excerpt(name.text);
    header_.elements.back().properties.push_back(std::move(property));
    return end_of_line(scan);
  }

  std::string_view bytes_;
  std::string_view source_;
  Header header_;
  bool have_format_ = false;
};

// ---- what OpenMesh can read ---------------------------------------------------------------------------

class RoleAssigner {
public:
  RoleAssigner(Header& header, std::string_view source, Notes* notes)
      : header_(header), source_(source), notes_(notes) {}

  Result<void> run() {
    Element* vertex = nullptr;
    Element* face = nullptr;
    std::vector<std::string> ignored;
    for (Element& e : header_.elements) {
      Element** slot = e.name == "vertex" ? &vertex : e.name == "face" ? &face : nullptr;
      if (!slot) {
        ignored.push_back(fmt::format("{} ({} items)", e.label, e.count));
        continue;
      }
      if (*slot) return fail(ErrorCode::Malformed, e.line, fmt::format("a second element {}", e.label));
      *slot = &e;
    }
    if (!ignored.empty()) note(fmt::format("elements ignored: {}", excerpt_list(ignored)));
    if (!vertex)
      return fail(ErrorCode::Malformed, header_.data_line - 1, "the header declares no vertex element");
    if (Result<void> ok = vertex_roles(*vertex); !ok) return ok;
    if (face) return face_roles(*face);
    return {};
  }

private:
  Error fail(ErrorCode code, std::uint64_t line, std::string message) const {
    return make_error(code, std::move(message), std::string(source_), Location::at_line(line));
  }
  void note(std::string message) const {
    if (notes_) notes_->push_back(fmt::format("{}: {}", source_, message));
  }
  Result<void> color_type(const Property& p) const {
    if (p.type == Scalar::UInt8 || p.type == Scalar::Float32) return {};
    return fail(ErrorCode::UnsupportedFormat, p.line,
                fmt::format("colour property {} is {}: OpenMesh reads colours only as uchar or float",
                            p.label, name_of(p.type)));
  }

  Result<void> vertex_roles(Element& vertex) const {
    std::vector<std::string> ignored;
    bool doubles = false;
    for (Property& p : vertex.properties) {
      if (p.count_type)
        return fail(
            ErrorCode::UnsupportedFormat, p.line,
            fmt::format("list property {} in element vertex: OpenMesh reads only the faces' vertex_indices "
                        "lists",
                        p.label));
      if (one_of(p.name, kCoordinateNames)) {
        if (is_integer(p.type))
          return fail(ErrorCode::UnsupportedFormat, p.line,
                      fmt::format("property {} is {}: OpenMesh reads coordinates only as float or double",
                                  p.label, name_of(p.type)));
        p.role = Role::Coordinate;
        doubles = doubles || p.type == Scalar::Float64;
      } else if (one_of(p.name, kVertexColorNames)) {
        if (Result<void> ok = color_type(p); !ok) return ok;
        p.role = Role::Color;
      } else {
        ignored.push_back(p.name);
      }
    }
    for (std::string_view axis : {"x", "y", "z"})
      if (std::ranges::find(vertex.properties, axis, &Property::name) == vertex.properties.end())
        return fail(ErrorCode::Malformed, vertex.line,
                    fmt::format("element vertex has no property {}", axis));
    if (!ignored.empty()) note(fmt::format("vertex properties ignored: {}", excerpt_list(ignored)));
    if (doubles) note("double coordinates are read as float32 (OpenMesh's PLY reader)");
    return {};
  }

  Result<void> face_roles(Element& face) const {
    std::vector<std::string> ignored;
    bool indices = false;
    for (Property& p : face.properties) {
      if (p.name == "vertex_indices" || p.name == "vertex_index") {
        if (!p.count_type)
          return fail(ErrorCode::Malformed, p.line, fmt::format("property {} must be a list", p.label));
        const Scalar count = *p.count_type;
        if (count != Scalar::UInt8 && count != Scalar::UInt16 && count != Scalar::Int32)
          return fail(ErrorCode::UnsupportedFormat, p.line,
                      fmt::format("{} lengths of type {}: OpenMesh reads only uchar, ushort or int lengths",
                                  p.label, name_of(count)));
        if (!is_integer(p.type))
          return fail(ErrorCode::Malformed, p.line,
                      fmt::format("{} entries must have an integer type", p.label));
        p.role = Role::Indices;
        indices = true;
      } else if (p.count_type) {
        return fail(ErrorCode::UnsupportedFormat, p.line,
                    fmt::format("list property {} in element face: OpenMesh misreads lists other than "
                                "vertex_indices",
                                p.label));
      } else if (one_of(p.name, kFaceColorNames)) {
        if (Result<void> ok = color_type(p); !ok) return ok;
        p.role = Role::Color;
      } else {
        ignored.push_back(p.name);
      }
    }
    if (!indices) return fail(ErrorCode::Malformed, face.line, "element face has no vertex_indices list");
    if (!ignored.empty()) note(fmt::format("face properties ignored: {}", excerpt_list(ignored)));
    return {};
  }

  Header& header_;
  std::string_view source_;
  Notes* notes_;
};

// ---- walking the data ---------------------------------------------------------------------------------

// Which value is being read, for messages.
struct Context {
  const Element& element;
  std::uint64_t index;
  const Property& property;
};

std::string describe(const Context& c) {
  return fmt::format("property {} of {} {}", c.property.label, c.element.label, c.index);
}

class BinaryValues {
public:
  BinaryValues(std::string_view bytes, std::size_t offset, bool big_endian, std::string_view source)
      : bytes_(bytes), pos_(offset), big_endian_(big_endian), source_(source) {}

  void start_record() { record_ = pos_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] Location last() const { return Location::at_byte(last_); }

  Result<double> read(Scalar type, const Context& c) {
    const std::size_t size = size_of(type);
    if (bytes_.size() - pos_ < size)
      return make_error(
          ErrorCode::Truncated,
          fmt::format("the data ends at byte {} inside {} {} of {}, which starts here, before its {}",
                      bytes_.size(), c.element.label, c.index, c.element.count, c.property.label),
          std::string(source_), Location::at_byte(record_));
    last_ = pos_;
    pos_ += size;
    return decode(type, bytes_.data() + last_, big_endian_);
  }

  void note_trailing(Notes* notes) const {
    if (notes && pos_ < bytes_.size())
      notes->push_back(fmt::format("{}: {} bytes after the last element ignored (from byte {})", source_,
                                   bytes_.size() - pos_, pos_));
  }

private:
  std::string_view bytes_;
  std::size_t pos_;
  std::size_t record_ = 0;
  std::size_t last_ = 0;
  bool big_endian_;
  std::string_view source_;
};

class AsciiValues {
public:
  AsciiValues(std::string_view bytes, std::size_t offset, std::uint64_t line, std::string_view source)
      : scan_(bytes, offset, line), source_(source) {}

  void start_record() {}
  [[nodiscard]] std::size_t offset() const { return scan_.offset(); }
  [[nodiscard]] Location last() const { return last_.location(); }

  Result<double> read(Scalar type, const Context& c) {
    last_ = scan_.next();
    if (last_.empty())
      return make_error(ErrorCode::Truncated,
                        fmt::format("the data ends inside {} {} of {}, before its {}", c.element.label,
                                    c.index, c.element.count, c.property.label),
                        std::string(source_), scan_.here());
    std::optional<double> value;
    if (is_integer(type)) {
      if (const std::optional<std::int64_t> n = text::parse_integer(last_.text))
        value = static_cast<double>(*n);
    } else {
      value = text::parse_double(last_.text);
    }
    if (!value || !in_range(type, *value))
      return make_error(
          ErrorCode::Malformed,
          fmt::format("expected a {} for {}, found '{}'", name_of(type), describe(c), excerpt(last_.text)),
          std::string(source_), last_.location());
    return *value;
  }

  void note_trailing(Notes* notes) {
    if (notes && !scan_.at_end())
      notes->push_back(fmt::format("{}:{}: data after the last element ignored", source_, scan_.here().line));
  }

private:
  Scanner scan_;
  Token last_;
  std::string_view source_;
};

// The smallest possible record: empty lists, one-character ASCII values.
std::uint64_t min_record_bytes(const Element& e, Encoding encoding) {
  std::uint64_t min_bytes = 0;
  for (const Property& p : e.properties)
    min_bytes += encoding == Encoding::Ascii ? 2 : size_of(p.count_type ? *p.count_type : p.type);
  if (encoding == Encoding::Ascii && min_bytes > 0) --min_bytes; // no blank needed after the very last value
  return min_bytes;
}

// Fails fast, before reading anything, on a count no file of this size could hold.
Result<void> check_count_fits(const Element& e, Encoding encoding, std::size_t file_size,
                              std::string_view source) {
  if (count_fits(e, encoding, file_size)) return {};
  const std::uint64_t min_bytes = min_record_bytes(e, encoding);
  return make_error(
      ErrorCode::CountTooLarge,
      fmt::format("element {} declares {} items of at least {} bytes each ({} bytes), but the whole "
                  "file has {} bytes",
                  e.label, e.count, min_bytes, e.count * min_bytes, file_size),
      std::string(source), Location::at_line(e.line));
}

template <class Values>
Result<DataRanges> walk(const Header& header, Values values, std::string_view bytes, std::string_view source,
                        Notes* notes) {
  const auto vertex = std::ranges::find(header.elements, "vertex", &Element::name);
  const double vertex_count = static_cast<double>(vertex->count);
  DataRanges ranges;
  for (const Element& e : header.elements) {
    if (Result<void> fits = check_count_fits(e, header.encoding, bytes.size(), source); !fits)
      return std::move(fits).error();
    const std::size_t begin = values.offset();
    for (std::uint64_t i = 0; i < e.count && !e.properties.empty(); ++i) {
      values.start_record();
      for (const Property& p : e.properties) {
        const Context c{e, i, p};
        if (!p.count_type) {
          Result<double> v = values.read(p.type, c);
          if (!v) return std::move(v).error();
          if (p.role != Role::Ignored && !fits_float(*v))
            return make_error(ErrorCode::NonFinite,
                              fmt::format("{} is {}, not a finite float", describe(c), *v),
                              std::string(source), values.last());
          continue;
        }
        Result<double> length = values.read(*p.count_type, c);
        if (!length) return std::move(length).error();
        if (*length < 0)
          return make_error(ErrorCode::Malformed,
                            fmt::format("negative list length {} for {}", *length, describe(c)),
                            std::string(source), values.last());
        for (auto k = static_cast<std::uint64_t>(*length); k > 0; --k) {
          Result<double> index = values.read(p.type, c);
          if (!index) return std::move(index).error();
          if (p.role == Role::Indices && (*index < 0 || *index >= vertex_count))
            return make_error(ErrorCode::IndexOutOfRange,
                              fmt::format("face {} refers to vertex {}, but there are {} vertices", i, *index,
                                          vertex->count),
                              std::string(source), values.last());
        }
      }
    }
    const std::string_view data = bytes.substr(begin, values.offset() - begin);
    if (e.name == "vertex") ranges.vertices = data;
    if (e.name == "face") ranges.faces = data;
  }
  values.note_trailing(notes);
  return ranges;
}

} // namespace

bool count_fits(const Element& e, Encoding encoding, std::size_t file_size) {
  return e.count * min_record_bytes(e, encoding) <= file_size;
}

Result<Header> parse_header(std::string_view bytes, std::string_view source, Notes* notes) {
  Result<Header> header = HeaderParser(bytes, source).parse();
  if (!header) return header;
  if (Result<void> ok = RoleAssigner(*header, source, notes).run(); !ok) return std::move(ok).error();
  return header;
}

Result<DataRanges> check_data(const Header& header, std::string_view bytes, std::string_view source,
                              Notes* notes) {
  if (header.encoding == Encoding::Ascii)
    return walk(header, AsciiValues(bytes, header.data_offset, header.data_line, source), bytes, source,
                notes);
  return walk(header,
              BinaryValues(bytes, header.data_offset, header.encoding == Encoding::BinaryBigEndian, source),
              bytes, source, notes);
}

std::string openmesh_input(const Header& header, const DataRanges& data) {
  const bool ascii = header.encoding == Encoding::Ascii;
  std::string out = fmt::format("ply\nformat {} 1.0\n", ascii ? "ascii"
                                                        : header.encoding == Encoding::BinaryBigEndian
                                                            ? "binary_big_endian"
                                                            : "binary_little_endian");
  for (std::string_view name : {"vertex", "face"}) {
    const auto e = std::ranges::find(header.elements, name, &Element::name);
    if (e == header.elements.end()) continue;
    out += fmt::format("element {} {}\n", e->name, e->count);
    for (const Property& p : e->properties) {
      if (p.count_type) // OpenMesh knows "uint16" but not "ushort" as a list length type
        out += fmt::format("property list {} {} {}\n",
                           *p.count_type == Scalar::UInt16 ? "uint16" : name_of(*p.count_type),
                           name_of(p.type), p.name);
      else
        out += fmt::format("property {} {}\n", name_of(p.type), openmesh_name(p.name));
    }
  }
  out += "end_header\n";
  out.reserve(out.size() + data.vertices.size() + data.faces.size() + 2);
  // ASCII elements end in a newline: OpenMesh fails if the stream hits its end before the face element.
  out += data.vertices;
  if (ascii) out += '\n';
  out += data.faces;
  if (ascii) out += '\n';
  return out;
}

} // namespace pdeface::ply::detail
