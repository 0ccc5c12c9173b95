#include "build.hpp"
#include "pdeface/core/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace pdeface::vrml::detail {
namespace {

// Limits on what `USE` can multiply: a few hundred bytes of nested instancing could otherwise ask for
// terabytes. They are checked by a counting pass before anything is allocated, and are far above any
// scan (the largest face scans have about a million vertices).
constexpr std::size_t kMaxVertices = std::size_t{1} << 25;
constexpr std::size_t kMaxCorners = std::size_t{1} << 27; // coordIndex entries, so about as many triangles
constexpr std::size_t kMaxVisits = std::size_t{1} << 24;  // node instances visited
// ... and bounded by what the file's size justifies: a vertex takes at least 6 bytes to write ("0 0 0 "), a
// corner 2 ("0 "), so these allow every one of them to be drawn about 100 times over, and any scene a
// small file can hold. An 11 KB file of nested USEs could otherwise ask for 33 million vertices (4 GB).
constexpr std::size_t kFreeElements = std::size_t{1} << 16;
constexpr std::size_t kVerticesPerByte = 16;
constexpr std::size_t kCornersPerByte = 64;

//! A per-vertex attribute as a face set gives it: values, an optional index list, and why the values
//! cannot be per vertex (empty when they can).
template <class T> struct Attribute {
  const std::vector<T>* values = nullptr;
  const IndexList* index = nullptr;
  std::string reason_not_per_vertex;
};

//! A face set with everything it needs resolved (VRML 2.0 from its fields, VRML 1.0 from the state).
struct FaceSetView {
  const Node* node = nullptr;
  const std::vector<Vec3>* points = nullptr;
  const IndexList* coord_index = nullptr;
  bool clockwise = false;
  Attribute<Vec3f> normals, colors;
  Attribute<Vec2f> texcoords;
};

struct PointSetView {
  const Node* node = nullptr;
  std::span<const Vec3> points;
  const std::vector<Vec3f>* colors = nullptr; // one per point of `points`, or more
};

//! One attribute of the merged mesh: kept only if every geometry has it (else dropped, with a note).
template <class T> class MergedAttribute {
public:
  //! Appends the values of a geometry of `count` vertices that starts at vertex `offset`, or notes that
  //! it has none.
  void append(std::optional<std::vector<T>> values, std::size_t offset, std::size_t count) {
    if (!values) {
      ++without_;
      if (with_ > 0) values_.resize(offset + count, T::Zero());
      return;
    }
    if (with_ == 0) values_.resize(offset, T::Zero());
    values_.insert(values_.end(), values->begin(), values->end());
    ++with_;
  }
  //! The values, or nothing (noted) when only some geometries had them.
  std::vector<T> take(Context& context, std::string_view what) {
    if (with_ > 0 && without_ > 0) {
      context.note(
          fmt::format("{} dropped: only {} of the {} geometries have them", what, with_, with_ + without_));
      return {};
    }
    return std::move(values_);
  }

private:
  std::vector<T> values_;
  std::size_t with_ = 0, without_ = 0;
};

std::string_view binding_name(Binding b) {
  switch (b) {
  case Binding::Default: return "DEFAULT";
  case Binding::Overall: return "OVERALL";
  case Binding::PerPart: return "PER_PART";
  case Binding::PerPartIndexed: return "PER_PART_INDEXED";
  case Binding::PerFace: return "PER_FACE";
  case Binding::PerFaceIndexed: return "PER_FACE_INDEXED";
  case Binding::PerVertex: return "PER_VERTEX";
  case Binding::PerVertexIndexed: return "PER_VERTEX_INDEXED";
  }
  return "?";
}

//! The length of an index list without one trailing -1 (a final polygon may or may not be closed).
std::size_t used_length(const std::vector<std::int32_t>& v) {
  return !v.empty() && v.back() == -1 ? v.size() - 1 : v.size();
}

class Builder {
public:
  Builder(Context& context, bool counting) : context_(context), counting_(counting) {}

