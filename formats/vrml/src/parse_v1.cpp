// VRML 1.0 (the 1995 specification, after Open Inventor's ASCII format).

#include "parse_v1.hpp"

#include <array>

namespace pdeface::vrml::detail {
namespace {

//! A VRML 1.0 index field whose value is just -1 (the default) means "use coordIndex".
IndexList with_default(IndexList list) {
  if (list.values.size() == 1 && list.values.front() == -1) list.values.clear();
  return list;
}

} // namespace

NodeData ParserV1::parse_body(const Token& type) {
  const std::string_view t = type.text;
  if (t == "Separator" || t == "TransformSeparator" || t == "Group" || t == "Switch" || t == "LOD" ||
      t == "WWWAnchor")
    return group(t);
  if (t == "Coordinate3") return list_node<Coordinates>("point", &Coordinates::points);
  if (t == "IndexedFaceSet") return face_set();
  if (t == "PointSet") return point_set();
  if (t == "Transform") return transform();
  if (t == "Translation")
    return single_field("translation",
                        [&] { return Eigen::Affine3d(Eigen::Translation3d(read_vec3("translation"))); });
  if (t == "Rotation")
    return single_field("rotation", [&] { return Eigen::Affine3d(read_rotation("rotation")); });
  if (t == "Scale")
    return single_field("scaleFactor",
                        [&] { return Eigen::Affine3d(Eigen::Scaling(read_vec3("scaleFactor"))); });
  if (t == "MatrixTransform") return matrix_transform();
  if (t == "Normal") return list_node<Normals>("vector", &Normals::vectors);
  if (t == "TextureCoordinate2") return list_node<TexCoords>("point", &TexCoords::points);
  if (t == "Material") return list_node<Material>("diffuseColor", &Material::diffuse);
  if (t == "NormalBinding" || t == "MaterialBinding") {
    Binding value = Binding::Default;
    only_field("value", [&] { value = read_binding("value"); });
    if (t == "NormalBinding") return NormalBinding{value};
    return MaterialBinding{value};
  }
  if (t == "ShapeHints") return shape_hints();
  if (t == "Info") return info();
  if (t == "WWWInline")
    context_.note(type.at, "WWWInline not followed (the reader does not fetch other files)");
  skip_body();
  return Skipped{};
}

NodeData ParserV1::group(std::string_view type) {
  Group g;
  g.scope = type == "Separator" ? Scope::All : type == "TransformSeparator" ? Scope::Matrix : Scope::None;
  std::int32_t which_child = -1;
  fields([&](const Token& name) {
    if (starts_node(name)) {
      if (NodePtr child = node_statement(name)) g.children.push_back(std::move(child));
    } else if (type == "Switch" && name.text == "whichChild") {
      which_child = read_int32(name.text);
    } else {
      return false;
    }
    return true;
  });
  if (type == "Switch") {
    constexpr std::int32_t kAll = -3; // SO_SWITCH_ALL
    if (which_child >= 0 && static_cast<std::size_t>(which_child) < g.children.size())
      g.children = {g.children[which_child]};
    else if (which_child != kAll)
      g.children.clear();
  } else if (type == "LOD" && g.children.size() > 1) {
    g.children.resize(1); // the first child is the most detailed level
  }
  return g;
}

NodeData ParserV1::transform() {
  TransformFields f;
  fields([&](const Token& name) { return transform_field(name.text, "scaleFactor", f); });
  return MatrixNode{f.matrix()};
}

template <class Field> NodeData ParserV1::single_field(std::string_view name, Field read) {
  MatrixNode m;
  only_field(name, [&] { m.matrix = read(); });
  return m;
}

NodeData ParserV1::matrix_transform() {
  MatrixNode m;
  only_field("matrix", [&] {
    // Inventor's matrices act on row vectors (p' = p·M): the file's rows are our columns, and its last
    // row is the translation. A projective last column cannot be an affine transform.
    const Position at = peek().at;
    Eigen::Matrix4d rows;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        rows(r, c) = read_double("matrix");
    if (rows.col(3) != Eigen::Vector4d(0, 0, 0, 1))
      context_.note(at, "MatrixTransform: the projective part of the matrix is ignored");
    m.matrix.linear() = rows.topLeftCorner<3, 3>().transpose();
    m.matrix.translation() = rows.row(3).head<3>().transpose();
  });
  return m;
}

NodeData ParserV1::face_set() {
  FaceSet f;
  fields([&](const Token& name) {
    const std::string_view n = name.text;
    if (n == "coordIndex")
      f.coord_index = read_index_list(n);
    else if (n == "materialIndex")
      f.color_index = with_default(read_index_list(n));
    else if (n == "normalIndex")
      f.normal_index = with_default(read_index_list(n));
    else if (n == "textureCoordIndex")
      f.texcoord_index = with_default(read_index_list(n));
    else
      return false;
    return true;
  });
  return f;
}

NodeData ParserV1::point_set() {
  PointSet p;
  fields([&](const Token& name) {
    if (name.text == "startIndex") {
      p.start_at = peek().at;
      p.start = read_int32(name.text);
    } else if (name.text == "numPoints") {
      p.count_at = peek().at;
      p.count = read_int32(name.text);
    } else {
      return false;
    }
    return true;
  });
  return p;
}

Binding ParserV1::read_binding(std::string_view field) {
  static constexpr std::array<std::pair<std::string_view, Binding>, 8> names{{
      {"DEFAULT", Binding::Default},
      {"OVERALL", Binding::Overall},
      {"PER_PART", Binding::PerPart},
      {"PER_PART_INDEXED", Binding::PerPartIndexed},
      {"PER_FACE", Binding::PerFace},
      {"PER_FACE_INDEXED", Binding::PerFaceIndexed},
      {"PER_VERTEX", Binding::PerVertex},
      {"PER_VERTEX_INDEXED", Binding::PerVertexIndexed},
  }};
  const Token t = next_required("a binding");
  for (const auto& [word, binding] : names)
    if (t.kind == TokenKind::Word && t.text == word) return binding;
  fail_expected(fmt::format("a binding for {} (OVERALL, PER_FACE, PER_VERTEX_INDEXED, ...)", field), t);
}

NodeData ParserV1::shape_hints() {
  ShapeHints hints;
  only_field("vertexOrdering", [&] { hints.clockwise = read_word("vertexOrdering") == "CLOCKWISE"; });
  return hints;
}

NodeData ParserV1::info() {
  only_field("string", [&] { take_info(read_strings("string")); });
  return Skipped{};
}

} // namespace pdeface::vrml::detail
