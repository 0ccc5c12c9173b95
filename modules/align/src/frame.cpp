#include "pdeface/align/frame.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace pdeface::align {

Units detect_units(const Mesh& scan) {
  return scan.units != Units::Unknown ? scan.units : units_by_size(bounding_box(scan).diagonal());
}

Units units_by_size(double diagonal) {
  if (diagonal < 2.0) return Units::Metres;
  if (diagonal < 60.0) return Units::Centimetres;
  return Units::Millimetres;
}

const Landmarks& canonical_template() {
  static const Landmarks t = [] {
    // Adult averages (Farkas' anthropometry, rounded) checked against the landmarks found on the real
    // scans in ../shared/faces: intercanthal width 30 mm, biocular width 96 mm, mouth width 52 mm; eye
    // corners 34-37 mm above the nose tip, mouth corners 31 mm below; the face region from hairline to
    // chin ~165 mm. Depths follow the curvature of the face.
    Landmarks l;
    l.units = Units::Millimetres;
    l[Landmark::NoseTip] = Vec3(0, 0, 0);
    l[Landmark::EyeInnerLeft] = Vec3(15, 37, -34);
    l[Landmark::EyeInnerRight] = Vec3(-15, 37, -34);
    l[Landmark::EyeOuterLeft] = Vec3(48, 34, -46);
    l[Landmark::EyeOuterRight] = Vec3(-48, 34, -46);
    l[Landmark::MouthLeft] = Vec3(26, -31, -33);
    l[Landmark::MouthRight] = Vec3(-26, -31, -33);
    l[Landmark::FaceTop] = Vec3(0, 88, -32);
    l[Landmark::FaceBottom] = Vec3(0, -78, -28);
    return l;
  }();
  return t;
}

double fit_weight(Landmark landmark) noexcept {
  // Measured against hand-placed landmarks (james, facefuns): the nose tip and inner eye corners are found
  // within 1-4 mm, the mouth corners within 2-5 mm (and they move with expressions), the outer eye
  // corners within 5-9 mm (their hollow lies beyond the end of the fissure, more or less).
  switch (landmark) {
  case Landmark::NoseTip:
  case Landmark::EyeInnerLeft:
  case Landmark::EyeInnerRight: return 1.0;
  case Landmark::EyeOuterLeft:
  case Landmark::EyeOuterRight: return 0.25;
  case Landmark::MouthLeft:
  case Landmark::MouthRight: return 0.5;
  default: return 0.0;
  }
}

namespace {

// The landmarks as the columns of a fit: each one `4 · weight` times (Eigen::umeyama has no weights;
// repeating a column is the same as doubling its weight), scaled by `scale`, and the template's points
// beside them. When the weighted ones do not span a plane (too few stable landmarks given), every
// landmark counts once.
struct FitColumns {
  Eigen::Matrix3Xd src, dst;
};

bool spans_a_plane(const Eigen::Matrix3Xd& m) {
  if (m.cols() < 3) return false;
  const Eigen::Matrix3Xd centred = m.colwise() - m.rowwise().mean();
  const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
  return svd.singularValues()(1) > 1e-6 * std::max(1.0, svd.singularValues()(0));
}

FitColumns fit_columns(const Landmarks& landmarks, double scale) {
  for (bool weighted : {true, false}) {
    std::vector<Vec3> from, to;
    for (std::size_t i = 0; i < kLandmarkCount; ++i) {
      if (!landmarks.points[i]) continue;
      const int times =
          weighted ? static_cast<int>(std::lround(4.0 * fit_weight(static_cast<Landmark>(i)))) : 1;
      for (int k = 0; k < times; ++k) {
        from.push_back(scale * *landmarks.points[i]);
        to.push_back(*canonical_template().points[i]);
      }
    }
    FitColumns c{Eigen::Matrix3Xd(3, static_cast<Eigen::Index>(from.size())),
                 Eigen::Matrix3Xd(3, static_cast<Eigen::Index>(to.size()))};
    for (std::size_t i = 0; i < from.size(); ++i) {
      c.src.col(static_cast<Eigen::Index>(i)) = from[i];
      c.dst.col(static_cast<Eigen::Index>(i)) = to[i];
    }
    if (!weighted || spans_a_plane(c.src)) return c;
  }
  return {}; // not reached
}

Error too_few(const Landmarks& landmarks) {
  return make_error(ErrorCode::InvalidArgument,
                    fmt::format("{} landmarks given, and they are collinear or too few: the nose tip and at "
                                "least two eye or mouth corners are needed",
                                landmarks.count()));
}

} // namespace

Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, Units scan_units) {
  return frame_from_landmarks(
      landmarks, millimetres_per(scan_units == Units::Unknown ? Units::Millimetres : scan_units), scan_units);
}

Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, double mm_per_unit, Units scan_units) {
  if (!(mm_per_unit > 0.0) || !std::isfinite(mm_per_unit))
    throw std::invalid_argument("frame_from_landmarks: the scale must be positive and finite");
  if (!landmarks.has(Landmark::NoseTip))
    return make_error(ErrorCode::InvalidArgument, "the nose tip is needed to place the face frame");
  // Three points that span a plane fix a rotation; fewer, or collinear ones, do not.
  const FitColumns c = fit_columns(landmarks, mm_per_unit);
  if (!spans_a_plane(c.src)) return too_few(landmarks);
  const Eigen::Matrix4d m = Eigen::umeyama(c.src, c.dst, false);
  FaceFrame frame;
  frame.rotation = m.topLeftCorner<3, 3>();
  frame.scale = mm_per_unit;
  frame.scan_units = scan_units;
  frame.translation = -frame.rotation * (mm_per_unit * *landmarks[Landmark::NoseTip]);
  return frame;
}