  //! Called on every node visited: bounds the work and the depth of `USE` chains.
  void enter(const Node& node, std::size_t depth) {
    if (++visits_ > kMaxVisits)
      context_.fail(
          ErrorCode::CountTooLarge, node.at,
          fmt::format("the scene graph draws more than {} node instances (through USE)", kMaxVisits));
    if (depth > kMaxDepth)
      context_.fail(ErrorCode::Malformed, node.at,
                    fmt::format("groups nest deeper than {} levels (through USE)", kMaxDepth));
  }

  [[noreturn]] void fail(ErrorCode code, const Position& at, std::string message) const {
    context_.fail(code, at, std::move(message));
  }
  void note(const Position& at, std::string_view text) {
    if (!counting_) context_.note(at, text);
  }
  void note(std::string_view text) {
    if (!counting_) context_.note(text);
  }

  void face_set(const FaceSetView& f, const Eigen::Affine3d& matrix);
  //! VRML 2.0: the Appearance of a Shape drawn; the first one's material is the mesh's.
  void appearance(const Node& node);
  void point_set(const PointSetView& p, const Eigen::Affine3d& matrix);

  //! After the counting pass: reserves the output.
  void reserve(const Builder& counted) {
    mesh_.positions.reserve(counted.vertices_);
    mesh_.triangles.reserve(counted.corners_ / 4); // exact for triangles ("a b c -1")
  }
  Mesh finish(const Scene& scene);

private:
  void count(const Node& node, std::size_t vertices, std::size_t corners);
  void append_positions(std::span<const Vec3> points, const Eigen::Affine3d& matrix);
  template <class T>
  std::optional<std::vector<T>> per_vertex(const Attribute<T>& a, const FaceSetView& f, std::string_view what,
                                           std::string_view index_name);

  Context& context_;
  bool counting_;
  std::size_t visits_ = 0, vertices_ = 0, corners_ = 0;
  std::size_t face_sets_ = 0, point_sets_ = 0, point_set_points_ = 0, short_polygons_ = 0;
  //! Each corner's index into its face set's texture coordinates (per coordIndex entry; -1 ends a
  //! polygon), or nullopt when the face set has none we can read.
  std::optional<std::vector<std::int32_t>> corner_texcoords(const FaceSetView& f);

