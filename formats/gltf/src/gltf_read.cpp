// glTF reader: our checks of the container and JSON (container.cpp, preflight.cpp), tinygltf's parse,
// then the scene walked here with transforms applied and every accessor read through checks
// (accessors.cpp).
#include "accessors.hpp"
#include "container.hpp"
#include "gltf_constants.hpp"
#include "pdeface/core/image.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/draco/detail.hpp"
#include "pdeface/gltf/gltf.hpp"
#include "preflight.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <tiny_gltf.h>

#include <limits>
#include <numeric>
#include <set>
#include <tuple>

namespace pdeface::gltf {
namespace {

using Matrix = Eigen::Matrix4d;

// Nodes may place one mesh many times: the vertices and triangles of repeated placements are bounded by
// the size of the file, so a few bytes of JSON cannot make us build gigabytes.
constexpr std::size_t kMaxInstancedPerByte = 16;
constexpr std::size_t kMaxNotes = 32;

// One primitive's vertices and faces, in world space.
struct Piece {
  std::vector<Vec3> positions;
  std::vector<Vec3f> normals;
  std::vector<Vec4f> colors;
  std::vector<Vec2f> texcoords;
  std::vector<Triangle> triangles;
  bool points = false;
  int material = -1;
};

// Images are never decoded: their encoded bytes (a buffer view's, a data URI's) are kept as they are, by
// image index, for the material.
bool keep_image(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user_data) {
  auto& images = *static_cast<std::vector<std::string>*>(user_data);
  if (index < 0 || size < 0) return true;
  if (images.size() <= static_cast<std::size_t>(index)) images.resize(static_cast<std::size_t>(index) + 1);
  images[static_cast<std::size_t>(index)].assign(reinterpret_cast<const char*>(bytes),
                                                 static_cast<std::size_t>(size));
  return true;
}

Result<tinygltf::Model> load(const Container& c, std::string_view source, std::vector<std::string>& images,
                             Notes* notes) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image, &images);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try { // our preflight has checked what tinygltf takes on trust; anything it throws is still bad data
    ok = c.glb ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                             reinterpret_cast<const unsigned char*>(c.bytes.data()),
                                             static_cast<unsigned>(c.bytes.size()))
               : loader.LoadASCIIFromString(&model, &err, &warn, c.json.data(),
                                            static_cast<unsigned>(c.json.size()), "");
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (!ok)
    return make_error(ErrorCode::Malformed, "tinygltf: " + drc::detail::message_text(err),
                      std::string(source));
  if (!warn.empty() && notes)
    notes->push_back(fmt::format("{}: tinygltf: {}", source, drc::detail::message_text(warn)));
  return model;
}

// Triangles of a primitive of `mode` over the vertex sequence `v`, as glTF 2.0 (3.7.2.1) defines them.
// Strips and fans repeat vertices to restart: their degenerate triangles are skipped.
std::vector<Triangle> triangulate(int mode, const std::vector<std::uint32_t>& v) {
  std::vector<Triangle> out;
  const std::size_t n = v.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t i = 0; i + 2 < n; i += 3)
      out.push_back({v[i], v[i + 1], v[i + 2]});
    return out;
  }
  for (std::size_t i = 0; i + 2 < n; ++i) {
    const Triangle t = mode == TINYGLTF_MODE_TRIANGLE_STRIP
                           ? Triangle{v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]}
                           : Triangle{v[i + 1], v[i + 2], v[0]};
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) out.push_back(t);
  }
  return out;
}

class SceneReader {
public:
  SceneReader(const tinygltf::Model& model, const Container& container, const Preflight& preflight,
              const std::vector<std::string>& images, const Resolver& resolve, std::string_view source,
              Notes* notes)
      : model_(model), container_(container), images_(images), resolve_(resolve),
        accessors_(model, container, preflight.buffer_views, source), source_(source), notes_(notes),
        instanced_limit_(kMaxInstancedPerByte * container.bytes.size()),
        mesh_seen_(model.meshes.size(), false) {}

