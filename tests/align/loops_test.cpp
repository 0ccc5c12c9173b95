// The mesh's boundaries inside align (modules/align/src/search.hpp) against their definition: the
// connected pieces of the edges that one triangle only has.

#include "search.hpp"

#include "pdeface/core/sample_face.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace pdeface::align::detail {
namespace {

Loops brute_loops(const std::vector<Triangle>& triangles) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k)
      ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  std::map<std::uint32_t, std::set<std::uint32_t>> next;
  for (const auto& [edge, count] : uses)
    if (count == 1) {
      next[edge.first].insert(edge.second);
      next[edge.second].insert(edge.first);
    }
  Loops loops;
  std::set<std::uint32_t> seen;
  for (const auto& [start, unused] : next) {
    if (seen.contains(start)) continue;
    std::vector<std::uint32_t> loop, stack{start};
    seen.insert(start);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      loop.push_back(v);
      for (std::uint32_t w : next[v])
        if (seen.insert(w).second) stack.push_back(w);
    }
    std::ranges::sort(loop);
    loops.push_back(loop);
  }
  std::ranges::sort(loops, {}, [](const auto& l) { return l.front(); });
  return loops;
}

TEST(BoundaryLoops, AreTheirDefinitionWithHolesAndDegenerateTriangles) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  std::vector<Triangle> triangles;
  // Holes: every 97th triangle and a band of them left out; a few degenerate and repeated ones added.
  for (std::size_t i = 0; i < face.triangles.size(); ++i)
    if (i % 97 != 0 && (i < 400 || i > 430)) triangles.push_back(face.triangles[i]);
  triangles.push_back({5, 5, 9});
  triangles.push_back(face.triangles[3]);
  const Loops loops = boundary_loops(triangles);
  EXPECT_EQ(loops, brute_loops(triangles));
  EXPECT_GT(loops.size(), 10U);
  EXPECT_TRUE(boundary_loops({}).empty());
}

} // namespace
} // namespace pdeface::align::detail
