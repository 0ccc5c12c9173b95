// Binary PLY written in pieces (ply/binary.hpp): the bytes `ply::write` gives the same mesh, and those
// OpenMesh's writer gives it (which `ply::write` used for every layout before it wrote these by itself).

#include "pdeface/core/sample_face.hpp"
#include "pdeface/openmesh_io/openmesh_io.hpp"
#include "pdeface/ply/binary.hpp"
#include "pdeface/ply/ply.hpp"

#include <gtest/gtest.h>

namespace pdeface {
namespace {

// What OpenMesh's PLY writer makes of `mesh` (the reference `ply::write`'s own records must match), with
// the units comment `ply::write` adds after the format line.
std::string openmesh_bytes(const Mesh& mesh) {
  std::string bytes =
      openmesh_io::write_openmesh(mesh, {.extension = "ply", .binary = true, .normals = mesh.has_normals()},
                                  "PLY", nullptr)
          .value();
  if (mesh.units != Units::Unknown)
    bytes.insert(bytes.find('\n', bytes.find("\nformat ") + 1) + 1,
                 "comment units " + std::string(to_string(mesh.units)) + "\n");
  return bytes;
}

TEST(PlyBinary, WriteIsOpenMeshsBytesForEveryLayout) {
  Mesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0.25, 0), Vec3(0, 1, 1e-7)};
  for (const bool cloud : {false, true})
    for (const Units units : {Units::Unknown, Units::Metres})
      for (const bool normals : {false, true}) {
        mesh.triangles = cloud ? std::vector<Triangle>{} : std::vector<Triangle>{Triangle{0, 1, 2}};
        mesh.units = units;
        mesh.normals = normals ? std::vector<Vec3f>(3, Vec3f(0, 0, 1)) : std::vector<Vec3f>{};
        const std::string written = ply::write(mesh).value(), expected = openmesh_bytes(mesh);
        EXPECT_EQ(written.size(), expected.size()) << cloud << normals << " " << to_string(units);
        EXPECT_TRUE(written == expected) << cloud << normals << " " << to_string(units);
      }
  Mesh face = sample_face();
  face.colors.clear();
  EXPECT_TRUE(ply::write(face).value() == openmesh_bytes(face));
}

TEST(PlyBinary, PiecesAreTheWritersBytesForEveryLayout) {
  Mesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0.25, 0), Vec3(0, 1, 1e-7)};
  mesh.triangles = {Triangle{0, 1, 2}};
  for (const Units units : {Units::Unknown, Units::Metres})
    for (const bool normals : {false, true}) {
      mesh.units = units;
      mesh.normals = normals ? std::vector<Vec3f>(3, Vec3f(0, 0, 1)) : std::vector<Vec3f>{};
      const ply::BinaryLayout layout{3, 1, normals, units};
      std::string bytes = ply::binary_header(layout);
      const std::size_t header = bytes.size();
      bytes.resize(ply::binary_size(layout));
      const std::span<char> body = std::span(bytes).subspan(header);
      ply::put_binary_vertices(body, mesh.positions, mesh.normals);
      ply::put_binary_triangles(body.subspan(ply::binary_vertex_bytes(3, normals)), mesh.triangles);
      EXPECT_TRUE(bytes == ply::write(mesh).value()) << normals << " " << to_string(units);
    }
  // A real mesh: the sample face without its colours.
  Mesh face = sample_face();
  face.colors.clear();
  const ply::BinaryLayout layout{face.vertex_count(), face.triangle_count(), true, face.units};
  std::string whole = ply::binary_header(layout);
  const std::size_t header = whole.size(), half = face.vertex_count() / 2;
  whole.resize(ply::binary_size(layout));
  std::span<char> body = std::span(whole).subspan(header);
  ply::put_binary_vertices(body, std::span(face.positions).first(half), std::span(face.normals).first(half));
  body = body.subspan(ply::binary_vertex_bytes(half, true));
  ply::put_binary_vertices(body, std::span(face.positions).subspan(half),
                           std::span(face.normals).subspan(half));
  body = body.subspan(ply::binary_vertex_bytes(face.vertex_count() - half, true));
  ply::put_binary_triangles(body, face.triangles);
  EXPECT_TRUE(whole == ply::write(face).value());

  std::string bytes(100, '\0');
  EXPECT_THROW(ply::put_binary_vertices(bytes, mesh.positions, std::vector<Vec3f>(2)), std::invalid_argument);
  EXPECT_THROW(ply::put_binary_vertices(std::span(bytes).first(35), mesh.positions, {}),
               std::invalid_argument);
  EXPECT_THROW(ply::put_binary_triangles(std::span(bytes).first(12), mesh.triangles), std::invalid_argument);
}

} // namespace
} // namespace pdeface
