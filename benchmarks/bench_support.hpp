#pragma once
// What every benchmark shares: where the real scans are.

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace pdeface::bench {

//! A scan of the faces folder: `$PDEFACE_DATA`, else the folder the build was configured with
//! (default ../shared/faces). The benchmarks that need it say so and skip when it is missing.
inline std::filesystem::path face(std::string_view name) {
  const char* env = std::getenv("PDEFACE_DATA");
  const std::filesystem::path dir = env && *env ? env : PDEFACE_DEFAULT_FACES;
  return dir / name;
}

} // namespace pdeface::bench
