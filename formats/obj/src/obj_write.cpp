#include "pdeface/obj/obj.hpp"

#include "pdeface/core/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

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

// "f a b c", "f a/a ...", "f a//a ..." or "f a/a/a ...": one index for every attribute, since our
// attributes are per vertex.
void write_faces(fmt::memory_buffer& out, const Mesh& mesh) {
  auto index = [&out](std::uint32_t v) { fmt::format_to(std::back_inserter(out), "{}", v + 1); };
  for (const Triangle& t : mesh.triangles) {
    out.push_back('f');
    for (std::uint32_t v : t) {
      out.push_back(' ');
      index(v);
      if (mesh.has_texcoords()) {
        out.push_back('/');
        index(v);
      }
      if (mesh.has_normals()) {
        out.append(std::string_view(mesh.has_texcoords() ? "/" : "//"));
        index(v);
      }
    }
    out.push_back('\n');
  }
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
  write_faces(out, mesh);
  return fmt::to_string(out);
}

} // namespace pdeface::obj
