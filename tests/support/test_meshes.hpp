#pragma once
// Meshes the tests and benchmarks make: small ones by hand, and larger ones from a scan. No GoogleTest
// here, so that the benchmarks can use them too.

#include "pdeface/core/mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

namespace pdeface::test {

//! Two triangles forming the unit square in the z = 0 plane, counter-clockwise seen from +z.
inline Mesh unit_square() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

//! `m` with each triangle split in four at its edge midpoints (positions and triangles only).
inline Mesh subdivided(const Mesh& m) {
  Mesh out;
  out.positions = m.positions;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
  auto mid = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, fresh] =
        middle.emplace(std::minmax(a, b), static_cast<std::uint32_t>(out.positions.size()));
    if (fresh) out.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
    return it->second;
  };
  for (const Triangle& t : m.triangles) {
    const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

} // namespace pdeface::test
