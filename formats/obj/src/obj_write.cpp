#include "pdeface/obj/obj.hpp"

#include "pdeface/core/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <stdexcept>

namespace pdeface::obj {
namespace {

constexpr int kFloatDigits = 9; // enough to round-trip any float

// Writes numbers as float32, the precision OBJ readers (tinyobjloader included) keep: with 9 or more digits
// the shortest text that reads back as the same float, else `precision` significant digits.
class NumberWriter {
public:
  NumberWriter(fmt::memory_buffer& out, int precision) : out_(out), precision_(precision) {}

  void operator()(double value) {
    const auto f = static_cast<float>(value);
    if (precision_ >= kFloatDigits)
      fmt::format_to(std::back_inserter(out_), " {}", f);
    else
      fmt::format_to(std::back_inserter(out_), " {:.{}g}", f, precision_);
  }

private:
  fmt::memory_buffer& out_;
  int precision_;
};

// "f a b c", "f a/a ...", "f a//a ..." or "f a/b/a ...": the vertex's index for every per-vertex
// attribute, the corner's own for per-corner texture coordinates.
void write_faces(fmt::memory_buffer& out, const Mesh& mesh) {
  auto index = [&out](std::uint32_t v) { fmt::format_to(std::back_inserter(out), "{}", v + 1); };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    out.push_back('f');
    for (std::size_t k = 0; k < 3; ++k) {
      out.push_back(' ');
      index(t[k]);
      if (mesh.has_texcoords()) {
        out.push_back('/');
        index(mesh.has_corner_texcoords() ? mesh.texcoord_triangles[f][k] : t[k]);
      }
      if (mesh.has_normals()) {
        out.append(std::string_view(mesh.has_texcoords() ? "/" : "//"));
        index(t[k]);
      }
    }
    out.push_back('\n');
  }
}

// A name as one token of a line: blanks and '#' (a comment) become '_'.
std::string token(std::string_view name) {
  std::string out = clean_name(name);
  std::ranges::replace_if(
      out, [](char c) { return c == '#' || std::isspace(static_cast<unsigned char>(c)) != 0; }, '_');
  return out;
}

} // namespace

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (options.precision < 1 || options.precision > 17)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("OBJ precision {} is outside 1..17 significant digits", options.precision));
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  if (notes && std::ranges::any_of(mesh.colors, [](const Vec4f& c) { return c[3] < 1.0f; }))
    notes->push_back("vertex colour alpha dropped: OBJ stores r g b only");

  fmt::memory_buffer out;
  NumberWriter number(out, options.precision);
  out.append(std::string_view("# written by pdeface\n"));
  if (mesh.units != Units::Unknown)
    fmt::format_to(std::back_inserter(out), "# units {}\n", to_string(mesh.units));
  // One line, without the '#' that would start a comment; UTF-8.
  std::string name = clean_name(mesh.name);
  std::ranges::replace(name, '#', ' ');
  if (!name.empty()) fmt::format_to(std::back_inserter(out), "o {}\n", name);
  const bool material = mesh.material && !options.material_library.empty();
  if (mesh.material && !material && notes)
    notes->push_back("material dropped: no material library to write it in (written by file only)");
  if (material) fmt::format_to(std::back_inserter(out), "mtllib {}\n", clean_name(options.material_library));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    out.push_back('v');
    for (double c : mesh.positions[i])
      number(c);
    if (mesh.has_colors())
      for (int k = 0; k < 3; ++k)
        number(mesh.colors[i][k]);
    out.push_back('\n');
  }
  for (const Vec3f& n : mesh.normals) {
    out.append(std::string_view("vn"));
    for (float c : n)
      number(c);
    out.push_back('\n');
  }
  for (const Vec2f& t : mesh.texcoords) {
    out.append(std::string_view("vt"));
    for (float c : t)
      number(c);
    out.push_back('\n');
  }
  if (material) fmt::format_to(std::back_inserter(out), "usemtl {}\n", material_name(*mesh.material));
  write_faces(out, mesh);
  return fmt::to_string(out);
}

std::string material_name(const Material& material) {
  std::string name = token(material.name);
  return name.empty() ? "material_0" : name;
}

std::string write_material_library(const Mesh& mesh, std::string_view image) {
  if (!mesh.material) throw std::invalid_argument("obj::write_material_library: the mesh has no material");
  const Material& m = *mesh.material;
  std::string out = "# written by pdeface\n";
  fmt::format_to(std::back_inserter(out), "newmtl {}\nKd {} {} {}\nd {}\nillum 1\n", material_name(m),
                 m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]);
  if (!image.empty()) fmt::format_to(std::back_inserter(out), "map_Kd {}\n", clean_name(image));
  return out;
}

} // namespace pdeface::obj
