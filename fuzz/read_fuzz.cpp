// libFuzzer target for one reader (PDEFACE_FUZZ_FORMAT, set per target in fuzz/CMakeLists.txt): whatever
// the bytes, reading gives a valid mesh no larger than the bytes justify or one clean error, never a crash,
// undefined behaviour, a hang or an unbounded allocation; and a mesh it reads, written again in the same
// format, reads back (fuzz/checks.hpp).

#include "checks.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

using pdeface::formats::Format;

constexpr Format kFormat = Format::PDEFACE_FUZZ_FORMAT;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fuzz = pdeface::fuzz;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz" + std::string(pdeface::formats::info(kFormat).extensions.front());
  pdeface::Notes notes;
  const pdeface::Result<pdeface::formats::LoadedMesh> read =
      pdeface::formats::read_mesh(bytes, source, {.format = kFormat}, &notes);
  fuzz::check_notes(notes);
  if (!read) {
    fuzz::check_error(read.error(), size);
    return 0;
  }
  fuzz::check_mesh(read->mesh, size);
  if (pdeface::formats::info(kFormat).writable) fuzz::round_trip(read->mesh, kFormat);
  return 0;
}
