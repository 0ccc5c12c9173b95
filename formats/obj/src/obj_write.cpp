// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/obj/obj.hpp"
namespace pdeface::obj {
Result<std::string> write(const Mesh&, const WriteOptions&, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "OBJ writer not built yet");
}
} // namespace pdeface::obj
