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

//! A triangle mesh as plain arrays (a "polygon soup" with shared vertices).
//!
//! `positions` is the only required attribute; each optional per-vertex attribute is either empty or has
//! exactly `positions.size()` entries. A mesh without triangles is a point cloud.
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Vec3f> normals;   //!< per vertex, unit length (optional)
  std::vector<Vec4f> colors;    //!< per vertex, linear RGBA in [0, 1] (optional)
  std::vector<Vec2f> texcoords; //!< per vertex (optional)
  Units units = Units::Unknown;
  std::string name;

  [[nodiscard]] std::size_t vertex_count() const noexcept { return positions.size(); }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return triangles.size(); }
  [[nodiscard]] bool is_point_cloud() const noexcept { return triangles.empty(); }
  [[nodiscard]] bool has_normals() const noexcept { return !normals.empty(); }
  [[nodiscard]] bool has_colors() const noexcept { return !colors.empty(); }
  [[nodiscard]] bool has_texcoords() const noexcept { return !texcoords.empty(); }
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

//! Checks the invariants writers and algorithms rely on: attribute sizes match the vertex count, every
//! index is in range, every coordinate is finite. Returns the first violation, naming `source`.
[[nodiscard]] Result<void> validate(const Mesh& mesh, std::string_view source = {});

//! What every writer requires: `validate`, and at least one vertex. An empty mesh is written by no writer
//! and read from no file (each reader refuses a file without vertices: `Empty`), so that every file
//! written reads back. Errors: those of `validate`, `Empty` naming the mesh.
[[nodiscard]] Result<void> check_writable(const Mesh& mesh);

} // namespace pdeface
