#include "pdeface/ply/ply.hpp"

#include "pdeface/openmesh_io/openmesh_io.hpp"
#include "ply_layout.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pdeface::ply {

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes) {
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
    return std::move(direct->mesh);
  }
  Result<detail::DataRanges> data = detail::check_data(*header, bytes, source, notes);
  if (!data) return std::move(data).error();
  Result<Mesh> mesh =
      openmesh_io::read_openmesh(detail::openmesh_input(*header, *data), {.extension = "ply"}, source, notes);
  if (mesh) mesh->units = header->units;
  return mesh;
}

Result<std::string> write(const Mesh& mesh, const WriteOptions& options, Notes* notes) {
  if (Result<void> valid = check_writable(mesh); !valid) return std::move(valid).error();
  const bool alpha = std::ranges::any_of(mesh.colors, [](const Vec4f& c) { return c[3] < 1.0f; });
  Result<std::string> bytes = openmesh_io::write_openmesh(mesh,
                                                          {.extension = "ply",
                                                           .binary = options.binary,
                                                           .normals = mesh.has_normals(),
                                                           .colors = mesh.has_colors(),
                                                           .alpha = alpha,
                                                           .texcoords = mesh.has_texcoords()},
                                                          "PLY", notes);
  if (!bytes || mesh.units == Units::Unknown) return bytes;
  // OpenMesh writes no comments: state the units after the format line, where our reader looks for them.
  const std::size_t format_end = bytes->find('\n', bytes->find("\nformat ") + 1);
  bytes->insert(format_end + 1, fmt::format("comment units {}\n", to_string(mesh.units)));
  return bytes;
}

} // namespace pdeface::ply
