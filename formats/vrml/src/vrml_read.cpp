// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/vrml/vrml.hpp"
namespace pdeface::vrml {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "VRML reader not built yet", std::string(source));
}
} // namespace pdeface::vrml
