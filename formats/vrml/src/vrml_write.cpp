// VRML 2.0 out: one Shape holding an IndexedFaceSet (or a PointSet), appended to one string.
//
// Numbers go through std::to_chars (general format, `precision` significant digits: the same text as
// printf's %.9g) rather than fmt: libstdc++'s Ryu-based to_chars measured 55 ns per value here against
// 100-135 ns for fmt's "{:.{}g}", and numbers are nearly all of the output. fmt formats the rest.

#include "pdeface/vrml/vrml.hpp"

#include "pdeface/core/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace pdeface::vrml {
namespace {

// Attributes are floats: 9 significant digits already give them back exactly.
constexpr int kFloatDigits = 9;

//! The output, appended to a line at a time: each line is built in a small array first, because a
//! string append per number (seven per vertex) measured slower than the number formatting itself.
class Text {
public:
  explicit Text(std::size_t capacity) { out_.reserve(capacity); }

  Text& operator<<(std::string_view s) {
    out_.append(s);
    return *this;
  }
  template <class... Args> void format(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(out_), f, std::forward<Args>(args)...);
  }
  //! One line: `indent`, the values separated by spaces, then `end`.
  template <class T>
  void line(std::string_view indent, const T* values, int count, int digits, std::string_view end) {
    std::array<char, 256> buf{}; // 4 values of at most 24 characters ("-1.2345678901234567e-308"), 3 spaces
    char* p = std::copy(indent.begin(), indent.end(), buf.data());
    char* const last = buf.data() + buf.size() - end.size();
    for (int i = 0; i < count; ++i) {
      if (i > 0) *p++ = ' ';
      if constexpr (std::is_integral_v<T>)
        p = std::to_chars(p, last, values[i]).ptr;
      else
        p = std::to_chars(p, last, values[i], std::chars_format::general, digits).ptr;
    }
    p = std::copy(end.begin(), end.end(), p);
    out_.append(buf.data(), p);
  }
  [[nodiscard]] std::string take() { return std::move(out_); }

private:
  std::string out_;
};

std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

//! `field Node { list [ ... ] }` at the indentation of the geometry's fields, one value per line.
template <class Vector>
void write_node(Text& out, std::string_view field, std::string_view node, std::string_view list,
                const std::vector<Vector>& values, int components, int digits) {
  out.format("    {} {} {{\n      {} [\n", field, node, list);
  for (const Vector& v : values)
    out.line("        ", v.data(), components, digits, ",\n");
  out << "      ]\n    }\n";
}

void write_world_info(Text& out, const Mesh& mesh) {
  const std::string name = clean_name(mesh.name); // VRML 2.0 text is UTF-8
  if (name.empty() && mesh.units == Units::Unknown) return;
  out << "WorldInfo {\n";
  if (!name.empty()) out.format("  title {}\n", quoted(name));
  // Our reader takes the units back from this entry; VRML itself has no units field.
  if (mesh.units != Units::Unknown) out.format("  info [ \"units: {}\" ]\n", to_string(mesh.units));
  out << "}\n";
}

void write_triangles(Text& out, std::string_view field, const std::vector<Triangle>& triangles) {
  out.format("    {} [\n", field);
  for (const Triangle& t : triangles)
    out.line("      ", t.data(), 3, 0, " -1,\n");
  out << "    ]\n";
}

// The material as an Appearance: its colour (VRML's diffuseColor, which an RGB texture replaces) and its
// image by name (`texture_url`, a file written beside).
void write_appearance(Text& out, const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (!mesh.material) return;
  const Material& m = *mesh.material;
  out << "  appearance Appearance {\n    material Material {\n";
  out.line("      diffuseColor ", m.base_color.data(), 3, kFloatDigits, "\n");
  if (m.base_color[3] < 1.0F) out.format("      transparency {}\n", 1.0F - m.base_color[3]);
  out << "    }\n";
  if (!options.texture_url.empty() && mesh.has_texcoords())
    out.format("    texture ImageTexture {{ url {} }}\n", quoted(clean_name(options.texture_url)));
  else if (m.base_color_image && notes)
    notes->push_back(options.texture_url.empty()
                         ? "texture image dropped: no file to write it in (written by file only)"
                         : "texture image dropped: the mesh has no texture coordinates");
  out << "  }\n";
}

void note(Notes* notes, std::string text) {
  if (notes) notes->push_back(std::move(text));
}

} // namespace

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (options.precision < 1 || options.precision > std::numeric_limits<double>::max_digits10)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("precision must be 1 to 17 significant digits, not {}", options.precision));
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  if (mesh.positions.empty())
    return make_error(ErrorCode::Empty, "nothing to write: the mesh has no vertices");
  if (mesh.positions.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    return make_error(
        ErrorCode::CountTooLarge,
        fmt::format("{} vertices: VRML indices are 32-bit signed integers", mesh.positions.size()));

  const bool points = mesh.is_point_cloud();
  // About 32 bytes per coordinate triple and 26 per triangle: one allocation for most meshes.
  Text out(32 * mesh.positions.size() * (1 + mesh.has_normals() + mesh.has_colors()) +
           26 * mesh.triangles.size());
  out << "#VRML V2.0 utf8\n# written by pdeface\n";
  write_world_info(out, mesh);
  out << "Shape {\n";
  write_appearance(out, mesh, options, notes);
  out.format("  geometry {} {{\n", points ? "PointSet" : "IndexedFaceSet");
  if (!points) out << "    solid FALSE\n";
  write_node(out, "coord", "Coordinate", "point", mesh.positions, 3, options.precision);

  const int digits = std::min(options.precision, kFloatDigits);
  if (mesh.has_normals() && points)
    note(notes, "normals dropped: a VRML PointSet cannot hold them");
  else if (mesh.has_normals())
    write_node(out, "normal", "Normal", "vector", mesh.normals, 3, digits);
  if (mesh.has_colors()) {
    if (std::any_of(mesh.colors.begin(), mesh.colors.end(), [](const Vec4f& c) { return c.w() != 1.0F; }))
      note(notes, "colour alpha dropped: VRML colours are RGB");
    write_node(out, "color", "Color", "color", mesh.colors, 3, digits);
  }
  if (mesh.has_texcoords() && points)
    note(notes, "texture coordinates dropped: a VRML PointSet cannot hold them");
  else if (mesh.has_texcoords())
    write_node(out, "texCoord", "TextureCoordinate", "point", mesh.texcoords, 2, digits);
  if (!points) write_triangles(out, "coordIndex", mesh.triangles);
  if (!points && mesh.has_corner_texcoords()) write_triangles(out, "texCoordIndex", mesh.texcoord_triangles);
  out << "  }\n}\n";
  return out.take();
}

} // namespace pdeface::vrml
