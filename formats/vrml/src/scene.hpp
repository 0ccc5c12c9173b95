#pragma once
// The part of a VRML scene graph the reader keeps: grouping nodes with their matrices, shapes, the
// geometry nodes it reads and (VRML 1.0) the property nodes that change the traversal state. Every other
// node is parsed past and kept as `Skipped` so that `DEF`/`USE` still resolve to something of known type.
//
// Nodes are immutable once parsed and shared: `USE` points at the same node, and a node can only refer
// to nodes finished before it, so the graph has no cycles.

#include "lexer.hpp"

#include "pdeface/core/mesh.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <variant>
#include <vector>

namespace pdeface::vrml::detail {

struct Node;
using NodePtr = std::shared_ptr<const Node>;

//! An MFInt32 index field, and where its value starts so that entry k can be located for an error.
struct IndexList {
  std::vector<std::int32_t> values;
  Position at;
};

struct Coordinates {
  std::vector<Vec3> points;
};
struct Colors {
  std::vector<Vec3f> values;
};
struct Normals {
  std::vector<Vec3f> vectors;
};
struct TexCoords {
  std::vector<Vec2f> points;
};

//! VRML 1.0 `Separator` saves and restores the whole traversal state, `TransformSeparator` only the
//! matrix; VRML 1.0 `Group`/`Switch`/`LOD` and all VRML 2.0 groups save nothing (2.0 has no such state).
enum class Scope : std::uint8_t { None, Matrix, All };

//! Any grouping node: VRML 2.0 `Transform` (with its matrix), `Group`, `Anchor`, ... with the children
//! that are drawn (`Switch` and `LOD` keep only the chosen one); VRML 1.0 `Separator`, `Group`, ...
struct Group {
  std::optional<Eigen::Affine3d> matrix; // none: the identity (most groups), which costs nothing to apply
  std::vector<NodePtr> children;
  Scope scope = Scope::None;
};

struct Shape {
  NodePtr geometry;
  NodePtr appearance; // VRML 2.0: an Appearance, or none
};

//! VRML 2.0: a Shape's `Appearance`: its `Material` and `ImageTexture` (or none).
struct Appearance {
  NodePtr material, texture;
};
struct ImageTexture {
  std::string url; // the first of its urls, unescaped
};

struct FaceSet {
  NodePtr coord, color, normal, texcoord; // VRML 2.0; VRML 1.0 takes them from the traversal state
  IndexList coord_index, color_index, normal_index, texcoord_index;
  bool ccw = true;
  bool color_per_vertex = true;
  bool normal_per_vertex = true;
};

struct PointSet {
  NodePtr coord, color;        // VRML 2.0
  std::int32_t start = 0;      // VRML 1.0: startIndex
  std::int32_t count = -1;     // VRML 1.0: numPoints (-1: to the end)
  Position start_at, count_at; // where startIndex and numPoints were given, for errors
};

// VRML 1.0 property nodes, applied to the traversal state in document order.
struct MatrixNode { // Transform, Translation, Rotation, Scale, MatrixTransform
  Eigen::Affine3d matrix = Eigen::Affine3d::Identity();
};
enum class Binding : std::uint8_t {
  Default,
  Overall,
  PerPart,
  PerPartIndexed,
  PerFace,
  PerFaceIndexed,
  PerVertex,
  PerVertexIndexed
};
struct NormalBinding {
  Binding value = Binding::Default;
};
struct MaterialBinding {
  Binding value = Binding::Default;
};
struct Material {
  std::vector<Vec3f> diffuse; // VRML 2.0: one colour
  float transparency = 0.0F;  // VRML 2.0
};
struct ShapeHints {
  bool clockwise = false; // vertexOrdering CLOCKWISE
};

//! The fields of a `Transform` (both versions; VRML 1.0 calls scale `scaleFactor`).
struct TransformFields {
  Vec3 translation = Vec3::Zero();
  Eigen::AngleAxisd rotation{0.0, Vec3::UnitZ()};
  Vec3 scale = Vec3::Ones();
  Eigen::AngleAxisd scale_orientation{0.0, Vec3::UnitZ()};
  Vec3 center = Vec3::Zero();

  //! T·C·R·SR·S·−SR·−C, the composition both specifications give: scale along the scaleOrientation
  //! axes, rotate, both about the center, then translate.
  [[nodiscard]] Eigen::Affine3d matrix() const {
    return Eigen::Translation3d(translation + center) * rotation * scale_orientation * Eigen::Scaling(scale) *
           scale_orientation.inverse() * Eigen::Translation3d(-center);
  }
};

//! A node parsed past: only its type name is known.
struct Skipped {};

using NodeData =
    std::variant<Skipped, Group, Shape, FaceSet, PointSet, Coordinates, Colors, Normals, TexCoords,
                 MatrixNode, NormalBinding, MaterialBinding, Material, ShapeHints, Appearance, ImageTexture>;

struct Node {
  std::string_view type; // as written in the file
  Position at;           // of the type name
  NodeData data;
};

//! What the parser hands to the mesh builder.
struct Scene {
  std::vector<NodePtr> roots;
  Units units = Units::Unknown;
  std::string title;
};

} // namespace pdeface::vrml::detail
