#include "pdeface/ply/ply.hpp"

#include "pdeface/openmesh_io/openmesh_io.hpp"
#include "pdeface/ply/binary.hpp"
#include "ply_layout.hpp"

#include <fmt/format.h>

#include "pdeface/core/text.hpp"

#include <algorithm>

namespace pdeface::ply {

namespace {

// The image a `comment TextureFile` names, as the material of a mesh with texture coordinates.
Result<Mesh> with_texture(Result<Mesh> mesh, const detail::Header& header, std::string_view source,
                          Notes* notes, const Resolver& resolve) {
  if (!mesh || header.texture_file.empty()) return mesh;
  if (!mesh->has_texcoords()) {
    if (notes)
      notes->push_back(fmt::format("{}: TextureFile '{}' ignored: the vertices have no texture coordinates",
                                   source, excerpt(header.texture_file)));
    return mesh;
  }
  Result<Image> image = resolve_image(resolve, header.texture_file, source, notes);
  if (!image) return std::move(image).error();
  mesh->material =
      Material{.name = {}, .base_color = Vec4f::Ones(), .base_color_image = std::move(image).value()};
  return mesh;
}

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes, const Resolver& resolve) {
  Result<detail::Header> header = detail::parse_header(bytes, source, notes);
  if (!header) return std::move(header).error();
  if (std::optional<detail::DirectRead> direct = detail::read_direct(*header, bytes)) {
    if (notes && header->encoding != detail::Encoding::Ascii && direct->data_end < bytes.size())
      notes->push_back(fmt::format("{}: {} bytes after the last element ignored (from byte {})", source,
                                   bytes.size() - direct->data_end, direct->data_end));
    if (notes && direct->trailing_line)
      notes->push_back(
          fmt::format("{}:{}: data after the last element ignored", source, *direct->trailing_line));
    if (notes && direct->short_faces != 0)
      notes->push_back(
          fmt::format("{}: {} faces with fewer than 3 corners skipped", source, direct->short_faces));
    if (direct->mesh.positions.empty())
      return make_error(ErrorCode::Empty, "no vertices in the file", std::string(source));
    direct->mesh.units = header->units;
    return with_texture(std::move(direct->mesh), *header, source, notes, resolve);
  }
  Result<detail::DataRanges> data = detail::check_data(*header, bytes, source, notes);
  if (!data) return std::move(data).error();
  Result<Mesh> mesh =
      openmesh_io::read_openmesh(detail::openmesh_input(*header, *data), {.extension = "ply"}, source, notes);
  if (mesh) mesh->units = header->units;
  return with_texture(std::move(mesh), *header, source, notes, resolve);
}

Result<std::string> write(const Mesh& input, const WriteOptions& options, Notes* notes) {
  if (Result<void> valid = check_writable(input); !valid) return std::move(valid).error();
  // One texture coordinate per vertex (s t): seam vertices written once per coordinate.
  std::size_t split = 0;
  const Mesh split_mesh = input.has_corner_texcoords() ? with_vertex_texcoords(input, &split) : Mesh();
  const Mesh& mesh = input.has_corner_texcoords() ? split_mesh : input;
  if (split > 0 && notes)
    notes->push_back(
        fmt::format("{} vertices on texture seams written once per texture coordinate: PLY's s t "
                    "are per vertex",
                    split));
  const bool names_texture = !options.texture_file.empty() && mesh.has_texcoords();
  if (!names_texture && mesh.material && mesh.material->base_color_image && notes)
    notes->push_back("texture image dropped: PLY names one only beside texture coordinates, written by file");
  if (options.binary && !mesh.has_colors() && !mesh.has_texcoords()) {
    // The usual layout (positions, perhaps normals, triangles) as plain records (ply/binary.hpp): OpenMesh's
    // bytes (tests/formats/ply/binary_test.cpp), without its stream of one value at a time (a 150k-vertex
    // mesh: 52 of the 130 ms `pdeface decode` took).
    const BinaryLayout layout{mesh.vertex_count(), mesh.triangle_count(), mesh.has_normals(), mesh.units};
    std::string bytes = binary_header(layout);
    const std::size_t header = bytes.size();
    bytes.resize(binary_size(layout));
    const std::span<char> body = std::span(bytes).subspan(header);
    put_binary_vertices(body, mesh.positions, mesh.normals);
    put_binary_triangles(body.subspan(binary_vertex_bytes(layout.vertices, layout.normals)), mesh.triangles);
    return bytes;
  }
  const bool alpha = std::ranges::any_of(mesh.colors, [](const Vec4f& c) { return c[3] < 1.0f; });
  Result<std::string> bytes = openmesh_io::write_openmesh(mesh,
                                                          {.extension = "ply",
                                                           .binary = options.binary,
                                                           .normals = mesh.has_normals(),
                                                           .colors = mesh.has_colors(),
                                                           .alpha = alpha,
                                                           .texcoords = mesh.has_texcoords()},
                                                          "PLY", notes);
  if (!bytes) return bytes;
  // OpenMesh writes no comments: state the units and the texture after the format line, where our reader
  // looks for them.
  std::string comments;
  if (mesh.units != Units::Unknown) comments += fmt::format("comment units {}\n", to_string(mesh.units));
  if (names_texture) comments += fmt::format("comment TextureFile {}\n", clean_name(options.texture_file));
  const std::size_t format_end = bytes->find('\n', bytes->find("\nformat ") + 1);
  bytes->insert(format_end + 1, comments);
  return bytes;
}

} // namespace pdeface::ply
