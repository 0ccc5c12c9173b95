#pragma once
// The VRML 2.0 / VRML97 parser: Transform (with center and scaleOrientation), the grouping nodes, Shape,
// IndexedFaceSet, PointSet and their attribute nodes, WorldInfo (for units); PROTO, EXTERNPROTO and ROUTE
// statements are parsed past, and so is every other node.

#include "parser.hpp"

namespace pdeface::vrml::detail {

class ParserV2 final : public Parser {
public:
  using Parser::Parser;

private:
  NodeData parse_body(const Token& type) override;
  bool other_statement(const Token& word) override;

  NodeData transform();
  NodeData group();
  NodeData switch_node();
  NodeData lod(const Token& type);
  NodeData shape();
  NodeData appearance();
  NodeData material();
  NodeData image_texture();
  NodeData face_set();
  NodeData point_set();
  NodeData world_info();
  NodeData inline_node(const Token& type);
};

} // namespace pdeface::vrml::detail
