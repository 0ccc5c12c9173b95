#include "pdeface/pipeline/preview.hpp"

#include "pdeface/svg/svg.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace pdeface::pipeline {
namespace {

std::string path_of(const std::vector<Eigen::Vector2d>& points, double dx, bool closed) {
  std::string d;
  for (std::size_t i = 0; i < points.size(); ++i)
    d += fmt::format("{}{:.2f},{:.2f} ", i == 0 ? "M" : "L", dx + points[i].x(), -points[i].y());
  return d + (closed ? "Z" : "");
}

} // namespace

std::string reconstruction_preview_svg(const Mesh& scan, const Mesh& reconstruction,
                                       const slice::ProfileSet& profiles, const PreviewOptions& options) {
  const slice::FaceMask& mask = profiles.mask;
  const double half = std::max(mask.half_width * 1.35, profiles.border_mm + 15.0);
  const double y0 = mask.centre_y - mask.half_height * 1.3, y1 = mask.centre_y + mask.half_height * 1.2;
  const double panel = 2.0 * half, gap = 8.0;
  const double width = 3.0 * panel + 2.0 * gap, height = (y1 - y0) + 14.0;
  std::string doc =
      fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.1f} {:.1f} {:.1f} {:.1f}\" "
                  "width=\"{:.0f}\" height=\"{:.0f}\" font-family=\"sans-serif\">\n"
                  "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"white\"/>\n",
                  -half, -y1, width, height, 2.5 * width, 2.5 * height, -half, -y1, width, height);
  auto view = [&](const Mesh& mesh, double dx) {
    const svg::FrontViewBox box{-half, half, y0, y1, options.pixel_mm};
    return fmt::format("<g transform=\"translate({:.2f},0)\">{}</g>\n", dx, svg::front_view_image(mesh, box));
  };
  // Scan, with the face mask dashed.
  doc += view(scan, 0.0);
  std::vector<Eigen::Vector2d> ellipse;
  for (int k = 0; k < 120; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 120.0;
    ellipse.emplace_back(mask.half_width * std::cos(t), mask.centre_y + mask.half_height * std::sin(t));
  }
  doc += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"0.6\" "
                     "stroke-dasharray=\"3 2\"/>\n",
                     path_of(ellipse, 0.0, true));
  // Reconstruction, with the curves' region and their filled stretches.
  const double dx = panel + gap;
  doc += view(reconstruction, dx);
  std::vector<Eigen::Vector2d> outline;
  for (const slice::ProfileCurve& c : profiles.curves)
    outline.emplace_back(c.x, c.extent[0]);
  for (auto c = profiles.curves.rbegin(); c != profiles.curves.rend(); ++c)
    outline.emplace_back(c->x, c->extent[1]);
  doc += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"0.5\"/>\n",
                     path_of(outline, dx, true));
  for (const slice::ProfileCurve& c : profiles.curves)
    for (const auto& h : c.holes)
      doc += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"#ff7f0e\" stroke-width=\"0.9\"/>\n",
                         path_of({{c.x, h[0]}, {c.x, h[1]}}, dx, false));
  // The reconstruction turned to its left (its right cheek towards the viewer).
  const double turn = options.turn_deg * std::numbers::pi / 180.0;
  Mesh turned = reconstruction;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Vec3::UnitY()).toRotationMatrix();
  for (Vec3& p : turned.positions)
    p = r * p;
  doc += view(turned, 2.0 * dx);
  doc += fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"4.5\">scan (face mask dashed)</text>\n"
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"4.5\">reconstruction (curves' region red, filled holes "
      "orange)</text>\n"
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"4.5\">reconstruction turned {:.0f} degrees</text>\n",
      -half + 2, -y1 + 6, dx - half + 2, -y1 + 6, 2 * dx - half + 2, -y1 + 6, options.turn_deg);
  doc += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"5\">{}</text>\n</svg>\n", -half + 2,
                     -y0 + 9, svg::escape(options.title));
  return doc;
}

} // namespace pdeface::pipeline
