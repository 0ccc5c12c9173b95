// A surface's colour at a point, and the colour differences between two surfaces (PSNR, CIEDE2000).

#include "pdeface/metrics/colour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pdeface::metrics {
namespace {

// The barycentric coordinates of p's projection onto the plane of (a, b, c), clamped into the triangle.
Eigen::Vector3d barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(std::abs(denominator) > 0)) return {1.0, 0.0, 0.0};
  double v = (d11 * d20 - d01 * d21) / denominator, w = (d00 * d21 - d01 * d20) / denominator;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1.0 - v - w, v, w};
}

double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
}

} // namespace

Result<SurfaceColour> SurfaceColour::of(const Mesh& mesh, std::string_view source) {
  SurfaceColour out(mesh);
  const bool has_image = mesh.material && mesh.material->base_color_image &&
                         !mesh.material->base_color_image->bytes.empty() && !mesh.texcoords.empty() &&
                         !mesh.triangles.empty();
  if (has_image) {
    Result<image::Pixels> pixels = image::decode(*mesh.material->base_color_image, source);
    if (!pixels) return std::move(pixels).error();
    out.pixels_ = *std::move(pixels);
    out.corners_ = corner_texcoords(mesh);
    out.source_ = ColourSource::Texture;
  } else if (!mesh.colors.empty()) {
    out.source_ = ColourSource::VertexColours;
  }
  return out;
}

std::optional<Eigen::Vector3f> SurfaceColour::at(const Vec3& point, std::size_t triangle) const {
  if (source_ == ColourSource::None) return std::nullopt;
  if (mesh_->triangles.empty()) { // a point cloud: the point's own colour
    if (triangle >= mesh_->colors.size()) return std::nullopt;
    const Vec4f& c = mesh_->colors[triangle];
    return Eigen::Vector3f(image::to_srgb(c.x()), image::to_srgb(c.y()), image::to_srgb(c.z()));
  }
  if (triangle >= mesh_->triangles.size()) return std::nullopt;
  const Triangle& t = mesh_->triangles[triangle];
  const Eigen::Vector3d w =
      barycentric(point, mesh_->positions[t[0]], mesh_->positions[t[1]], mesh_->positions[t[2]]);
  if (source_ == ColourSource::Texture) {
    const Vec2f st = static_cast<float>(w.x()) * corners_[3 * triangle] +
                     static_cast<float>(w.y()) * corners_[3 * triangle + 1] +
                     static_cast<float>(w.z()) * corners_[3 * triangle + 2];
    return image::sample(pixels_, st);
  }
  Eigen::Vector3f linear = Eigen::Vector3f::Zero();
  for (int k = 0; k < 3; ++k)
    linear += static_cast<float>(w(k)) * mesh_->colors[t[static_cast<std::size_t>(k)]].head<3>();
  return Eigen::Vector3f(image::to_srgb(linear.x()), image::to_srgb(linear.y()), image::to_srgb(linear.z()));
}