  Mesh mesh_;
  MergedAttribute<Vec3f> normals_;
  MergedAttribute<Vec4f> colors_;
  // Texture coordinates per corner, whatever the file's form: the face sets' values one after another, and
  // one index triangle per triangle; made per vertex in `finish` when no vertex has two.
  std::vector<Vec2f> uv_table_;
  std::vector<Triangle> uv_triangles_;
  std::size_t uv_sets_ = 0, no_uv_sets_ = 0;
  std::size_t appearances_ = 0;
};

void Builder::appearance(const Node& node) {
  const auto* a = std::get_if<Appearance>(&node.data);
  if (counting_ || !a || ++appearances_ > 1) {
    if (!counting_ && appearances_ == 2)
      note(node.at, "Appearances after the first dropped: a mesh holds one material");
    return;
  }
  pdeface::Material m;
  const auto* image = a->texture ? std::get_if<ImageTexture>(&a->texture->data) : nullptr;
  if (a->texture && !image)
    note(a->texture->at,
         fmt::format("texture {} dropped: only ImageTexture is read", excerpt(a->texture->type)));
  if (const auto* material = a->material ? std::get_if<Material>(&a->material->data) : nullptr) {
    // An RGB texture replaces the diffuse colour (VRML97 4.14): the colour only without an image.
    if (!material->diffuse.empty() && (!image || image->url.empty()))
      m.base_color.head<3>() = material->diffuse.front();
    m.base_color[3] = std::clamp(1.0F - material->transparency, 0.0F, 1.0F);
  }
  if (image && !image->url.empty())
    m.base_color_image = pdeface::Image{.bytes = {}, .mime_type = {}, .uri = image->url};
  mesh_.material = std::move(m);
}

void Builder::count(const Node& node, std::size_t vertices, std::size_t corners) {
  vertices_ += vertices;
  corners_ += corners;
  const std::size_t bytes = context_.bytes().size();
  const std::size_t max_vertices = std::min(kMaxVertices, kFreeElements + kVerticesPerByte * bytes);
  const std::size_t max_corners = std::min(kMaxCorners, kFreeElements + kCornersPerByte * bytes);
  if (vertices_ > max_vertices || corners_ > max_corners)
    context_.fail(ErrorCode::CountTooLarge, node.at,
                  fmt::format("the scene instances more than {} vertices or {} coordIndex entries (through "
                              "USE): more than a file of {} bytes justifies",
                              max_vertices, max_corners, bytes));
}

void Builder::append_positions(std::span<const Vec3> points, const Eigen::Affine3d& matrix) {
  if (matrix.matrix().isIdentity(0.0)) {
    mesh_.positions.insert(mesh_.positions.end(), points.begin(), points.end()); // bit for bit
    return;
  }
  for (const Vec3& p : points)
    mesh_.positions.push_back(matrix * p);
}

void Builder::face_set(const FaceSetView& f, const Eigen::Affine3d& matrix) {
  const std::size_t n = f.points->size();
  const std::vector<std::int32_t>& index = f.coord_index->values;
  if (counting_) return count(*f.node, n, index.size());
  ++face_sets_;

  // Check every index, then fan-triangulate each polygon (v0 vi vi+1). A mirroring transform turns the
  // winding over, so it flips the order back, like ccw FALSE does.
  const bool flip = f.clockwise != (matrix.linear().determinant() < 0.0);
  const auto offset = static_cast<std::uint32_t>(mesh_.positions.size());
  const std::optional<std::vector<std::int32_t>> uv = corner_texcoords(f);
  const auto uv_offset = static_cast<std::uint32_t>(uv_table_.size());
  if (uv) {
    ++uv_sets_;
    uv_table_.insert(uv_table_.end(), f.texcoords.values->begin(), f.texcoords.values->end());
  } else {
    ++no_uv_sets_;
  }
  std::size_t start = 0;
  for (std::size_t k = 0; k <= index.size(); ++k) {
    if (k < index.size() && index[k] != -1) {
      if (index[k] < 0 || static_cast<std::size_t>(index[k]) >= n)
        context_.fail(
            ErrorCode::IndexOutOfRange, context_.locate(*f.coord_index, k),
            fmt::format("coordIndex {} is out of range: the Coordinate has {} points (0 to {}), and -1 "
                        "ends a polygon",
                        index[k], n, static_cast<std::int64_t>(n) - 1));
      continue;
    }
    const std::size_t size = k - start;
    if (size > 0 && size < 3) ++short_polygons_;
    for (std::size_t i = start + 1; i + 1 < k; ++i) {
      const auto a = static_cast<std::uint32_t>(index[start]), b = static_cast<std::uint32_t>(index[i]),
                 c = static_cast<std::uint32_t>(index[i + 1]);
      mesh_.triangles.push_back(flip ? Triangle{offset + a, offset + c, offset + b}
                                     : Triangle{offset + a, offset + b, offset + c});
      Triangle t{0, 0, 0};
      if (uv) {
        const auto at = [&](std::size_t corner) {
          return uv_offset + static_cast<std::uint32_t>((*uv)[corner]);
        };
        t = flip ? Triangle{at(start), at(i + 1), at(i)} : Triangle{at(start), at(i), at(i + 1)};
      }
      uv_triangles_.push_back(t);
    }
    start = k + 1;
  }
  append_positions(*f.points, matrix);

  std::optional<std::vector<Vec3f>> normals = per_vertex(f.normals, f, "normals", "normalIndex");
  if (normals && !matrix.linear().isIdentity(0.0)) {
    // Normals transform by the inverse transpose of the linear part, and are then unit again.
    const Eigen::Matrix3f m = matrix.linear().inverse().transpose().cast<float>();
    for (Vec3f& v : *normals)
      if (const float len = (m * v).norm(); len > 0.0F) v = (m * v) / len;
  }
  normals_.append(std::move(normals), offset, n);

  std::optional<std::vector<Vec3f>> rgb = per_vertex(f.colors, f, "colours", "colorIndex");
  std::optional<std::vector<Vec4f>> rgba;
  if (rgb) {
    rgba.emplace();
    rgba->reserve(rgb->size());
    for (const Vec3f& c : *rgb)
      rgba->emplace_back(c.x(), c.y(), c.z(), 1.0F);
  }
  colors_.append(std::move(rgba), offset, n);
}

// Texture coordinates follow coordIndex without a texCoordIndex, else texCoordIndex: per corner, so a
// seam (a vertex given two) is kept.
std::optional<std::vector<std::int32_t>> Builder::corner_texcoords(const FaceSetView& f) {
  const Attribute<Vec2f>& a = f.texcoords;
  if (!a.values) return std::nullopt;
  const Position& at = f.node->at;
  const std::vector<Vec2f>& values = *a.values;
  const std::vector<std::int32_t>& corners = f.coord_index->values;
  const std::size_t n = f.points->size();
  if (!a.index || a.index->values.empty()) {
    if (values.size() < n) {
      note(at, fmt::format("texture coordinates dropped: {} of them for {} points", values.size(), n));
      return std::nullopt;
    }
    return corners;
  }
  const std::vector<std::int32_t>& index = a.index->values;
  const std::size_t length = used_length(corners);
  if (used_length(index) != length) {
    note(at, fmt::format("texture coordinates dropped: texCoordIndex has {} entries where coordIndex has {}",
                         index.size(), corners.size()));
    return std::nullopt;
  }
  std::vector<std::int32_t> out(corners.size(), -1);
  for (std::size_t k = 0; k < length; ++k) {
    const std::int32_t i = index[k];
    if (i < -1 || (i >= 0 && static_cast<std::size_t>(i) >= values.size()))
      context_.fail(ErrorCode::IndexOutOfRange, context_.locate(*a.index, k),
                    fmt::format("texCoordIndex {} is out of range: there are {} texture coordinates", i,
                                values.size()));
    if ((corners[k] == -1) != (i == -1)) {
      note(at, "texture coordinates dropped: texCoordIndex and coordIndex do not end polygons at the same "
               "places");
      return std::nullopt;
    }
    out[k] = i;
  }
  return out;
}

void Builder::point_set(const PointSetView& p, const Eigen::Affine3d& matrix) {
  const std::size_t n = p.points.size();
  if (counting_) return count(*p.node, n, 0);
  ++point_sets_;
  point_set_points_ += n;
  const std::size_t offset = mesh_.positions.size();
  append_positions(p.points, matrix);
  std::optional<std::vector<Vec4f>> colors;
  if (p.colors && p.colors->size() >= n) {
    colors.emplace();
    colors->reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      colors->emplace_back((*p.colors)[i].x(), (*p.colors)[i].y(), (*p.colors)[i].z(), 1.0F);
  } else if (p.colors) {
    note(p.node->at, fmt::format("PointSet colours dropped: {} colours for {} points", p.colors->size(), n));
  }
  colors_.append(std::move(colors), offset, n);
  normals_.append(std::nullopt, offset, n);
}

// The rule for every attribute: keep it when each vertex gets exactly one value. With no index list
// the values follow coordIndex (value v for vertex v); with one, every corner's entry must agree for
// its vertex (a seam, where one vertex has two values, would need the vertex split: dropped instead).
template <class T>
std::optional<std::vector<T>> Builder::per_vertex(const Attribute<T>& a, const FaceSetView& f,
                                                  std::string_view what, std::string_view index_name) {
  if (!a.values) return std::nullopt;
  const Position& at = f.node->at;
  if (!a.reason_not_per_vertex.empty()) {
    note(at, fmt::format("{} dropped: {}", what, a.reason_not_per_vertex));
    return std::nullopt;
  }
  const std::vector<T>& values = *a.values;
  const std::size_t n = f.points->size();
  if (!a.index || a.index->values.empty()) {
    if (values.size() < n) {
      note(at, fmt::format("{} dropped: {} of them for {} points", what, values.size(), n));
      return std::nullopt;
    }
    return std::vector<T>(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n));
  }
  const std::vector<std::int32_t>& corners = f.coord_index->values;
  const std::vector<std::int32_t>& index = a.index->values;
  const std::size_t length = used_length(corners);
  if (used_length(index) != length) {
    note(at, fmt::format("{} dropped: {} has {} entries where coordIndex has {}", what, index_name,
                         index.size(), corners.size()));
    return std::nullopt;
  }
  std::vector<std::int32_t> chosen(n, -1);
  for (std::size_t k = 0; k < length; ++k) {
    const std::int32_t i = index[k];
    if (i < -1 || (i >= 0 && static_cast<std::size_t>(i) >= values.size()))
      context_.fail(
          ErrorCode::IndexOutOfRange, context_.locate(*a.index, k),
          fmt::format("{} {} is out of range: there are {} {}", index_name, i, values.size(), what));
    const std::int32_t c = corners[k];
    if ((c == -1) != (i == -1)) {
      note(at, fmt::format("{} dropped: {} and coordIndex do not end polygons at the same places", what,
                           index_name));
      return std::nullopt;
    }
    if (c == -1) continue;
    std::int32_t& v = chosen[static_cast<std::size_t>(c)];
    if (v != -1 && v != i) {
      note(at, fmt::format("{} dropped: vertex {} has two {} values ({} and {}); splitting vertices at such "
                           "seams is not supported",
                           what, c, index_name, v, i));
      return std::nullopt;
    }
    v = i;
  }
  std::vector<T> out(n, T::Zero()); // vertices on no face get zeros
  for (std::size_t v = 0; v < n; ++v)
    if (chosen[v] >= 0) out[v] = values[static_cast<std::size_t>(chosen[v])];
  return out;
}

