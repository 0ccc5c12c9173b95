// The method end to end through the installed package: the built-in sample face, detected, reconstructed,
// measured, written as GLB bytes.

#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pipeline/requests.hpp"

#include <cstdio>

int main() {
  const pdeface::Mesh scan = pdeface::sample_face();
  auto made = pdeface::pipeline::reconstruct_request(scan, {.source = "sample"});
  if (!made) {
    std::fprintf(stderr, "%s\n", made.error().to_string().c_str());
    return 1;
  }
  auto glb = pdeface::formats::encode_mesh(made->reconstruction.scan, "face.glb");
  if (!glb || !made->fidelity) return 1;
  std::printf("%zu curves, coverage %.3f, %zu GLB bytes\n", made->reconstruction.profiles.curves.size(),
              made->fidelity->coverage.share, glb->size());
  return made->fidelity->coverage.share > 0.9 ? 0 : 1;
}
