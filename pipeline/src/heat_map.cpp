#include "heat_map.hpp"

#include "pdeface/formats/formats.hpp"
#include "pdeface/svg/svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace pdeface::pipeline::detail {

Eigen::Vector3f heat_colour(double distance_mm, double scale_mm) {
  // Blue, cyan, green-yellow, orange, red: ordered by lightness and hue, readable on a shaded face.
  static const std::array<Eigen::Vector3f, 5> kStops{
      Eigen::Vector3f{0.16F, 0.33F, 0.80F}, Eigen::Vector3f{0.15F, 0.70F, 0.85F},
      Eigen::Vector3f{0.56F, 0.82F, 0.27F}, Eigen::Vector3f{0.98F, 0.65F, 0.14F},
      Eigen::Vector3f{0.80F, 0.08F, 0.10F}};
  const double t = std::clamp(distance_mm / scale_mm, 0.0, 1.0) * (kStops.size() - 1);
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(t), kStops.size() - 2);
  const auto f = static_cast<float>(t - static_cast<double>(i));
  return (1.0F - f) * kStops[i] + f * kStops[i + 1];
}

HeatMap heat_map(const Mesh& mesh, const metrics::FaceYardstick& yardstick, double scale_mm,
                 const std::string& variant, const std::string& file) {
  const slice::FaceMask& mask = yardstick.mask();
  const auto colour = [&](const Vec3& p) -> Eigen::Vector3f {
    return mask.contains(p) ? heat_colour(yardstick.distance_to_scan(p), scale_mm) : kUnjudged;
  };
  // glTF's COLOR_0 is linear: the sRGB colours are converted so that viewers show them as on the page,
  // and rounded to bytes (the writer then stores them as normalised bytes).
  Mesh coloured;
  coloured.positions = mesh.positions;
  coloured.triangles = mesh.triangles;
  coloured.units = Units::Millimetres;
  coloured.name = variant + " (error heat map, 0-" + fmt::format("{:g}", scale_mm) + " mm)";
  coloured.colors.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) {
    const Eigen::Vector3f srgb = colour(p);
    Vec4f linear = Vec4f::Ones();
    for (int k = 0; k < 3; ++k)
      linear[k] = std::round(255.0F * std::pow(srgb[k], 2.2F)) / 255.0F;
    coloured.colors.push_back(linear);
  }
  HeatMap out{.variant = variant, .file = file, .scale_mm = scale_mm};
  Result<std::string> glb = formats::encode_mesh(coloured, file, {.format = formats::Format::Glb});
  if (glb) out.glb = *std::move(glb);
  const svg::FrontViewBox box{
      -1.25 * mask.half_width, 1.25 * mask.half_width, mask.centre_y - 1.15 * mask.half_height,
      mask.centre_y + 1.15 * mask.half_height, 0.6}; // about a pixel of the page, which shows 1.5 px per mm
  out.front_svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.1f} {:.1f} {:.1f} {:.1f}\" width=\"{:.0f}\" "
      "height=\"{:.0f}\">\n{}</svg>\n",
      box.x0, -box.y1, box.x1 - box.x0, box.y1 - box.y0, 1.5 * (box.x1 - box.x0), 1.5 * (box.y1 - box.y0),
      svg::front_view_image(mesh, box, colour));
  return out;
}

} // namespace pdeface::pipeline::detail
