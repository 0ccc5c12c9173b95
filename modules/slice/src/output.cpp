#include "pdeface/slice/output.hpp"

#include "pdeface/svg/svg.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace pdeface::slice {
namespace {

nlohmann::json to_json(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json to_json(const std::vector<Vec3>& points) {
  nlohmann::json out = nlohmann::json::array();
  for (const Vec3& p : points)
    out.push_back(to_json(p));
  return out;
}

} // namespace

std::string write_profiles_json(const ProfileSet& set) {
  nlohmann::json j;
  j["format"] = "pdeface-profiles";
  j["version"] = 1;
  j["units"] = "mm";
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({set.frame.rotation(r, 0), set.frame.rotation(r, 1), set.frame.rotation(r, 2)});
  j["to_canonical"] = {{"rotation", rows},
                       {"translation_mm", to_json(set.frame.translation)},
                       {"scale_mm_per_unit", set.frame.scale},
                       {"scan_units", to_string(set.frame.scan_units)}};
  j["height_range"] = {set.height_range[0], set.height_range[1]};
  j["border"] = set.border_mm;
  j["border_right_left"] = {set.border[0], set.border[1]};
  j["face_mask"] = {{"centre_y", set.mask.centre_y},
                    {"half_width", set.mask.half_width},
                    {"half_height", set.mask.half_height},
                    {"min_z", set.mask.min_z}};
  j["mask_coverage"] = set.mask_coverage;
  j["max_hole"] = set.max_hole_mm;
  j["filled_fraction"] = set.filled_fraction;
  j["missing"] = set.missing;
  j["central_width"] = set.central_width_mm;
  j["eye_height"] = set.eye_height_mm;
  j["parameter"] = to_string(set.parameter);
  j["sampling"] = to_string(set.sampling);
  j["sampling_ratio"] = set.ratio;
  j["points_per_curve"] = set.k;
  j["reference_points"] = set.reference_points;
  j["raw_points"] = set.raw_points;
  j["point_cloud"] = set.point_cloud;
  if (set.point_cloud) j["point_spacing"] = set.spacing_mm;
  nlohmann::json curves = nlohmann::json::array();
  for (const ProfileCurve& c : set.curves) {
    nlohmann::json holes = nlohmann::json::array(), filled = nlohmann::json::array();
    for (const auto& h : c.holes)
      holes.push_back({h[0], h[1]});
    for (std::size_t k = 0; k < c.filled.size(); ++k)
      if (c.filled[k]) filled.push_back(k);
    curves.push_back({{"index", c.index},
                      {"x", c.x},
                      {"role", to_string(c.role)},
                      {"feature", c.feature},
                      {"extent", {c.extent[0], c.extent[1]}},
                      {"ends", {to_string(c.ends[0]), to_string(c.ends[1])}},
                      {"raw_points", c.raw.size()},
                      {"surface_points", c.surface_points},
                      {"holes", std::move(holes)},
                      {"filled", std::move(filled)},
                      {"points", to_json(c.points)}});
  }
  j["curves"] = std::move(curves);
  nlohmann::json evaluation = nlohmann::json::array();
  for (const EvaluationProfile& e : set.evaluation)
    evaluation.push_back({{"name", e.name},
                          {"plane", {{"normal", to_json(e.plane.normal)}, {"offset", e.plane.offset}}},
                          {"along", to_json(e.along)},
                          {"gaps", e.gaps},
                          {"points", to_json(e.points)}});
  j["evaluation"] = std::move(evaluation);
  return j.dump(1) + "\n";
}

std::string profiles_svg(const Mesh& canonical, const ProfileSet& set, const SvgOptions& options) {
  // Front view: x across, y up (SVG y = −y); margins around the curves' rectangle.
  const double x0 = -set.border_mm - 35.0, x1 = set.border_mm + 35.0;
  const double y0 = set.height_range[0] - 25.0, y1 = set.height_range[1] + 20.0;
  const EvaluationProfile* symmetry = nullptr;
  for (const EvaluationProfile& e : set.evaluation)
    if (e.name == "symmetry") symmetry = &e;
  // Side view to the right: z across (the face looks right), y up.
  double z0 = -20.0;
  if (symmetry)
    for (const Vec3& p : symmetry->points)
      z0 = std::min(z0, p.z());
  z0 -= 10.0;
  const double side_width = std::max(15.0 - z0, 95.0), gap = 15.0; // room for the caption
  const double width = (x1 - x0) + gap + side_width, height = (y1 - y0) + 16.0;

  std::string doc =
      fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.1f} {:.1f} {:.1f} {:.1f}\" "
                  "width=\"{:.0f}\" height=\"{:.0f}\" font-family=\"sans-serif\">\n",
                  x0, -y1, width, height, 3 * width, 3 * height);
  doc += "<rect x=\"" + fmt::format("{:.1f}", x0) + "\" y=\"" + fmt::format("{:.1f}", -y1) +
         fmt::format("\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"white\"/>\n", width, height);
  doc += svg::front_view_image(canonical, {x0, x1, y0, y1, 0.5});
  const auto front = [](const Vec3& p) { return std::pair{p.x(), -p.y()}; };
  for (const ProfileCurve& c : set.curves)
    doc += svg::polyline(c.points, front,
                         c.role == PlaneRole::Joint ? "stroke=\"#d62728\" stroke-width=\"0.7\""
                                                    : "stroke=\"#ff7f0e\" stroke-width=\"0.4\"");
  static constexpr std::array<const char*, 4> kColours{"#1f77b4", "#2ca02c", "#9467bd", "#17becf"};
  for (std::size_t i = 0; i < set.evaluation.size(); ++i)
    doc += svg::polyline(set.evaluation[i].points, front,
                         fmt::format("stroke=\"{}\" stroke-width=\"0.5\" stroke-dasharray=\"2 1\"",
                                     kColours[i % kColours.size()]));
  doc +=
      fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"4\">front: {} curves (joints red), evaluation "
                  "profiles dashed</text>\n",
                  x0 + 2, -y1 + 5, set.curves.size());

  // Side view of the symmetry profile: raw as a line, fitted as crosses (the paper's Figure 4).
  if (symmetry && set.k >= 4) {
    const double dx = x1 + gap - z0;
    const auto side = [dx](const Vec3& p) { return std::pair{dx + p.z(), -p.y()}; };
    doc += svg::polyline(symmetry->points, side, "stroke=\"#333\" stroke-width=\"0.4\"");
    if (auto fitted = fit_spline(symmetry->points, {.parameter = set.parameter, .controls = set.k}))
      for (const Vec3& p : fitted->resample(set.k)) {
        const auto [u, v] = side(p);
        doc += fmt::format(
            "<path d=\"M{0:.2f},{1:.2f}l1.6,1.6m0,-1.6l-1.6,1.6\" transform=\"translate(-0.8,-0.8)\" "
            "stroke=\"#d62728\" stroke-width=\"0.35\"/>\n",
            u, v);
      }
    // Two lines: one would be wider than the side view (~0.55 em a character).
    doc += fmt::format("<text x=\"{0:.1f}\" y=\"{1:.1f}\" font-size=\"4\">side: symmetry profile</text>\n"
                       "<text x=\"{0:.1f}\" y=\"{2:.1f}\" font-size=\"4\">{3} raw points (line), {4} fitted "
                       "(x)</text>\n",
                       x1 + gap, -y1 + 5, -y1 + 10, symmetry->points.size(), set.k);
  }
  doc += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"5\">{}</text>\n</svg>\n", x0 + 2, -y0 + 10,
                     svg::escape(options.title));
  return doc;
}

} // namespace pdeface::slice
