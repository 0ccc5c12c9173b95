// Placeholder until the format lands; returns an error so callers see it is missing.
#include "pdeface/obj/obj.hpp"
namespace pdeface::obj {
Result<Mesh> read(std::string_view, std::string_view source, Notes*) {
  return make_error(ErrorCode::UnsupportedFormat, "OBJ reader not built yet", std::string(source));
}
} // namespace pdeface::obj
