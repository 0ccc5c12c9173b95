#pragma once
//! \file
//! Plane–mesh intersection: triangle–plane segments chained into polylines.
//!
//! Vertices are classified by the sign of their signed distance with an exact zero, so a vertex lying on
//! a plane is one polyline point (keyed by the vertex), never two; an edge crossing is keyed by its edge,
//! so the two triangles that share it produce one point. For axis-aligned planes (`normal` a unit axis)
//! the signed distances are exact and every point lies exactly on the plane.

#include "pdeface/core/geometry.hpp"
#include "pdeface/core/mesh.hpp"

#include <span>
#include <vector>

namespace pdeface::slice {

//! A plane n · p = offset (n of unit length).
using Plane = pdeface::Plane;

//! A connected piece of a plane's intersection with a mesh.
using Polyline = pdeface::Polyline;

//! The intersection of `mesh` with one plane, in any orientation. Triangles lying in the plane add
//! nothing themselves; their edges come from the neighbours that leave the plane. A mesh edge lying in
//! the plane appears once however many triangles share it.
[[nodiscard]] std::vector<Polyline> intersect(const Mesh& mesh, const Plane& plane);

//! The intersections of `mesh` with any planes, in one pass over the mesh: planes that share a normal
//! are bucketed by offset, so that each triangle is cut only by the planes its extent spans. Result `j`
//! belongs to `planes[j]`.
//! \throw std::invalid_argument when a normal is not of unit length or an offset is not finite.
[[nodiscard]] std::vector<std::vector<Polyline>> intersect(const Mesh& mesh, std::span<const Plane> planes);

//! The intersections of `mesh` with the parallel planes `normal · p = offsets[j]` (any order), in one
//! pass over the mesh: each triangle goes only to the planes its extent along `normal` spans. Result `j`
//! belongs to `offsets[j]`.
//! \throw std::invalid_argument when `normal` is not of unit length or an offset is not finite.
[[nodiscard]] std::vector<std::vector<Polyline>> intersect(const Mesh& mesh, const Vec3& normal,
                                                           std::span<const double> offsets);

} // namespace pdeface::slice
