#include "pdeface/core/openmesh.hpp"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <mutex>

namespace pdeface {
namespace {

// What OpenMesh logged on this thread since the last `take_openmesh_log()`. OpenMesh hands each finished
// log line to its targets on the thread that wrote it, so a thread-local buffer collects exactly one
// caller's lines.
thread_local std::string tl_log;
constexpr std::size_t kMaxLog = 4096; // a thread that never takes its log must not grow it without bound

struct LogSink {
  LogSink& operator<<(const std::string& line) {
    if (tl_log.size() < kMaxLog) tl_log += line;
    return *this;
  }
};

} // namespace

void capture_openmesh_log() {
  static std::once_flag once;
  std::call_once(once, [] {
    static LogSink sink;
    ::omerr().disconnect(std::cerr);
    ::omlog().disconnect(std::clog);
    ::omout().disconnect(std::cout);
    ::omerr().connect(sink);
    ::omlog().connect(sink);
    ::omout().connect(sink);
  });
}

std::string take_openmesh_log() {
  std::string log;
  log.swap(tl_log);
  while (!log.empty() && std::isspace(static_cast<unsigned char>(log.back())))
    log.pop_back();
  std::ranges::replace(log, '\n', ' ');
  return log;
}

HalfedgeConversion to_halfedge_mesh(const Mesh& mesh) {
  capture_openmesh_log(); // add_face complains about every non-manifold triangle: we count them instead
  HalfedgeConversion out;
  HalfedgeMesh& om = out.mesh;
  om.reserve(mesh.positions.size(), 3 * mesh.triangles.size() / 2, mesh.triangles.size());
  for (const Vec3& p : mesh.positions)
    om.add_vertex(HalfedgeMesh::Point(p.x(), p.y(), p.z()));
  for (const Triangle& t : mesh.triangles) {
    const auto face = om.add_face(om.vertex_handle(t[0]), om.vertex_handle(t[1]), om.vertex_handle(t[2]));
    if (!face.is_valid()) ++out.rejected_triangles;
  }
  (void)take_openmesh_log();
  return out;
}

Mesh from_halfedge_mesh(const HalfedgeMesh& om) {
  Mesh mesh;
  std::vector<std::uint32_t> index(om.n_vertices(), 0);
  mesh.positions.reserve(om.n_vertices());
  for (auto v : om.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(mesh.positions.size());
    const auto& p = om.point(v);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  mesh.triangles.reserve(om.n_faces());
  for (auto f : om.faces()) {
    Triangle t{};
    int i = 0;
    for (auto v : f.vertices())
      t[i++] = index[v.idx()];
    mesh.triangles.push_back(t);
  }
  return mesh;
}

} // namespace pdeface
