#pragma once
// The error of a decoded variant as colours: on its vertices (a GLB for any glTF viewer) and as a picture
// from the front (for the report's page).

#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/report.hpp"

#include <Eigen/Core>

#include <string>

namespace pdeface::pipeline::detail {

//! sRGB of a distance on the scale 0 (blue) … `scale_mm` (red), clamped.
[[nodiscard]] Eigen::Vector3f heat_colour(double distance_mm, double scale_mm);
//! Where nothing is judged (outside the face mask).
inline const Eigen::Vector3f kUnjudged{0.78F, 0.78F, 0.78F};

//! `mesh` (canonical frame, mm) coloured by each vertex's distance to the scan, as a GLB, and its front
//! view coloured the same way.
[[nodiscard]] HeatMap heat_map(const Mesh& mesh, const metrics::FaceYardstick& yardstick, double scale_mm,
                               const std::string& variant, const std::string& file);

} // namespace pdeface::pipeline::detail
