#pragma once
//! \file
//! Geometry every module shares: planes and polylines.

#include "pdeface/core/mesh.hpp"

#include <vector>

namespace pdeface {

//! A plane n · p = offset (n of unit length).
struct Plane {
  Vec3 normal = Vec3::UnitX();
  double offset = 0.0;
};

//! A connected chain of points, e.g. a piece of a plane's intersection with a mesh.
struct Polyline {
  std::vector<Vec3> points;
  bool closed = false; //!< the last point joins the first (not repeated)
};

} // namespace pdeface
