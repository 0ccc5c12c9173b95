#include "pdeface/slice/face_mask.hpp"

#include "detail.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pdeface::slice {

using align::Landmark;

std::optional<std::array<double, 2>> FaceMask::heights_at(double x) const {
  const double u = x / half_width;
  if (!(std::abs(u) < 1.0)) return std::nullopt;
  const double h = half_height * std::sqrt(1.0 - u * u);
  return std::array<double, 2>{centre_y - h, centre_y + h};
}

FaceMask FaceMask::grown(double across, double along) const {
  FaceMask out = *this;
  out.half_width *= across;
  out.half_height *= along;
  return out;
}

Result<FaceMask> face_mask(const align::Landmarks& l, const FaceMaskOptions& options) {
  if (auto ok = detail::require_landmarks(l,
                                          {Landmark::NoseTip, Landmark::EyeOuterLeft, Landmark::EyeOuterRight,
                                           Landmark::FaceTop, Landmark::FaceBottom},
                                          "the face mask");
      !ok)
    return ok.error();
  const double bottom = l[Landmark::FaceBottom]->y(), top = l[Landmark::FaceTop]->y();
  const double eye_y = 0.5 * (l[Landmark::EyeOuterLeft]->y() + l[Landmark::EyeOuterRight]->y());
  const double eye_x =
      0.5 * (std::abs(l[Landmark::EyeOuterLeft]->x()) + std::abs(l[Landmark::EyeOuterRight]->x()));
  FaceMask mask;
  mask.centre_y = 0.5 * (bottom + top);
  mask.half_height = 0.5 * (top - bottom);
  const double w = mask.half_height > 0.0 ? (eye_y - mask.centre_y) / mask.half_height : 1.0;
  if (!(mask.half_height > 0.0) || !(std::abs(w) < 0.95) || !(eye_x > 0.0))
    return make_error(
        ErrorCode::NoFace,
        fmt::format("the landmarks make no face outline: the chin at y = {:.1f} mm, the forehead "
                    "at y = {:.1f} mm and the outer eye corners at y = {:.1f} mm, |x| = {:.1f} mm",
                    bottom, top, eye_y, eye_x));
  mask.half_width = options.beyond_outer_corners * eye_x / std::sqrt(1.0 - w * w);
  mask.min_z = l[Landmark::NoseTip]->z() - options.depth_fraction * (top - bottom);
  return mask;
}

} // namespace pdeface::slice