Eigen::Vector3d srgb_to_lab(const Eigen::Vector3f& srgb) {
  const Eigen::Vector3d linear(image::to_linear(srgb.x()), image::to_linear(srgb.y()),
                               image::to_linear(srgb.z()));
  Eigen::Matrix3d to_xyz;
  to_xyz << 0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522, 0.0721750, 0.0193339, 0.1191920, 0.9503041;
  const Eigen::Vector3d xyz = to_xyz * linear;
  const double fx = lab_f(xyz.x() / 0.95047), fy = lab_f(xyz.y()), fz = lab_f(xyz.z() / 1.08883);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double delta_e2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2) {
  using std::atan2, std::cos, std::sin, std::sqrt, std::pow, std::abs, std::exp;
  constexpr double pi = std::numbers::pi;
  const auto degrees = [](double r) { return r * 180.0 / pi; };
  const auto radians = [](double d) { return d * pi / 180.0; };
  const double l1 = lab1.x(), a1 = lab1.y(), b1 = lab1.z(), l2 = lab2.x(), a2 = lab2.y(), b2 = lab2.z();
  const double c_bar = 0.5 * (sqrt(a1 * a1 + b1 * b1) + sqrt(a2 * a2 + b2 * b2));
  const double c7 = pow(c_bar, 7);
  const double g = 0.5 * (1 - sqrt(c7 / (c7 + pow(25.0, 7))));
  const double a1p = (1 + g) * a1, a2p = (1 + g) * a2;
  const double c1p = sqrt(a1p * a1p + b1 * b1), c2p = sqrt(a2p * a2p + b2 * b2);
  const auto hue = [&](double b, double ap) {
    if (b == 0 && ap == 0) return 0.0;
    const double h = degrees(atan2(b, ap));
    return h < 0 ? h + 360 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  const double dlp = l2 - l1, dcp = c2p - c1p;
  double dhp = 0;
  if (c1p * c2p != 0) {
    dhp = h2p - h1p;
    if (dhp > 180) dhp -= 360;
    if (dhp < -180) dhp += 360;
  }
  const double delta_h = 2 * sqrt(c1p * c2p) * sin(radians(dhp / 2));
  const double lbp = 0.5 * (l1 + l2), cbp = 0.5 * (c1p + c2p);
  double hbp = h1p + h2p;
  if (c1p * c2p != 0) {
    if (abs(h1p - h2p) <= 180)
      hbp = 0.5 * (h1p + h2p);
    else
      hbp = h1p + h2p < 360 ? 0.5 * (h1p + h2p + 360) : 0.5 * (h1p + h2p - 360);
  }
  const double t = 1 - 0.17 * cos(radians(hbp - 30)) + 0.24 * cos(radians(2 * hbp)) +
                   0.32 * cos(radians(3 * hbp + 6)) - 0.20 * cos(radians(4 * hbp - 63));
  const double dtheta = 30 * exp(-pow((hbp - 275) / 25, 2));
  const double cbp7 = pow(cbp, 7);
  const double rc = 2 * sqrt(cbp7 / (cbp7 + pow(25.0, 7)));
  const double sl = 1 + 0.015 * pow(lbp - 50, 2) / sqrt(20 + pow(lbp - 50, 2));
  const double sc = 1 + 0.045 * cbp, sh = 1 + 0.015 * cbp * t;
  const double rt = -sin(radians(2 * dtheta)) * rc;
  return sqrt(pow(dlp / sl, 2) + pow(dcp / sc, 2) + pow(delta_h / sh, 2) + rt * (dcp / sc) * (delta_h / sh));
}

ColourError colour_error(const SurfaceColour& reference, const SurfaceDistance& on_reference,
                         const SurfaceColour& test, const SurfaceDistance& on_test,
                         std::span<const Vec3> points) {
  if (points.empty()) throw std::invalid_argument("metrics::colour_error: no points");
  if (reference.source() == ColourSource::None)
    throw std::invalid_argument("metrics::colour_error: a reference without colour");
  ColourError out;
  double squared = 0;
  std::vector<double> differences;
  differences.reserve(points.size());
  for (const Vec3& p : points) {
    const SurfaceDistance::Nearest r = on_reference.nearest(p);
    const std::optional<Eigen::Vector3f> want = reference.at(r.point, r.triangle);
    if (!want) continue;
    const SurfaceDistance::Nearest t = on_test.nearest(p);
    std::optional<Eigen::Vector3f> got = test.at(t.point, t.triangle);
    if (!got) {
      ++out.uncoloured;
      got = Eigen::Vector3f::Zero();
    }
    // As the 8-bit values a viewer shows.
    for (int c = 0; c < 3; ++c) {
      const double d = std::round(255.0 * (*want)(c)) - std::round(255.0 * (*got)(c));
      squared += d * d;
    }
    differences.push_back(delta_e2000(srgb_to_lab(*want), srgb_to_lab(*got)));
  }
  out.samples = differences.size();
  if (differences.empty()) return out;
  const double mse = squared / (3.0 * static_cast<double>(differences.size()));
  out.psnr_db = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const double d : differences)
    sum += d;
  out.mean_delta_e = sum / static_cast<double>(differences.size());
  const auto p95 =
      differences.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(differences.size() - 1));
  std::nth_element(differences.begin(), p95, differences.end());
  out.p95_delta_e = *p95;
  return out;
}

} // namespace pdeface::metrics
