// libFuzzer target for the whole path: bytes of any format (chosen by their content) -> a mesh -> every
// writer, each read back by its reader -> the mesh encoded as a `.pdef` (landmark detection, slicing, the
// PDE) -> decoded. Whatever the bytes and the coordinates: no crash, no undefined behaviour, bounded time and
// memory, and what a writer writes, its reader reads (fuzz/checks.hpp).

#include "checks.hpp"

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pipeline/encode.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

namespace fuzz = pdeface::fuzz;
namespace formats = pdeface::formats;

// Detection and slicing are bounded whatever the input, but take a second or more on a whole scan: larger
// meshes are only converted, so that the fuzzer keeps its pace (scans are what the integration tests run).
constexpr std::size_t kMaxEncodedVertices = 3000;

void encode_and_decode(const pdeface::Mesh& mesh) {
  pdeface::pipeline::EncodeRequest request;
  request.name = mesh.name; // any bytes: the encoder makes them valid UTF-8
  request.source = "fuzz";
  const pdeface::Result<pdeface::pipeline::EncodeOutcome> made =
      pdeface::pipeline::encode_request(mesh, request);
  if (!made) return fuzz::check_error(made.error(), SIZE_MAX);
  const std::string& bytes = made->encoded.bytes;
  const pdeface::Result<pdeface::pdef::Face> face = pdeface::pdef::decode(bytes, "fuzz.pdef");
  if (!face) fuzz::broken("encode writes a .pdef that decode cannot read: " + face.error().to_string());
  const pdeface::Result<pdeface::Mesh> surface =
      pdeface::pdef::to_mesh(*face, pdeface::pdef::Resolution{20, 20});
  if (!surface) fuzz::broken("a decoded .pdef gives no surface: " + surface.error().to_string());
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  pdeface::Notes notes;
  const pdeface::Result<formats::LoadedMesh> read = formats::read_mesh(bytes, "fuzz", {}, &notes);
  fuzz::check_notes(notes);
  if (!read) {
    fuzz::check_error(read.error(), size);
    return 0;
  }
  const pdeface::Mesh& mesh = read->mesh;
  fuzz::check_mesh(mesh, size);
  for (const formats::FormatInfo& f : formats::all_formats())
    if (f.writable) fuzz::round_trip(mesh, f.format);
  fuzz::round_trip(mesh, formats::Format::Ply, {.ascii = true});
  fuzz::round_trip(mesh, formats::Format::Stl, {.ascii = true});
  fuzz::round_trip(mesh, formats::Format::Glb, {.draco_in_gltf = true});
  fuzz::round_trip(mesh, formats::Format::Draco, {.draco_level = 0});
  if (mesh.vertex_count() <= kMaxEncodedVertices) encode_and_decode(mesh);
  return 0;
}
