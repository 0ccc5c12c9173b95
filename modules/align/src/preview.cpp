#include "pdeface/align/preview.hpp"

#include "pdeface/svg/svg.hpp"

#include <fmt/format.h>

namespace pdeface::align {

std::string preview_svg(const Mesh& scan, const FaceFrame& frame, const Landmarks& landmarks,
                        const PreviewOptions& options) {
  const Mesh face = to_canonical(scan, frame);
  constexpr double kX0 = -110.0, kX1 = 110.0, kY0 = -150.0, kY1 = 130.0; // mm around the nose tip
  const double width_mm = kX1 - kX0, height_mm = kY1 - kY0;
  std::string doc = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{} {} {} {}\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\">\n",
      kX0, -kY1, width_mm, height_mm + 14, 2 * width_mm, 2 * (height_mm + 14));
  doc += svg::front_view_image(face, {kX0, kX1, kY0, kY1, options.pixel_mm});
  doc += fmt::format("<line x1=\"0\" y1=\"{}\" x2=\"0\" y2=\"{}\" stroke=\"#1f77b4\" stroke-width=\"0.6\" "
                     "stroke-dasharray=\"3 2\"/>\n",
                     -kY1, -kY0);
  const Landmarks canonical = to_canonical(landmarks, frame);
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    if (!canonical.points[i]) continue;
    const Vec3& p = *canonical.points[i];
    const bool midline = mirrored(static_cast<Landmark>(i)) == static_cast<Landmark>(i);
    doc += fmt::format(
        "<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"2\" fill=\"{}\" stroke=\"white\" stroke-width=\"0.5\"/>\n",
        p.x(), -p.y(), midline ? "#d62728" : "#ff7f0e");
    doc += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"4\" fill=\"#d62728\">{}</text>\n",
                       p.x() + 3, -p.y() - 2, name(static_cast<Landmark>(i)));
  }
  doc += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"6\">{}</text>\n</svg>\n", kX0 + 3, -kY0 + 10,
                     svg::escape(options.title));
  return doc;
}

} // namespace pdeface::align
