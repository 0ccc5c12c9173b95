#include "frame.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <cmath>

namespace pdeface::pdef::detail {
namespace {

// The rotation of the unit quaternion (w, x, y, z), w = sqrt(1 − x² − y² − z²).
Eigen::Matrix3d rotation_of(double x, double y, double z) {
  const double w = std::sqrt(std::max(0.0, 1.0 - (x * x + y * y + z * z)));
  Eigen::Matrix3d r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), //
      2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),  //
      2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y);
  return r;
}

} // namespace

void write_frame(Writer& w, const Frame& f, bool float64) {
  w.u8(float64 ? 8 : 4);
  if (float64) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        w.f64(f.rotation(r, c));
    for (int i = 0; i < 3; ++i)
      w.f64(f.translation(i));
    w.f64(f.scale);
    return;
  }
  Eigen::Quaterniond q(f.rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  w.f32(static_cast<float>(q.x()));
  w.f32(static_cast<float>(q.y()));
  w.f32(static_cast<float>(q.z()));
  for (int i = 0; i < 3; ++i)
    w.f32(static_cast<float>(f.translation(i)));
  w.f32(static_cast<float>(f.scale));
}

Frame read_frame(Reader& r, bool& float64) {
  Frame f;
  const std::size_t at = r.offset();
  const std::uint8_t width = r.u8("the frame's precision");
  float64 = width == 8;
  if (r.ok() && width != 4 && width != 8) {
    r.fail(ErrorCode::Malformed, fmt::format("the frame's precision is {} bytes (4 or 8)", width), at);
    return f;
  }
  const std::size_t values = r.offset();
  if (float64) {
    for (int row = 0; row < 3; ++row)
      for (int c = 0; c < 3; ++c)
        f.rotation(row, c) = r.f64("the frame's rotation");
  } else {
    const double x = r.f32("the frame's rotation"), y = r.f32("the frame's rotation"),
                 z = r.f32("the frame's rotation");
    if (r.ok() && !(x * x + y * y + z * z <= 1.0 + 1e-6)) {
      r.fail(std::isfinite(x + y + z) ? ErrorCode::Malformed : ErrorCode::NonFinite,
             "the frame's rotation is not a unit quaternion", values);
      return f;
    }
    f.rotation = rotation_of(x, y, z);
  }
  auto get = [&](std::string_view what) { return float64 ? r.f64(what) : static_cast<double>(r.f32(what)); };
  for (int i = 0; i < 3; ++i)
    f.translation(i) = get("the frame's translation");
  const std::size_t scale_at = r.offset();
  f.scale = get("the frame's scale");
  if (!r.ok()) return f;
  if (!f.rotation.allFinite() || !f.translation.allFinite() || !std::isfinite(f.scale))
    r.fail(ErrorCode::NonFinite, "the frame has a NaN or infinite value", values);
  else if (!(f.scale > 0))
    r.fail(ErrorCode::Malformed, fmt::format("the frame's scale {} is not positive", f.scale), scale_at);
  else if ((f.rotation.transpose() * f.rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
           f.rotation.determinant() < 0)
    r.fail(ErrorCode::Malformed, "the frame's rotation is not a rotation", values);
  return f;
}

Frame as_float32(const Frame& frame) {
  Writer w;
  write_frame(w, frame, false);
  Reader r(w.str(), 0, {});
  bool float64 = false;
  Frame back = read_frame(r, float64);
  back.scan_units = frame.scan_units;
  return back;
}

} // namespace pdeface::pdef::detail
