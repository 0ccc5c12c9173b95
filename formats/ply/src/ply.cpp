// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/ply/ply.hpp"
namespace pdeface {
namespace ply {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "PLY reader not built yet", std::string(source));
}
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "PLY writer not built yet");
}
} // namespace ply
namespace off {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "OFF reader not built yet", std::string(source));
}
Result<std::string> write(const Mesh&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "OFF writer not built yet");
}
} // namespace off
namespace stl {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "STL reader not built yet", std::string(source));
}
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "STL writer not built yet");
}
} // namespace stl
} // namespace pdeface