Units snap_units(double mm_per_unit) noexcept {
  Units best = Units::Unknown;
  double nearest = std::log(kUnitSnapFactor);
  for (Units u : {Units::Millimetres, Units::Centimetres, Units::Inches, Units::Metres})
    if (const double d = std::abs(std::log(mm_per_unit / millimetres_per(u))); d < nearest) {
      nearest = d;
      best = u;
    }
  return best;
}

Result<ScaleEstimate> estimate_scale(const Landmarks& landmarks) {
  const FitColumns c = fit_columns(landmarks, 1.0);
  if (!spans_a_plane(c.src)) return too_few(landmarks);
  const Eigen::Matrix4d m = Eigen::umeyama(c.src, c.dst, true);
  // The similarity's linear part is scale · rotation: its determinant is scale³.
  const double mm = std::cbrt(m.topLeftCorner<3, 3>().determinant());
  if (!(mm > 0.0) || !std::isfinite(mm)) return too_few(landmarks);
  ScaleEstimate out;
  out.estimated = mm;
  out.units = snap_units(mm);
  out.mm_per_unit = out.units == Units::Unknown ? mm : millimetres_per(out.units);
  return out;
}

namespace {

Mesh mapped(Mesh out, const auto& map_point, const Eigen::Matrix3d& normal_rotation, Units units) {
  for (Vec3& p : out.positions)
    p = map_point(p);
  const Eigen::Matrix3f r = normal_rotation.cast<float>();
  for (Vec3f& n : out.normals)
    n = r * n;
  out.units = units;
  return out;
}

} // namespace

Mesh to_canonical(Mesh scan, const FaceFrame& frame) {
  return mapped(
      std::move(scan), [&](const Vec3& p) { return frame.to_canonical(p); }, frame.rotation,
      Units::Millimetres);
}

Mesh to_scan(Mesh canonical, const FaceFrame& frame) {
  return mapped(
      std::move(canonical), [&](const Vec3& p) { return frame.to_scan(p); }, frame.rotation.transpose(),
      frame.scan_units);
}

Landmarks to_canonical(const Landmarks& scan, const FaceFrame& frame) {
  Landmarks out;
  out.units = Units::Millimetres;
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    if (scan.points[i]) out.points[i] = frame.to_canonical(*scan.points[i]);
  return out;
}

std::string write_alignment_json(const Landmarks& landmarks, const FaceFrame& frame,
                                 std::optional<double> confidence) {
  nlohmann::json j = nlohmann::json::parse(write_landmarks_json(landmarks));
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    rows.push_back({frame.rotation(r, 0), frame.rotation(r, 1), frame.rotation(r, 2)});
  j["to_canonical"] = {
      {"rotation", rows},
      {"translation_mm", {frame.translation.x(), frame.translation.y(), frame.translation.z()}},
      {"scale_mm_per_unit", frame.scale}};
  if (confidence) j["confidence"] = *confidence;
  return j.dump(2) + "\n";
}

} // namespace pdeface::align