Mesh Builder::finish(const Scene& scene) {
  if (mesh_.positions.empty())
    context_.fail(ErrorCode::Empty, Position{}, "no IndexedFaceSet or PointSet with coordinates in the file");
  if (short_polygons_ > 0)
    context_.note(fmt::format("{} polygons with fewer than 3 vertices skipped", short_polygons_));
  if (face_sets_ > 0 && point_sets_ > 0)
    context_.note(fmt::format("the {} points of the PointSets are vertices without faces in the merged mesh",
                              point_set_points_));
  mesh_.normals = normals_.take(context_, "normals");
  mesh_.colors = colors_.take(context_, "colours");
  if (uv_sets_ > 0 && no_uv_sets_ > 0) {
    context_.note(fmt::format("texture coordinates dropped: only {} of the {} face sets have them", uv_sets_,
                              uv_sets_ + no_uv_sets_));
  } else if (uv_sets_ > 0 && !mesh_.triangles.empty()) {
    mesh_.texcoords = std::move(uv_table_);
    mesh_.texcoord_triangles = std::move(uv_triangles_);
    // Per vertex when no vertex has two (the vertices stay as they are).
    std::size_t split = 0;
    if (Mesh per_vertex = with_vertex_texcoords(mesh_, &split); split == 0) mesh_ = std::move(per_vertex);
  }
  mesh_.units = scene.units;
  mesh_.name = scene.title;
  return std::move(mesh_);
}

