// VRML 2.0 / VRML97 (ISO/IEC 14772-1): the nodes the reader keeps, and the statements it parses past.

#include "parse_v2.hpp"
#include "pdeface/core/text.hpp"

#include <algorithm>

namespace pdeface::vrml::detail {

NodeData ParserV2::parse_body(const Token& type) {
  const std::string_view t = type.text;
  if (t == "Transform") return transform();
  if (t == "Group" || t == "Anchor" || t == "Billboard" || t == "Collision") return group();
  if (t == "Switch") return switch_node();
  if (t == "LOD") return lod(type);
  if (t == "Shape") return shape();
  if (t == "Appearance") return appearance();
  if (t == "Material") return material();
  if (t == "ImageTexture") return image_texture();
  if (t == "IndexedFaceSet") return face_set();
  if (t == "PointSet") return point_set();
  if (t == "Coordinate") return list_node<Coordinates>("point", &Coordinates::points);
  if (t == "Color") return list_node<Colors>("color", &Colors::values);
  if (t == "Normal") return list_node<Normals>("vector", &Normals::vectors);
  if (t == "TextureCoordinate") return list_node<TexCoords>("point", &TexCoords::points);
  if (t == "WorldInfo") return world_info();
  if (t == "Inline") return inline_node(type);
  if (protos_.contains(t))
    context_.note(type.at, fmt::format("instance of PROTO {} skipped (PROTOs are not expanded)", excerpt(t)));
  skip_body();
  return Skipped{};
}

bool ParserV2::other_statement(const Token& word) {
  if (word.kind != TokenKind::Word) return false;
  if (word.text == "PROTO" || word.text == "EXTERNPROTO") {
    const bool external = word.text == "EXTERNPROTO";
    const Token name = next_required("a PROTO name");
    if (name.kind != TokenKind::Word) fail_expected("a PROTO name", name);
    const Token interface = next_required("'['");
    if (interface.kind != TokenKind::OpenBracket) fail_expected("'[' opening the PROTO interface", interface);
    skip_balanced();
    if (external) {
      (void)read_strings("EXTERNPROTO url");
    } else {
      const Token body = next_required("'{'");
      if (body.kind != TokenKind::OpenBrace) fail_expected("'{' opening the PROTO body", body);
      skip_balanced(); // names inside a PROTO body are its own: nothing there is DEF'd for the file
    }
    protos_.insert(name.text);
    return true;
  }
  if (word.text == "ROUTE") {
    const Token from = next_required("an event name after ROUTE");
    if (from.kind != TokenKind::Word) fail_expected("node.eventOut after ROUTE", from);
    const Token to = next_required("TO");
    if (to.kind != TokenKind::Word || to.text != "TO") fail_expected("TO", to);
    const Token target = next_required("an event name after TO");
    if (target.kind != TokenKind::Word) fail_expected("node.eventIn after TO", target);
    return true;
  }
  return false;
}

NodeData ParserV2::transform() {
  TransformFields f;
  Group g;
  fields([&](const Token& name) {
    if (name.text != "children") return transform_field(name.text, "scale", f);
    g.children = read_mfnode();
    return true;
  });
  if (const Eigen::Affine3d m = f.matrix(); !m.matrix().isIdentity(0.0)) g.matrix = m;
  return g;
}

NodeData ParserV2::group() {
  Group g;
  only_field("children", [&] { g.children = read_mfnode(); });
  return g;
}

NodeData ParserV2::switch_node() {
  std::vector<NodePtr> choice;
  std::int32_t which = -1;
  fields([&](const Token& name) {
    if (name.text == "choice")
      choice = read_mfnode();
    else if (name.text == "whichChoice")
      which = read_int32(name.text);
    else
      return false;
    return true;
  });
  Group g;
  if (which >= 0 && static_cast<std::size_t>(which) < choice.size()) g.children.push_back(choice[which]);
  return g;
}

NodeData ParserV2::lod(const Token& type) {
  std::vector<NodePtr> levels;
  only_field("level", [&] { levels = read_mfnode(); });
  Group g;
  if (!levels.empty()) g.children.push_back(levels.front());
  if (levels.size() > 1)
    context_.note(type.at, fmt::format("LOD: the first (finest) of its {} levels is read", levels.size()));
  return g;
}

NodeData ParserV2::shape() {
  Shape s;
  fields([&](const Token& name) {
    if (name.text == "geometry")
      s.geometry = read_sfnode();
    else if (name.text == "appearance")
      s.appearance = read_node_of<Appearance>(name.text, "Appearance");
    else
      return false;
    return true;
  });
  return s;
}

NodeData ParserV2::appearance() {
  Appearance a;
  fields([&](const Token& name) {
    if (name.text == "material")
      a.material = read_node_of<Material>(name.text, "Material");
    else if (name.text == "texture")
      a.texture = read_sfnode(); // an ImageTexture, or a PixelTexture or MovieTexture (skipped)
    else
      return false;
    return true;
  });
  return a;
}

NodeData ParserV2::material() {
  Material m;
  fields([&](const Token& name) {
    if (name.text == "diffuseColor") {
      const std::vector<Vec3f> colour = read_vectors<Vec3f>(name.text);
      m.diffuse.assign(colour.begin(), colour.begin() + std::min<std::ptrdiff_t>(1, std::ssize(colour)));
    } else if (name.text == "transparency") {
      m.transparency = number<float>(next_required("a number"), name.text);
    } else {
      return false;
    }
    return true;
  });
  return m;
}

NodeData ParserV2::image_texture() {
  ImageTexture t;
  fields([&](const Token& name) {
    if (name.text != "url") return false;
    const std::vector<std::string_view> urls = read_strings(name.text);
    if (!urls.empty()) t.url = unescape(urls.front());
    return true;
  });
  return t;
}

NodeData ParserV2::face_set() {
  FaceSet f;
  fields([&](const Token& name) {
    const std::string_view n = name.text;
    if (n == "coord")
      f.coord = read_node_of<Coordinates>(n, "Coordinate");
    else if (n == "color")
      f.color = read_node_of<Colors>(n, "Color");
    else if (n == "normal")
      f.normal = read_node_of<Normals>(n, "Normal");
    else if (n == "texCoord")
      f.texcoord = read_node_of<TexCoords>(n, "TextureCoordinate");
    else if (n == "coordIndex")
      f.coord_index = read_index_list(n);
    else if (n == "colorIndex")
      f.color_index = read_index_list(n);
    else if (n == "normalIndex")
      f.normal_index = read_index_list(n);
    else if (n == "texCoordIndex")
      f.texcoord_index = read_index_list(n);
    else if (n == "ccw")
      f.ccw = read_bool(n);
    else if (n == "colorPerVertex")
      f.color_per_vertex = read_bool(n);
    else if (n == "normalPerVertex")
      f.normal_per_vertex = read_bool(n);
    else
      return false;
    return true;
  });
  return f;
}

NodeData ParserV2::point_set() {
  PointSet p;
  fields([&](const Token& name) {
    const std::string_view n = name.text;
    if (n == "coord")
      p.coord = read_node_of<Coordinates>(n, "Coordinate");
    else if (n == "color")
      p.color = read_node_of<Colors>(n, "Color");
    else
      return false;
    return true;
  });
  return p;
}

NodeData ParserV2::world_info() {
  fields([&](const Token& name) {
    if (name.text == "info") {
      take_info(read_strings(name.text));
    } else if (name.text == "title") {
      const std::vector<std::string_view> title = read_strings(name.text);
      if (scene_.title.empty() && !title.empty()) scene_.title = unescape(title.front());
    } else {
      return false;
    }
    return true;
  });
  return Skipped{};
}

NodeData ParserV2::inline_node(const Token& type) {
  std::vector<std::string_view> url;
  only_field("url", [&] { url = read_strings("url"); });
  context_.note(type.at,
                fmt::format("Inline {} not followed (the reader does not fetch other files)",
                            url.empty() ? std::string("without url") : excerpt(unescape(url.front()))));
  return Skipped{};
}

} // namespace pdeface::vrml::detail
