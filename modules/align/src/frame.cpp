#include "pdeface/align/frame.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <vector>

namespace pdeface::align {

Units detect_units(const Mesh& scan) {
  if (scan.units != Units::Unknown) return scan.units;
  const double diagonal = bounding_box(scan).diagonal();
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

Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, Units scan_units) {
  const double scale = millimetres_per(scan_units == Units::Unknown ? Units::Millimetres : scan_units);
  if (!landmarks.has(Landmark::NoseTip))
    return make_error(ErrorCode::InvalidArgument, "the nose tip is needed to place the face frame");
  std::vector<Vec3> from, to;
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    if (!landmarks.points[i]) continue;
    from.push_back(scale * *landmarks.points[i]);
    to.push_back(*canonical_template().points[i]);
  }
  Eigen::Matrix3Xd src(3, from.size()), dst(3, to.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = from[i];
    dst.col(static_cast<Eigen::Index>(i)) = to[i];
  }
  // Three points that span a plane fix a rotation; fewer, or collinear ones, do not.
  const Eigen::Matrix3Xd centred = src.colwise() - src.rowwise().mean();
  const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(centred);
  if (from.size() < 3 || svd.singularValues()(1) < 1e-6 * std::max(1.0, svd.singularValues()(0)))
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("{} landmarks given, and they are collinear or too few: the nose tip and at "
                    "least two eye or mouth corners are needed",
                    from.size()));
  const Eigen::Matrix4d m = Eigen::umeyama(src, dst, false);
  FaceFrame frame;
  frame.rotation = m.topLeftCorner<3, 3>();
  frame.scale = scale;
  frame.scan_units = scan_units;
  frame.translation = -frame.rotation * (scale * *landmarks[Landmark::NoseTip]);
  return frame;
}

namespace {

Mesh mapped(const Mesh& mesh, const auto& map_point, const Eigen::Matrix3d& normal_rotation, Units units) {
  Mesh out = mesh;
  for (Vec3& p : out.positions)
    p = map_point(p);
  const Eigen::Matrix3f r = normal_rotation.cast<float>();
  for (Vec3f& n : out.normals)
    n = r * n;
  out.units = units;
  return out;
}

} // namespace

Mesh to_canonical(const Mesh& scan, const FaceFrame& frame) {
  return mapped(
      scan, [&](const Vec3& p) { return frame.to_canonical(p); }, frame.rotation, Units::Millimetres);
}

Mesh to_scan(const Mesh& canonical, const FaceFrame& frame) {
  return mapped(
      canonical, [&](const Vec3& p) { return frame.to_scan(p); }, frame.rotation.transpose(),
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
