// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/gltf/gltf.hpp"
namespace pdeface::gltf {
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "glTF writer not built yet");
}
} // namespace pdeface::gltf