// --- VRML 2.0: geometry hangs under Shape nodes, each face set names its own attribute nodes --------------

template <class Data, class T>
const std::vector<T>* values_of(const NodePtr& node, std::vector<T> Data::*list) {
  return node ? &(std::get<Data>(node->data).*list) : nullptr;
}

void visit_v2(Builder& b, const Node& node, const Eigen::Affine3d& matrix, std::size_t depth) {
  b.enter(node, depth);
  if (const auto* g = std::get_if<Group>(&node.data)) {
    if (node.type == "Billboard")
      b.note(node.at, "Billboard: its rotation towards the viewer is not applied");
    const Eigen::Affine3d inner = g->matrix ? Eigen::Affine3d(matrix * *g->matrix) : matrix;
    for (const NodePtr& child : g->children)
      visit_v2(b, *child, inner, depth + 1);
    return;
  }
  const auto* shape = std::get_if<Shape>(&node.data);
  if (!shape || !shape->geometry) return;
  if (shape->appearance) b.appearance(*shape->appearance);
  const Node& geometry = *shape->geometry;
  b.enter(geometry, depth + 1);
  if (const auto* f = std::get_if<FaceSet>(&geometry.data)) {
    if (!f->coord) return b.note(geometry.at, "IndexedFaceSet without coord skipped");
    FaceSetView view{.node = &geometry,
                     .points = values_of(f->coord, &Coordinates::points),
                     .coord_index = &f->coord_index,
                     .clockwise = !f->ccw,
                     .normals = {values_of(f->normal, &Normals::vectors), &f->normal_index,
                                 f->normal_per_vertex ? "" : "normalPerVertex FALSE gives one per face"},
                     .colors = {values_of(f->color, &Colors::values), &f->color_index,
                                f->color_per_vertex ? "" : "colorPerVertex FALSE gives one per face"},
                     .texcoords = {values_of(f->texcoord, &TexCoords::points), &f->texcoord_index, ""}};
    b.face_set(view, matrix);
  } else if (const auto* p = std::get_if<PointSet>(&geometry.data)) {
    if (!p->coord) return b.note(geometry.at, "PointSet without coord skipped");
    b.point_set({&geometry, *values_of(p->coord, &Coordinates::points), values_of(p->color, &Colors::values)},
                matrix);
  } else {
    b.note(fmt::format("Shape geometry {} ignored (only IndexedFaceSet and PointSet are read)",
                       excerpt(geometry.type)));
  }
}

