#pragma once
// The VRML 1.0 parser: Separator and the other grouping nodes with their children in document order,
// the property nodes that change the traversal state (Coordinate3, the transforms, Normal, NormalBinding,
// TextureCoordinate2, Material, MaterialBinding, ShapeHints), IndexedFaceSet, PointSet, and Info (for
// units). Every other node is parsed past.

#include "parser.hpp"

namespace pdeface::vrml::detail {

class ParserV1 final : public Parser {
public:
  using Parser::Parser;

private:
  NodeData parse_body(const Token& type) override;

  NodeData group(std::string_view type);
  NodeData transform();
  NodeData matrix_transform();
  template <class Field> NodeData single_field(std::string_view name, Field read);
  NodeData face_set();
  NodeData point_set();
  Binding read_binding(std::string_view field);
  NodeData shape_hints();
  NodeData info();
};

} // namespace pdeface::vrml::detail
