#pragma once
// What the .pdef tests share: a small synthetic face made from a formula (no slicing involved, so its bytes
// do not change when the slicer does), and helpers to read and patch files.

#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/pdef.hpp"

#include "pdeface_test.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

namespace pdeface::test {

//! A face-like surface: z(x, y) in mm, smooth, with a nose-like bump.
inline double synthetic_depth(double x, double y) {
  return -0.004 * x * x - 0.0015 * y * y + 18.0 * std::exp(-(x * x / 60.0 + y * y / 500.0)) + 0.02 * x;
}

//! J curves of K samples of `synthetic_depth` (planes 3p + 1 with joints 12 mm apart and two
//! intermediates at thirds, heights from -70 to 85 mm with curve-dependent ends), a turned and shifted
//! frame in centimetres, some filled samples, spline scheme with the isotropic smoothing parameter.
inline pdef::Face synthetic_face(std::size_t curves = 10, std::size_t samples = 12) {
  pdef::Face face;
  face.curves.units = Units::Millimetres;
  const double width = 12.0 * static_cast<double>(curves - 1) / 3.0;
  for (std::size_t j = 0; j < curves; ++j) {
    const double x = -width / 2 + width * static_cast<double>(j) / static_cast<double>(curves - 1);
    face.planes.push_back(x);
    const double bottom = -70.0 + 0.08 * x * x / 10.0, top = 85.0 - 0.05 * std::abs(x);
    pde::Curve c(static_cast<Eigen::Index>(samples), 3);
    std::vector<bool> filled(samples, false);
    for (std::size_t k = 0; k < samples; ++k) {
      const double t =
          0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(k) / static_cast<double>(samples - 1));
      const double y = bottom + (top - bottom) * t;
      c.row(static_cast<Eigen::Index>(k)) << x, y, synthetic_depth(x, y);
      filled[k] = (j == 3 || j == 4) && k >= 5 && k <= 6;
    }
    face.curves.samples.push_back(c);
    face.filled.push_back(filled);
  }
  face.pde.spacing = pde::Spacing::Physical;
  face.pde.smoothing = pde::isotropic_smoothing(face.curves).value();
  face.pde.modes = samples - 1;
  face.frame.rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  face.frame.translation = Vec3(12.5, -40.0, 300.25);
  face.frame.scale = 10.0; // mm per cm
  face.frame.scan_units = Units::Centimetres;
  return face;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

//! The file with its checksum recomputed (to make hostile files that pass it).
inline std::string with_checksum(std::string bytes) {
  const std::uint32_t crc = pdef::checksum(std::string_view(bytes).substr(0, bytes.size() - 4));
  for (int i = 0; i < 4; ++i)
    bytes[bytes.size() - 4 + static_cast<std::size_t>(i)] = static_cast<char>(crc >> (8 * i));
  return bytes;
}

} // namespace pdeface::test
