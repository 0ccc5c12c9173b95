// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/draco/draco.hpp"
namespace pdeface::draco {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "Draco reader not built yet", std::string(source));
}
Result<void> check(const WriteOptions&) { return {}; }
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "Draco writer not built yet");
}
} // namespace pdeface::draco
