// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/vrml/vrml.hpp"
namespace pdeface::vrml {
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "VRML writer not built yet");
}
} // namespace pdeface::vrml