  Result<Mesh> run() {
    if (auto e = walk()) return std::move(*e);
    return merge();
  }

private:
  [[nodiscard]] Error error(ErrorCode code, std::string message) const {
    return make_error(code, std::move(message), std::string(source_));
  }
  // Each distinct note once; past kMaxNotes of them, one saying so (a file naming a thousand attributes
  // should not give a thousand notes).
  void note(std::string text) {
    if (!notes_ || !noted_.insert(text).second || noted_.size() > kMaxNotes + 1) return;
    notes_->push_back(noted_.size() > kMaxNotes ? fmt::format("{}: more notes not shown", source_)
                                                : fmt::format("{}: {}", source_, text));
  }

  // The default scene, else scene 0, else every root node; a file with meshes but no nodes at all has
  // them read untransformed.
  std::optional<Error> walk() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<std::size_t>(scene) >= model_.scenes.size())
        return error(ErrorCode::Malformed, fmt::format("the default scene {} does not exist", scene));
      roots = model_.scenes[scene].nodes;
    } else if (!model_.nodes.empty()) {
      std::vector<bool> child(model_.nodes.size(), false);
      for (const tinygltf::Node& node : model_.nodes)
        for (int c : node.children)
          if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[c] = true;
      for (std::size_t i = 0; i < child.size(); ++i)
        if (!child[i]) roots.push_back(static_cast<int>(i));
    } else {
      if (!model_.meshes.empty()) note("no nodes: every mesh read untransformed");
      for (std::size_t m = 0; m < model_.meshes.size(); ++m)
        if (auto e = mesh(static_cast<int>(m), Matrix::Identity())) return e;
      return std::nullopt;
    }
    return nodes(roots);
  }

  // The nodes under `roots`, depth first with an explicit stack (a hostile chain of nodes must not
  // exhaust the call stack). The hierarchy is a forest (glTF 2.0 3.5.2): a node reached twice is in a cycle
  // or has two parents, both invalid; refusing it also bounds the walk.
  std::optional<Error> nodes(const std::vector<int>& roots) {
    std::vector<bool> visited(model_.nodes.size(), false);
    std::vector<std::pair<int, Matrix>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.emplace_back(*it, Matrix::Identity());
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
        return error(ErrorCode::Malformed, fmt::format("node {} does not exist", index));
      if (visited[index])
        return error(ErrorCode::Malformed,
                     fmt::format("node {} is reached twice: the node hierarchy must be a forest", index));
      visited[index] = true;
      const tinygltf::Node& n = model_.nodes[index];
      Result<Matrix> local = transform(n, index);
      if (!local) return std::move(local).error();
      const Matrix world = parent * *local;
      if (n.mesh >= 0)
        if (auto e = mesh(n.mesh, world)) return e;
      for (auto it = n.children.rbegin(); it != n.children.rend(); ++it)
        stack.emplace_back(*it, world);
    }
    return std::nullopt;
  }

  // A node's matrix, or its translation * rotation * scale.
  Result<Matrix> transform(const tinygltf::Node& n, int index) const {
    auto bad = [&](std::string_view what) {
      return error(ErrorCode::Malformed, fmt::format("node {}: {}", index, what));
    };
    auto finite = [](const std::vector<double>& v) {
      return std::ranges::all_of(v, [](double x) { return std::isfinite(x); });
    };
    if (!finite(n.matrix) || !finite(n.translation) || !finite(n.rotation) || !finite(n.scale))
      return error(ErrorCode::NonFinite, fmt::format("node {}: its transform is not finite", index));
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) return bad("a matrix needs 16 numbers");
      return Matrix(Eigen::Map<const Matrix>(n.matrix.data())); // column-major, as glTF stores it
    }
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) return bad("a translation needs 3 numbers");
      t.translate(Vec3(n.translation[0], n.translation[1], n.translation[2]));
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) return bad("a rotation needs 4 numbers (a quaternion x, y, z, w)");
      const Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      if (q.norm() < 1e-6) return bad("its rotation quaternion is zero");
      t.rotate(q.normalized());
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) return bad("a scale needs 3 numbers");
      t.scale(Vec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return t.matrix();
  }

  std::optional<Error> mesh(int index, const Matrix& world) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.meshes.size())
      return error(ErrorCode::Malformed, fmt::format("mesh {} does not exist", index));
    const tinygltf::Mesh& m = model_.meshes[index];
    if (!m.name.empty()) names_.insert(m.name);
    const bool instance = mesh_seen_[index];
    mesh_seen_[index] = true;
    for (std::size_t p = 0; p < m.primitives.size(); ++p)
      if (auto e =
              primitive(m.primitives[p], world, instance, fmt::format("meshes[{}].primitives[{}]", index, p)))
        return e;
    return std::nullopt;
  }

  // An optional attribute: its values if the primitive has it, with `components` of the allowed ones.
  Result<std::optional<Floats>> attribute(const tinygltf::Primitive& p, const std::string& name,
                                          const std::vector<int>& components, std::size_t count,
                                          const std::string& where) const {
    const auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return std::optional<Floats>();
    Result<Floats> values = accessors_.floats(it->second, where + " " + name);
    if (!values) return std::move(values).error();
    if (std::ranges::find(components, values->components) == components.end())
      return error(ErrorCode::Malformed,
                   fmt::format("{} {} has {} components", where, name, values->components));
    if (values->count() != count)
      return error(ErrorCode::Malformed,
                   fmt::format("{} {} has {} elements, POSITION {}", where, name, values->count(), count));
    return std::optional<Floats>(std::move(values).value());
  }

  // A primitive's arrays, as the file has them.
  struct Arrays {
    Floats positions;
    std::optional<Floats> normals, colors, texcoords;
    std::vector<std::uint32_t> order; // the indices, or 0..n-1
  };

  Result<Arrays> arrays(const tinygltf::Primitive& p, const std::string& where) const {
    const auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end())
      return error(ErrorCode::Malformed, where + " has no POSITION attribute");
    Result<Floats> positions = accessors_.floats(position->second, where + " POSITION");
    if (!positions) return std::move(positions).error();
    if (positions->components != 3)
      return error(ErrorCode::Malformed,
                   fmt::format("{} POSITION has {} components", where, positions->components));
    Arrays a;
    a.positions = std::move(positions).value();
    const std::size_t n = a.positions.count();
    struct Optional {
      std::string name;
      std::vector<int> components; // the counts allowed
      std::optional<Floats>* out;
    };
    for (const Optional& o : {Optional{"NORMAL", {3}, &a.normals}, Optional{"COLOR_0", {3, 4}, &a.colors},
                              Optional{"TEXCOORD_0", {2}, &a.texcoords}}) {
      Result<std::optional<Floats>> values = attribute(p, o.name, o.components, n, where);
      if (!values) return std::move(values).error();
      *o.out = std::move(values).value();
    }
    if (p.indices >= 0) {
      Result<std::vector<std::uint32_t>> indices = accessors_.indices(p.indices, n, where + " indices");
      if (!indices) return std::move(indices).error();
      a.order = std::move(indices).value();
    } else {
      a.order.resize(n);
      std::iota(a.order.begin(), a.order.end(), 0u);
    }
    return a;
  }

  // A primitive of a mesh placed by `world`; `instance`: the mesh was placed before.
  std::optional<Error> primitive(const tinygltf::Primitive& p, const Matrix& world, bool instance,
                                 const std::string& where) {
    // Draco data decodes to a triangle list whatever the mode says (TRIANGLES or TRIANGLE_STRIP).
    const bool draco = p.extensions.count(std::string(kDracoExtension)) > 0;
    const int mode = draco ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
      note("line primitives skipped: a mesh holds triangles and points");
      return std::nullopt;
    }
    if (mode != TINYGLTF_MODE_POINTS && mode != TINYGLTF_MODE_TRIANGLES &&
        mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return error(ErrorCode::Malformed, fmt::format("{}: unknown mode {}", where, p.mode));
    for (const auto& [name, accessor] : p.attributes)
      if (name != "POSITION" && name != "NORMAL" && name != "COLOR_0" && name != "TEXCOORD_0")
        note(fmt::format("attribute {} dropped: we read POSITION, NORMAL, COLOR_0 and TEXCOORD_0",
                         excerpt(name)));
    Result<Arrays> a = arrays(p, where);
    if (!a) return std::move(a).error();
    if (instance) {
      instanced_ += a->positions.count() + a->order.size() / 3;
      if (instanced_ > instanced_limit_)
        return error(ErrorCode::CountTooLarge,
                     fmt::format("nodes instance meshes into more than {} further vertices and triangles ({} "
                                 "per byte of the file)",
                                 instanced_limit_, kMaxInstancedPerByte));
    }
    pieces_.push_back(place(*a, world, mode, where));
    pieces_.back().material = p.material;
    return std::nullopt;
  }

  // A primitive in world space: positions by the node's transform, normals by its inverse transpose (made
  // unit again), triangles from the mode.
  Piece place(const Arrays& a, const Matrix& world, int mode, const std::string& where) {
    Piece piece;
    const std::size_t n = a.positions.count();
    const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
    piece.positions.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const float* p = a.positions[i];
      piece.positions[i] = linear * Vec3(p[0], p[1], p[2]) + world.topRightCorner<3, 1>();
    }
    if (a.normals && std::abs(linear.determinant()) < 1e-12) {
      note("normals dropped: a node scales a primitive to zero");
    } else if (a.normals) {
      const Eigen::Matrix3f normal_matrix = linear.inverse().transpose().cast<float>();
      piece.normals.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const float* v = (*a.normals)[i];
        const Vec3f m = normal_matrix * Vec3f(v[0], v[1], v[2]);
        piece.normals[i] = m.norm() > 0 ? Vec3f(m.normalized()) : m;
      }
    }
    if (a.colors) {
      piece.colors.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const float* c = (*a.colors)[i];
        piece.colors[i] = Vec4f(c[0], c[1], c[2], a.colors->components == 4 ? c[3] : 1.0f);
      }
    }
    if (a.texcoords) {
      piece.texcoords.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        piece.texcoords[i] = Vec2f((*a.texcoords)[i][0], (*a.texcoords)[i][1]);
    }
    if (mode == TINYGLTF_MODE_POINTS) {
      piece.points = true;
      if (a.order.size() != n || !std::ranges::is_sorted(a.order))
        note("indices of POINTS primitives ignored: every vertex is a point");
      return piece;
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && a.order.size() % 3 != 0)
      note(fmt::format("{}: {} indices left over after the last whole triangle", where, a.order.size() % 3));
    piece.triangles = triangulate(mode, a.order);
    // A mirroring transform turns counter-clockwise triangles clockwise (glTF 2.0 3.7.4).
    if (linear.determinant() < 0)
      for (Triangle& t : piece.triangles)
        std::swap(t[1], t[2]);
    return piece;
  }

  // Every piece in one mesh; an attribute only some pieces have is dropped, with a note.
  Result<Mesh> merge() {
    if (pieces_.empty()) return error(ErrorCode::Empty, "the scene holds no triangle or point primitive");
    std::size_t total = 0;
    for (const Piece& p : pieces_)
      total += p.positions.size();
    if (total > std::numeric_limits<std::uint32_t>::max())
      return error(ErrorCode::CountTooLarge,
                   fmt::format("{} vertices: more than 32-bit indices can address", total));
    auto all = [&](auto member) {
      return std::ranges::all_of(pieces_, [&](const Piece& p) { return !(p.*member).empty(); });
    };
    auto keep = [&](auto member, std::string_view what) {
      const bool every = all(member);
      const bool some = std::ranges::any_of(pieces_, [&](const Piece& p) { return !(p.*member).empty(); });
      if (some && !every) note(fmt::format("{} dropped: only some primitives have them", what));
      return every;
    };
    const bool normals = keep(&Piece::normals, "normals");
    const bool colors = keep(&Piece::colors, "vertex colours");
    const bool texcoords = keep(&Piece::texcoords, "texture coordinates");

    Mesh mesh;
    std::size_t points = 0;
    for (const Piece& p : pieces_) {
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), p.positions.begin(), p.positions.end());
      if (normals) mesh.normals.insert(mesh.normals.end(), p.normals.begin(), p.normals.end());
      if (colors) mesh.colors.insert(mesh.colors.end(), p.colors.begin(), p.colors.end());
      if (texcoords) mesh.texcoords.insert(mesh.texcoords.end(), p.texcoords.begin(), p.texcoords.end());
      for (const Triangle& t : p.triangles)
        mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
      if (p.points) points += p.positions.size();
    }
    if (points > 0 && !mesh.triangles.empty())
      note(fmt::format("the scene mixes points and triangles: its {} points are vertices on no triangle",
                       points));
    if (names_.size() == 1) mesh.name = *names_.begin();
    read_units(mesh);
    if (Result<void> valid = validate(mesh, source_); !valid) return std::move(valid).error();
    if (mesh.positions.empty()) return error(ErrorCode::Empty, "the scene's primitives hold no vertices");
    // glTF's (0, 0) is the image's top left, ours its bottom left (OBJ's, VRML's).
    for (Vec2f& t : mesh.texcoords)
      t.y() = 1.0F - t.y();
    if (Result<void> m = read_material(mesh); !m) return std::move(m).error();
    if (mesh.has_texcoords()) {
      // Vertices a writer split at texture seams (ours among them) joined again: one vertex, a texture
      // coordinate per corner, as the shape's connectivity is.
      std::size_t merged = 0;
      mesh = weld_texcoord_seams(std::move(mesh), &merged);
      if (merged > 0)
        note(fmt::format(
            "{} vertices that repeat another's position, normal and colour merged with it (texture "
            "coordinates per corner)",
            merged));
    }
    return mesh;
  }

  // The material of the first primitive (a face is one): base colour factor and image.
  Result<void> read_material(Mesh& mesh) {
    int index = -1;
    for (const Piece& p : pieces_) {
      if (p.material < 0) continue;
      if (index < 0) index = p.material;
      if (p.material != index) note("materials of primitives after the first dropped: a mesh holds one");
    }
    if (index < 0 || static_cast<std::size_t>(index) >= model_.materials.size()) return {};
    const tinygltf::Material& m = model_.materials[static_cast<std::size_t>(index)];
    Material material;
    material.name = m.name;
    const std::vector<double>& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4 && std::ranges::all_of(f, [](double x) { return std::isfinite(x); }))
      material.base_color = Vec4f(static_cast<float>(f[0]), static_cast<float>(f[1]),
                                  static_cast<float>(f[2]), static_cast<float>(f[3]));
    const int texture = m.pbrMetallicRoughness.baseColorTexture.index;
    if (texture >= 0) {
      if (m.pbrMetallicRoughness.baseColorTexture.texCoord != 0)
        note("base colour texture dropped: it maps through TEXCOORD_1 or above, which we do not read");
      else if (static_cast<std::size_t>(texture) >= model_.textures.size())
        return error(ErrorCode::IndexOutOfRange, fmt::format("materials[{}] refers to texture {} of {}",
                                                             index, texture, model_.textures.size()));
      else if (Result<std::optional<Image>> image = read_image(model_.textures[texture].source); !image)
        return std::move(image).error();
      else
        material.base_color_image = std::move(image).value();
    }
    mesh.material = std::move(material);
    return {};
  }

  // Image `index`: embedded (a buffer view, a data URI), else through the resolver.
  Result<std::optional<Image>> read_image(int index) {
    if (index < 0) return std::optional<Image>();
    if (static_cast<std::size_t>(index) >= model_.images.size())
      return error(ErrorCode::IndexOutOfRange,
                   fmt::format("a texture refers to image {} of {}", index, model_.images.size()));
    const tinygltf::Image& gi = model_.images[static_cast<std::size_t>(index)];
    const bool embedded = gi.bufferView >= 0 || gi.uri.starts_with("data:");
    if (!embedded) {
      Result<Image> image = resolve_image(resolve_, gi.uri, source_, notes_);
      if (!image) return std::move(image).error();
      return std::optional<Image>(std::move(image).value());
    }
    Image image;
    if (static_cast<std::size_t>(index) < images_.size())
      image.bytes = images_[static_cast<std::size_t>(index)];
    if (image.bytes.empty()) {
      note(fmt::format("image {} dropped: it holds no bytes", index));
      return std::optional<Image>();
    }
    if (!image_mime_type(image.bytes)) {
      note(fmt::format("image {} dropped: neither JPEG nor PNG", index));
      return std::optional<Image>();
    }
    Result<ImageInfo> info = inspect_image(image.bytes, source_);
    if (!info) {
      Error e = std::move(info).error();
      e.message = fmt::format("image {}: {}", index, e.message);
      // Where the image starts in a GLB's BIN chunk, when it lies there.
      if (gi.bufferView >= 0 && container_.glb && e.where.byte &&
          static_cast<std::size_t>(gi.bufferView) < model_.bufferViews.size() &&
          model_.bufferViews[gi.bufferView].buffer == 0)
        e.where.byte = *e.where.byte + container_.bin_offset + model_.bufferViews[gi.bufferView].byteOffset;
      else
        e.where = {};
      return e;
    }
    image.mime_type = info->mime_type;
    return std::optional<Image>(std::move(image));
  }

  void read_units(Mesh& mesh) {
    const tinygltf::Value& extras = model_.asset.extras;
    if (!extras.IsObject() || !extras.Has(std::string(kUnitsKey))) return;
    const tinygltf::Value& units = extras.Get(std::string(kUnitsKey));
    const std::optional<Units> known =
        units.IsString() ? units_from_string(units.Get<std::string>()) : std::nullopt;
    if (known)
      mesh.units = *known;
    else
      note("asset.extras.units is not one of \"mm\", \"cm\", \"m\", \"in\": units unknown");
  }

  const tinygltf::Model& model_;
  const Container& container_;
  const std::vector<std::string>& images_;
  const Resolver& resolve_;
  Accessors accessors_;
  std::string_view source_;
  Notes* notes_;
  std::set<std::string> noted_;
  std::set<std::string> names_;
  std::vector<Piece> pieces_;
  std::size_t instanced_ = 0;
  std::size_t instanced_limit_;
  std::vector<bool> mesh_seen_;
};

} // namespace

Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes, const Resolver& resolve) {
  if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
    return make_error(ErrorCode::CountTooLarge, "more than 4 GiB: glTF files are limited to 32-bit lengths",
                      std::string(source));
  Result<Container> container = split_container(bytes, source, notes);
  if (!container) return std::move(container).error();
  Result<Preflight> checked = preflight(*container, source);
  if (!checked) return std::move(checked).error();
  std::vector<std::string> images;
  Result<tinygltf::Model> model = load(*container, source, images, notes);
  if (!model) return std::move(model).error();
  return SceneReader(*model, *container, *checked, images, resolve, source, notes).run();
}

} // namespace pdeface::gltf
