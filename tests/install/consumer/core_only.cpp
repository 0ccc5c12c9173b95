// pdeface::core alone: the mesh type and the sample face.

#include "pdeface/core/sample_face.hpp"

#include <cstdio>

int main() {
  const pdeface::Mesh face = pdeface::sample_face();
  std::printf("%zu vertices\n", face.vertex_count());
  return face.vertex_count() > 1000 ? 0 : 1;
}
