#pragma once
//! \file
//! The one place where our `Mesh` becomes an OpenMesh half-edge mesh, for modules that need topology.

#include "pdeface/core/mesh.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <string>

namespace pdeface {

struct OpenMeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3f;
};
using HalfedgeMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

//! A half-edge mesh built from a `Mesh`. OpenMesh cannot represent non-manifold configurations (an edge
//! shared by three triangles, a vertex joining two fans); such triangles are left out and counted.
struct HalfedgeConversion {
  HalfedgeMesh mesh;                  //!< vertex i is OpenMesh vertex i
  std::size_t rejected_triangles = 0; //!< triangles OpenMesh could not add (non-manifold, degenerate)
};

[[nodiscard]] HalfedgeConversion to_halfedge_mesh(const Mesh& mesh);
//! Positions and triangles of a half-edge mesh (deleted elements skipped, indices compacted).
[[nodiscard]] Mesh from_halfedge_mesh(const HalfedgeMesh& mesh);

//! Routes OpenMesh's log streams (`omerr`, `omlog`, `omout`), which print to the terminal, into a
//! per-thread buffer instead: library code never prints. Process-wide and idempotent; every function
//! here that calls OpenMesh does it first.
void capture_openmesh_log();
//! What OpenMesh logged on this thread since the last call, as one line (for error messages).
[[nodiscard]] std::string take_openmesh_log();

} // namespace pdeface
