#pragma once
//! \file
//! The mesh value type every module shares, and its point-cloud form.

#include "pdeface/core/result.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry> // cross products on Vec3 everywhere

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface {

using Vec2f = Eigen::Vector2f;
using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Vec4f = Eigen::Vector4f;
using Triangle = std::array<std::uint32_t, 3>;

//! Length units of a scan's coordinates. Most scanners write millimetres; VRML and glTF say metres.
enum class Units { Unknown, Millimetres, Centimetres, Metres, Inches };

[[nodiscard]] std::string_view to_string(Units units) noexcept;
//! The units a word names: "mm", "millimetres", "millimeters", "cm", ..., "m", "metres", "meters", "in",
//! "inch", "inches" (case-sensitive: the words our writers put in files); nullopt for anything else.
[[nodiscard]] std::optional<Units> units_from_string(std::string_view word) noexcept;
//! Millimetres per unit (1 for mm, 1000 for m); 0 for `Units::Unknown`.
[[nodiscard]] double millimetres_per(Units units) noexcept;

//! An axis-aligned box; empty when `min > max`.
struct Box {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  [[nodiscard]] bool empty() const { return (min.array() > max.array()).any(); }
  [[nodiscard]] Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
  [[nodiscard]] double diagonal() const { return size().norm(); }
};

//! An encoded image as a file holds it (JPEG or PNG bytes, never decoded by pdeface), and where it came from.
struct Image {
  std::string bytes;     //!< the encoded image; empty when the file it names could not be read
  std::string mime_type; //!< "image/jpeg" or "image/png" (empty with empty `bytes`)
  std::string uri;       //!< the path or URI the file gave it ("james.jpg"), or empty for an embedded image
};

//! What a face scan's surface looks like: a colour factor and, optionally, the photograph its texture
//! coordinates map into (glTF's `pbrMetallicRoughness` base colour, OBJ's `Kd` and `map_Kd`).
struct Material {
  std::string name;
  Vec4f base_color = Vec4f::Ones(); //!< linear RGBA in [0, 1], multiplied with the image
  std::optional<Image> base_color_image;
};

//! A triangle mesh as plain arrays (a "polygon soup" with shared vertices).
//!
//! `positions` is the only required attribute; each optional per-vertex attribute is either empty or has
//! exactly `positions.size()` entries. A mesh without triangles is a point cloud.
//!
//! Texture coordinates come in two forms. With `texcoord_triangles` empty, `texcoords` is per vertex like
//! the other attributes. With `texcoord_triangles` set (one entry per triangle), each triangle's corners
//! index `texcoords`, then a table of any size: a vertex on a texture seam keeps one position and its
//! corners give it different coordinates. The shape's connectivity is the same in both forms, so slicing
//! (which chains segments by shared vertices) and detection never see a seam; `with_vertex_texcoords`
//! splits the seam vertices for formats that need one coordinate per vertex (glTF, PLY).
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Vec3f> normals;   //!< per vertex, unit length (optional)
  std::vector<Vec4f> colors;    //!< per vertex, linear RGBA in [0, 1] (optional)
  std::vector<Vec2f> texcoords; //!< per vertex, or the table `texcoord_triangles` indexes (optional)
  //! Empty, or one per triangle: the `texcoords` of each corner of `triangles[i]`.
  std::vector<Triangle> texcoord_triangles;
  std::optional<Material> material; //!< one for the whole mesh (optional)
  Units units = Units::Unknown;
  std::string name;

  [[nodiscard]] std::size_t vertex_count() const noexcept { return positions.size(); }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return triangles.size(); }
  [[nodiscard]] bool is_point_cloud() const noexcept { return triangles.empty(); }
  [[nodiscard]] bool has_normals() const noexcept { return !normals.empty(); }
  [[nodiscard]] bool has_colors() const noexcept { return !colors.empty(); }
  [[nodiscard]] bool has_texcoords() const noexcept { return !texcoords.empty(); }
  //! Whether the texture coordinates are per corner (`texcoord_triangles`), not per vertex.
  [[nodiscard]] bool has_corner_texcoords() const noexcept { return !texcoord_triangles.empty(); }
};

//! The point-cloud form of a scan: positions only.
struct PointCloud {
  std::vector<Vec3> positions;
  Units units = Units::Unknown;
  std::string name;
};

//! The positions of a mesh as a point cloud (connectivity and attributes dropped).
[[nodiscard]] PointCloud to_point_cloud(const Mesh& mesh);
//! A mesh with no triangles holding the cloud's points.
[[nodiscard]] Mesh to_mesh(PointCloud cloud);

[[nodiscard]] Box bounding_box(std::span<const Vec3> points);
[[nodiscard]] inline Box bounding_box(const Mesh& mesh) { return bounding_box(mesh.positions); }

//! Area-weighted vertex normals; vertices on no triangle get (0, 0, 0).
[[nodiscard]] std::vector<Vec3f> vertex_normals(const Mesh& mesh);

//! Checks the invariants writers and algorithms rely on: attribute sizes match the vertex count (per-corner
//! texture coordinates: one index triangle per triangle), every index is in range, every coordinate is
//! finite. Returns the first violation, naming `source`.
[[nodiscard]] Result<void> validate(const Mesh& mesh, std::string_view source = {});

//! What every writer requires: `validate`, and at least one vertex. An empty mesh is written by no writer
//! and read from no file (each reader refuses a file without vertices: `Empty`), so that every file
//! written reads back. Errors: those of `validate`, `Empty` naming the mesh.
[[nodiscard]] Result<void> check_writable(const Mesh& mesh);

//! The texture coordinate of every corner, 3 per triangle in order (of either form); empty without
//! texture coordinates or triangles.
[[nodiscard]] std::vector<Vec2f> corner_texcoords(const Mesh& mesh);

//! A mesh whose texture coordinates are per vertex, for formats that store them so: each vertex whose
//! corners give it different coordinates is split into one copy per coordinate (same position, normal
//! and colour); the others keep their index, copies come after them. Per-vertex texture coordinates and
//! meshes without any are returned unchanged; vertices on no triangle get (0, 0). `split`, when given,
//! receives the number of vertices added. Taken by value: a mesh moved in is changed in place.
//! \pre validate(mesh)
[[nodiscard]] Mesh with_vertex_texcoords(Mesh mesh, std::size_t* split = nullptr);

//! The inverse, for what a format split: vertices with the same position, normal and colour (bit for bit)
//! merged into one, the texture coordinates becoming per corner. Meshes without texture coordinates and
//! meshes without such duplicates are returned unchanged. `merged`, when given, receives the number of
//! vertices removed. Taken by value: a mesh moved in and returned unchanged is not copied.
//! \pre validate(mesh)
[[nodiscard]] Mesh weld_texcoord_seams(Mesh mesh, std::size_t* merged = nullptr);

} // namespace pdeface
