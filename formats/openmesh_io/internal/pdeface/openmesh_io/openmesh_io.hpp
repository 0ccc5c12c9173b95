#pragma once
// OpenMesh's IO as the PLY, OFF and STL code shares it (internal to formats/), made safe to call from any
// thread and silent: every call goes through one mutex (OpenMesh's readers and writers are global singletons
// that keep per-file state), its log streams are captured into our error messages, and meshes travel as
// polygon soups, never as half-edge meshes (which would reject or duplicate non-manifold faces and change
// the counts).
//
// The bytes handed to `read_openmesh` must already have passed the format's validator: OpenMesh's readers
// hang, crash or misread silently on malformed input (see third_party_notes/openmesh.md).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::openmesh_io {

struct OpenMeshRead {
  std::string_view extension; //!< "ply" or "off": picks OpenMesh's reader (STL is read by stl.cpp itself)
};

//! Reads validated bytes through OpenMesh into a mesh (polygons fan-triangulated, attributes the file
//! has kept). Faces with fewer than three corners are skipped with a note.
[[nodiscard]] Result<Mesh> read_openmesh(std::string bytes, const OpenMeshRead& how, std::string_view source,
                                         Notes* notes);

struct OpenMeshWrite {
  std::string_view extension; //!< "ply", "off" or "stl"
  bool binary = true;
  bool normals = false;   //!< write the mesh's vertex normals
  bool colors = false;    //!< write vertex colours as uchar
  bool alpha = false;     //!< ... with an alpha channel
  bool texcoords = false; //!< write texture coordinates (PLY: as s, t)
};

//! Writes a mesh through OpenMesh: positions and normals as float32, 9 significant digits in text.
//! Notes each attribute the mesh has but `how` does not write.
[[nodiscard]] Result<std::string> write_openmesh(const Mesh& mesh, const OpenMeshWrite& how,
                                                 std::string_view format, Notes* notes);

} // namespace pdeface::openmesh_io
