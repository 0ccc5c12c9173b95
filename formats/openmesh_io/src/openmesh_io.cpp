#include "pdeface/openmesh_io/openmesh_io.hpp"

#include "pdeface/core/openmesh.hpp"

#include <Eigen/Geometry>
#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/exporter/BaseExporter.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/Mesh/BaseKernel.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>

namespace pdeface::openmesh_io {
namespace {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;
using StatusInfo = OpenMesh::Attributes::StatusInfo;

// OpenMesh's readers and writers are singletons with per-file state: one call at a time.
std::mutex& openmesh_mutex() {
  static std::mutex mutex;
  return mutex;
}

// ---- reading: a polygon soup straight into a Mesh -----------------------------------------------------

class SoupImporter final : public OpenMesh::IO::BaseImporter {
public:
  explicit SoupImporter(std::size_t max_reserve) : max_reserve_(max_reserve) {}

  Mesh mesh;
  std::size_t short_faces = 0;   // fewer than three corners: skipped
  std::size_t invalid_faces = 0; // a corner that is no vertex (the validators make this impossible)
  bool face_colors = false;

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return add_vertex(OpenMesh::Vec3d(p)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    mesh.positions.emplace_back(p[0], p[1], p[2]);
    return VertexHandle(static_cast<int>(mesh.positions.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
  void set_point(VertexHandle vh, const OpenMesh::Vec3f& p) override {
    if (valid(vh)) mesh.positions[index(vh)] = Vec3(p[0], p[1], p[2]);
  }

  // Polygons are fan-triangulated: (c0, c1, c2), (c0, c2, c3), ...
  FaceHandle add_face(const VHandles& corners) override {
    if (corners.size() < 3) {
      ++short_faces;
      return FaceHandle();
    }
    if (!std::ranges::all_of(corners, [this](VertexHandle vh) { return valid(vh); })) {
      ++invalid_faces;
      return FaceHandle();
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      mesh.triangles.push_back({static_cast<std::uint32_t>(corners[0].idx()),
                                static_cast<std::uint32_t>(corners[k].idx()),
                                static_cast<std::uint32_t>(corners[k + 1].idx())});
    return FaceHandle(static_cast<int>(polygons_++));
  }

  void set_normal(VertexHandle vh, const OpenMesh::Vec3f& n) override {
    set(mesh.normals, vh, Vec3f(n[0], n[1], n[2]));
  }
  void set_normal(VertexHandle vh, const OpenMesh::Vec3d& n) override { set_normal(vh, OpenMesh::Vec3f(n)); }
  void set_color(VertexHandle vh, const OpenMesh::Vec3uc& c) override {
    set_color(vh, OpenMesh::Vec4uc(c[0], c[1], c[2], 255));
  }
  void set_color(VertexHandle vh, const OpenMesh::Vec4uc& c) override {
    set(mesh.colors, vh, Vec4f(Vec4f(c[0], c[1], c[2], c[3]) / 255.0f));
  }
  void set_color(VertexHandle vh, const OpenMesh::Vec3f& c) override {
    set(mesh.colors, vh, Vec4f(c[0], c[1], c[2], 1.0f));
  }
  void set_color(VertexHandle vh, const OpenMesh::Vec4f& c) override {
    set(mesh.colors, vh, Vec4f(c[0], c[1], c[2], c[3]));
  }
  void set_texcoord(VertexHandle vh, const OpenMesh::Vec2f& t) override {
    set(mesh.texcoords, vh, Vec2f(t[0], t[1]));
  }

  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override { face_colors = true; }
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override { face_colors = true; }
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override { face_colors = true; }
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override { face_colors = true; }

  // The counts come from the file's header; never reserve more than the input could hold.
  void reserve(unsigned int vertices, unsigned int, unsigned int faces) override {
    mesh.positions.reserve(std::min<std::size_t>(vertices, max_reserve_));
    mesh.triangles.reserve(std::min<std::size_t>(faces, max_reserve_));
  }
  size_t n_vertices() const override { return mesh.positions.size(); }
  size_t n_faces() const override { return polygons_; }
  size_t n_edges() const override { return 0; }

  // Attributes set for some vertices only get zeros elsewhere, so every attribute has one entry per vertex.
  void finish() override {
    pad(mesh.normals);
    pad(mesh.colors);
    pad(mesh.texcoords);
  }

  // What only OpenMesh's own OM format or half-edge meshes use: not reachable from PLY, OFF and STL.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_status(VertexHandle, const StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_status(FaceHandle, const StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

private:
  static std::size_t index(VertexHandle vh) { return static_cast<std::size_t>(vh.idx()); }
  bool valid(VertexHandle vh) const { return vh.idx() >= 0 && index(vh) < mesh.positions.size(); }

  template <class T> void pad(std::vector<T>& attribute) const {
    if (!attribute.empty()) attribute.resize(mesh.positions.size(), T::Zero());
  }
  template <class T> void set(std::vector<T>& attribute, VertexHandle vh, const T& value) {
    if (!valid(vh)) return;
    if (attribute.size() <= index(vh)) attribute.resize(mesh.positions.size(), T::Zero());
    attribute[index(vh)] = value;
  }

  std::size_t max_reserve_;
  std::size_t polygons_ = 0;
};

// ---- writing: OpenMesh's writers over a Mesh ----------------------------------------------------------

OpenMesh::Vec4uc to_bytes(const Vec4f& c) {
  auto byte = [](float v) {
    return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  return {byte(c[0]), byte(c[1]), byte(c[2]), byte(c[3])};
}

// Our meshes colour only their vertices: every other element (faces, edges) has no colour and no status.
// One layer of these per element kind, over `Base`.
template <class Handle, class Base> class Uncoloured : public Base {
public:
  // The other element kinds' overloads stay visible beside these.
  using Base::color;
  using Base::colorA;
  using Base::colorAf;
  using Base::colorAi;
  using Base::colorf;
  using Base::colori;
  using Base::status;
  OpenMesh::Vec3uc color(Handle) const override { return OpenMesh::Vec3uc(0, 0, 0); }
  OpenMesh::Vec4uc colorA(Handle) const override { return OpenMesh::Vec4uc(0, 0, 0, 0); }
  OpenMesh::Vec3ui colori(Handle) const override { return OpenMesh::Vec3ui(0, 0, 0); }
  OpenMesh::Vec4ui colorAi(Handle) const override { return OpenMesh::Vec4ui(0, 0, 0, 0); }
  OpenMesh::Vec3f colorf(Handle) const override { return OpenMesh::Vec3f(0, 0, 0); }
  OpenMesh::Vec4f colorAf(Handle) const override { return OpenMesh::Vec4f(0, 0, 0, 0); }
  StatusInfo status(Handle) const override { return {}; }
};

using UncolouredExporter = Uncoloured<EdgeHandle, Uncoloured<FaceHandle, OpenMesh::IO::BaseExporter>>;

class MeshExporter final : public UncolouredExporter {
public:
  using UncolouredExporter::color;
  using UncolouredExporter::colorA;
  using UncolouredExporter::colorAf;
  using UncolouredExporter::colorAi;
  using UncolouredExporter::colorf;
  using UncolouredExporter::colori;
  using UncolouredExporter::status;
  MeshExporter(const Mesh& mesh, const OpenMeshWrite& how) : mesh_(mesh), how_(how) {}

  // Positions leave as float32 whatever the writer would do with doubles: the usual PLY/STL/OFF precision.
  OpenMesh::Vec3f point(VertexHandle vh) const override {
    const Vec3& p = mesh_.positions[index(vh)];
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
  }
  OpenMesh::Vec3d pointd(VertexHandle vh) const override { return OpenMesh::Vec3d(point(vh)); }
  bool is_point_double() const override { return false; }
  OpenMesh::Vec3f normal(VertexHandle vh) const override {
    const Vec3f& n = mesh_.normals[index(vh)];
    return {n.x(), n.y(), n.z()};
  }
  OpenMesh::Vec3d normald(VertexHandle vh) const override { return OpenMesh::Vec3d(normal(vh)); }
  bool is_normal_double() const override { return false; }
  OpenMesh::Vec3uc color(VertexHandle vh) const override {
    const OpenMesh::Vec4uc c = colorA(vh);
    return {c[0], c[1], c[2]};
  }
  OpenMesh::Vec4uc colorA(VertexHandle vh) const override { return to_bytes(mesh_.colors[index(vh)]); }
  OpenMesh::Vec3ui colori(VertexHandle vh) const override { return OpenMesh::Vec3ui(color(vh)); }
  OpenMesh::Vec4ui colorAi(VertexHandle vh) const override { return OpenMesh::Vec4ui(colorA(vh)); }
  OpenMesh::Vec3f colorf(VertexHandle vh) const override {
    const Vec4f& c = mesh_.colors[index(vh)];
    return {c[0], c[1], c[2]};
  }
  OpenMesh::Vec4f colorAf(VertexHandle vh) const override {
    const Vec4f& c = mesh_.colors[index(vh)];
    return {c[0], c[1], c[2], c[3]};
  }
  OpenMesh::Vec2f texcoord(VertexHandle vh) const override {
    const Vec2f& t = mesh_.texcoords[index(vh)];
    return {t.x(), t.y()};
  }

  unsigned int get_vhandles(FaceHandle fh, std::vector<VertexHandle>& corners) const override {
    corners.clear();
    for (std::uint32_t v : mesh_.triangles[static_cast<std::size_t>(fh.idx())])
      corners.emplace_back(static_cast<int>(v));
    return 3;
  }
  // STL stores one normal per facet.
  OpenMesh::Vec3f normal(FaceHandle fh) const override {
    const Triangle& t = mesh_.triangles[static_cast<std::size_t>(fh.idx())];
    const Vec3 n =
        (mesh_.positions[t[1]] - mesh_.positions[t[0]]).cross(mesh_.positions[t[2]] - mesh_.positions[t[0]]);
    const double length = n.norm();
    if (length == 0.0) return {0.0f, 0.0f, 0.0f};
    return {static_cast<float>(n.x() / length), static_cast<float>(n.y() / length),
            static_cast<float>(n.z() / length)};
  }
  OpenMesh::Vec3d normald(FaceHandle fh) const override { return OpenMesh::Vec3d(normal(fh)); }

  // The PLY writer lists the kernel's custom properties: an empty kernel has none (nullptr would crash it).
  const OpenMesh::BaseKernel* kernel() override { return &kernel_; }
  size_t n_vertices() const override { return mesh_.positions.size(); }
  size_t n_faces() const override { return mesh_.triangles.size(); }
  size_t n_edges() const override { return 0; }
  bool is_triangle_mesh() const override { return true; }
  bool has_vertex_normals() const override { return how_.normals; }
  bool has_vertex_colors() const override { return how_.colors; }
  bool has_vertex_texcoords() const override { return how_.texcoords; }

  // Data our meshes do not have.
  OpenMesh::Vec2f texcoord(HalfedgeHandle) const override { return {0.0f, 0.0f}; }
  StatusInfo status(VertexHandle) const override { return {}; }
  HalfedgeHandle getHeh(FaceHandle, VertexHandle) const override { return HalfedgeHandle(); }
  unsigned int get_face_texcoords(std::vector<OpenMesh::Vec2f>&) const override { return 0; }
  int get_halfedge_id(VertexHandle) override { return -1; }
  int get_halfedge_id(FaceHandle) override { return -1; }
  int get_next_halfedge_id(HalfedgeHandle) override { return -1; }
  int get_to_vertex_id(HalfedgeHandle) override { return -1; }
  int get_face_id(HalfedgeHandle) override { return -1; }
  StatusInfo status(HalfedgeHandle) const override { return {}; }

private:
  static std::size_t index(VertexHandle vh) { return static_cast<std::size_t>(vh.idx()); }

  const Mesh& mesh_;
  OpenMeshWrite how_;
  OpenMesh::BaseKernel kernel_;
};

// Runs one OpenMesh read or write, `call` (which returns OpenMesh's success flag): alone, as OpenMesh needs,
// with its log and its exceptions caught. Nothing on success; else why it failed (the exception's message,
// or `failed` when it only returned false) with what OpenMesh logged.
template <class Call> std::optional<std::string> run_openmesh(std::string_view failed, Call&& call) {
  capture_openmesh_log();
  bool ok = false;
  std::string log;
  std::string failure;
  {
    const std::scoped_lock lock(openmesh_mutex());
    (void)take_openmesh_log(); // drop what earlier OpenMesh users on this thread left
    try {
      ok = call();
    } catch (const std::exception& e) {
      failure = e.what();
    }
    log = take_openmesh_log();
  }
  if (failure.empty() && ok) return std::nullopt;
  const std::string why = failure.empty() ? std::string(failed) : failure;
  return log.empty() ? why : fmt::format("{} (OpenMesh: {})", why, log);
}

} // namespace

Result<Mesh> read_openmesh(std::string bytes, const OpenMeshRead& how, std::string_view source,
                           Notes* notes) {
  SoupImporter importer(bytes.size());
  OpenMesh::IO::Options options =
      OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexColor |
      OpenMesh::IO::Options::VertexTexCoord | OpenMesh::IO::Options::ColorAlpha |
      OpenMesh::IO::Options::FaceColor; // only to note that face colours are dropped
  std::istringstream in(std::move(bytes));
  const std::optional<std::string> failed = run_openmesh("OpenMesh could not read the data", [&] {
    const bool ok = OpenMesh::IO::IOManager().read(in, std::string(how.extension), importer, options);
    importer.finish();
    return ok;
  });
  if (failed) return make_error(ErrorCode::Malformed, *failed, std::string(source));
  if (importer.invalid_faces != 0)
    return make_error(ErrorCode::IndexOutOfRange,
                      fmt::format("{} faces refer to vertices that do not exist", importer.invalid_faces),
                      std::string(source));
  if (notes && importer.short_faces != 0)
    notes->push_back(
        fmt::format("{}: {} faces with fewer than 3 corners skipped", source, importer.short_faces));
  if (notes && importer.face_colors)
    notes->push_back(fmt::format("{}: face colours dropped: meshes hold vertex colours only", source));
  if (Result<void> valid = validate(importer.mesh, source); !valid) return std::move(valid).error();
  // An empty mesh is read from no file and written by no writer (`check_writable`).
  if (importer.mesh.positions.empty())
    return make_error(ErrorCode::Empty, "no vertices in the file", std::string(source));
  return std::move(importer.mesh);
}

Result<std::string> write_openmesh(const Mesh& mesh, const OpenMeshWrite& how, std::string_view format,
                                   Notes* notes) {
  auto note_dropped = [&](bool present, bool written, std::string_view what) {
    if (notes && present && !written)
      notes->push_back(fmt::format("{} dropped: {} cannot store them", what, format));
  };
  note_dropped(mesh.has_normals(), how.normals, "normals");
  note_dropped(mesh.has_colors(), how.colors, "vertex colours");
  note_dropped(mesh.has_texcoords(), how.texcoords, "texture coordinates");
  MeshExporter exporter(mesh, how);
  OpenMesh::IO::Options options;
  if (how.binary) options += OpenMesh::IO::Options::Binary;
  if (how.binary) options += OpenMesh::IO::Options::LSB;
  if (how.normals) options += OpenMesh::IO::Options::VertexNormal;
  if (how.colors) options += OpenMesh::IO::Options::VertexColor;
  if (how.alpha) options += OpenMesh::IO::Options::ColorAlpha;
  if (how.texcoords) options += OpenMesh::IO::Options::VertexTexCoord;
  if (how.texcoords) options += OpenMesh::IO::Options::TexCoordST;
  std::ostringstream out;
  const std::optional<std::string> failed = run_openmesh("OpenMesh could not write the mesh", [&] {
    constexpr std::streamsize kDigits = 9; // a float32 printed with 9 digits reads back exactly
    return OpenMesh::IO::IOManager().write(out, std::string(how.extension), exporter, options, kDigits);
  });
  if (failed) return make_error(ErrorCode::Io, *failed);
  return std::move(out).str();
}

} // namespace pdeface::openmesh_io