// --- VRML 1.0: property nodes change a state that later shapes use; Separators save and restore it ---------

struct StateV1 {
  Eigen::Affine3d matrix = Eigen::Affine3d::Identity();
  const Coordinates* coords = nullptr;
  const Normals* normals = nullptr;
  const TexCoords* texcoords = nullptr;
  const Material* material = nullptr;
  Binding normal_binding = Binding::Default;
  Binding material_binding = Binding::Default;
  bool clockwise = false;
};

FaceSetView view_v1(const Node& node, const FaceSet& f, const StateV1& s) {
  FaceSetView view;
  view.node = &node;
  view.points = &s.coords->points;
  view.coord_index = &f.coord_index;
  view.clockwise = s.clockwise;
  if (s.normals) {
    // An IndexedFaceSet's DEFAULT normal binding is PER_VERTEX_INDEXED.
    const bool per_vertex =
        s.normal_binding == Binding::Default || s.normal_binding == Binding::PerVertexIndexed;
    view.normals = {
        &s.normals->vectors, &f.normal_index,
        per_vertex ? "" : fmt::format("NormalBinding {} is not per vertex", binding_name(s.normal_binding))};
  }
  // A Material's DEFAULT binding is OVERALL: one colour for the shape, not vertex data, so not a colour.
  if (s.material && s.material_binding != Binding::Default && s.material_binding != Binding::Overall) {
    const bool per_vertex = s.material_binding == Binding::PerVertexIndexed;
    view.colors = {
        &s.material->diffuse, &f.color_index,
        per_vertex ? ""
                   : fmt::format("MaterialBinding {} is not per vertex", binding_name(s.material_binding))};
  }
  if (s.texcoords) view.texcoords = {&s.texcoords->points, &f.texcoord_index, ""};
  return view;
}

