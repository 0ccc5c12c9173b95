// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/gltf/gltf.hpp"
namespace pdeface::gltf {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "glTF reader not built yet", std::string(source));
}
} // namespace pdeface::gltf