void point_set_v1(Builder& b, const Node& node, const PointSet& p, const StateV1& s) {
  const std::size_t n = s.coords->points.size();
  if (p.start < 0 || static_cast<std::size_t>(p.start) > n)
    b.fail(ErrorCode::IndexOutOfRange, p.start_at,
           fmt::format("startIndex {} is out of range: the Coordinate3 has {} points", p.start, n));
  const auto first = static_cast<std::size_t>(p.start);
  if (p.count < -1 || (p.count >= 0 && static_cast<std::size_t>(p.count) > n - first))
    b.fail(ErrorCode::IndexOutOfRange, p.count_at,
           fmt::format("numPoints {} from startIndex {} is out of range: the Coordinate3 has {} points",
                       p.count, first, n));
  const std::size_t count = p.count == -1 ? n - first : static_cast<std::size_t>(p.count);
  if (s.material &&
      (s.material_binding == Binding::PerVertex || s.material_binding == Binding::PerVertexIndexed))
    b.note(node.at, "PointSet colours from a per-vertex Material are not read");
  b.point_set({&node, std::span<const Vec3>(s.coords->points).subspan(first, count), nullptr}, s.matrix);
}

void visit_v1(Builder& b, const Node& node, StateV1& s, std::size_t depth) {
  b.enter(node, depth);
  const NodeData& d = node.data;
  if (const auto* g = std::get_if<Group>(&d)) {
    const StateV1 saved = s;
    for (const NodePtr& child : g->children)
      visit_v1(b, *child, s, depth + 1);
    if (g->scope == Scope::All)
      s = saved;
    else if (g->scope == Scope::Matrix)
      s.matrix = saved.matrix;
  } else if (const auto* coords = std::get_if<Coordinates>(&d)) {
    s.coords = coords;
  } else if (const auto* normals = std::get_if<Normals>(&d)) {
    s.normals = normals;
  } else if (const auto* texcoords = std::get_if<TexCoords>(&d)) {
    s.texcoords = texcoords;
  } else if (const auto* material = std::get_if<Material>(&d)) {
    s.material = material;
  } else if (const auto* nb = std::get_if<NormalBinding>(&d)) {
    s.normal_binding = nb->value;
  } else if (const auto* mb = std::get_if<MaterialBinding>(&d)) {
    s.material_binding = mb->value;
  } else if (const auto* hints = std::get_if<ShapeHints>(&d)) {
    s.clockwise = hints->clockwise;
  } else if (const auto* m = std::get_if<MatrixNode>(&d)) {
    s.matrix = s.matrix * m->matrix;
  } else if (const auto* f = std::get_if<FaceSet>(&d)) {
    if (!s.coords) return b.note(node.at, "IndexedFaceSet before any Coordinate3 skipped");
    b.face_set(view_v1(node, *f, s), s.matrix);
  } else if (const auto* p = std::get_if<PointSet>(&d)) {
    if (!s.coords) return b.note(node.at, "PointSet before any Coordinate3 skipped");
    point_set_v1(b, node, *p, s);
  }
}

} // namespace

Mesh build_mesh(const Scene& scene, Version version, Context& context) {
  auto traverse = [&](Builder& b) {
    StateV1 state; // VRML 1.0: a file with several top-level nodes reads as if they were in one Group
    for (const NodePtr& root : scene.roots) {
      if (version == Version::V2)
        visit_v2(b, *root, Eigen::Affine3d::Identity(), 1);
      else
        visit_v1(b, *root, state, 1);
    }
  };
  Builder counter(context, true);
  traverse(counter);
  Builder builder(context, false);
  builder.reserve(counter);
  traverse(builder);
  return builder.finish(scene);
}

} // namespace pdeface::vrml::detail
