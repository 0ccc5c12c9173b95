#include "pdeface/core/sample_face.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pdeface {
namespace {

// exp(-(dx² / 2sx² + dy² / 2sy²)): the building block of every feature.
double bump(double x, double y, double cx, double cy, double sx, double sy) {
  const double u = (x - cx) / sx;
  const double v = (y - cy) / sy;
  return std::exp(-0.5 * (u * u + v * v));
}

// A hash of integers to [0, 1): reproducible across platforms, unlike std:: distributions.
double unit_hash(std::uint32_t a, std::uint32_t b, std::uint32_t seed) {
  std::uint64_t h =
      (static_cast<std::uint64_t>(a) << 32U) ^ b ^ (static_cast<std::uint64_t>(seed) * 0x9E3779B97F4A7C15ULL);
  h ^= h >> 33U;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33U;
  h *= 0xC4CEB9FE1A85EC53ULL;
  h ^= h >> 33U;
  return static_cast<double>(h >> 11U) * 0x1.0p-53;
}

// Outline of the scanned region: an ellipse whose radius wobbles with the angle.
bool inside_outline(double x, double y, std::uint32_t seed) {
  const double cx = 0.0, cy = -8.0, ax = 84.0, ay = 102.0;
  const double dx = (x - cx) / ax, dy = (y - cy) / ay;
  const double theta = std::atan2(dy, dx);
  const double phase = 0.7 * static_cast<double>(seed % 97U);
  const double wobble = 1.0 + 0.035 * std::sin(5.0 * theta + phase) +
                        0.02 * std::sin(11.0 * theta + 2.0 * phase) +
                        0.012 * std::sin(23.0 * theta + 3.0 * phase);
  return dx * dx + dy * dy < wobble * wobble;
}

struct Hole {
  double x, y, r;
};
constexpr Hole kHoles[] = {{-47.0, 47.0, 3.0}, {21.0, -72.0, 2.4}, {54.0, -12.0, 3.6}, {-9.0, 71.0, 2.0}};

// 1 across the mouth (|x| < 14 mm), falling off over 4 mm towards its corners at ±23 mm.
double mouth_span(double x) {
  const double beyond = std::max(0.0, std::abs(x) - 14.0) / 4.0;
  return std::exp(-0.5 * beyond * beyond);
}

Vec4f skin_colour(double x, double y) {
  const double lips =
      mouth_span(x) * std::max(bump(0.0, y, 0.0, -24.5, 1.0, 3.5), bump(0.0, y, 0.0, -36.5, 1.0, 4.0));
  const double brows = bump(x, y, -30.0, 39.0, 15.0, 3.0) + bump(x, y, 30.0, 39.0, 15.0, 3.0);
  const double r = 0.85 - 0.45 * brows + 0.02 * lips;
  const double g = 0.68 - 0.35 * brows - 0.25 * lips;
  const double b = 0.58 - 0.30 * brows - 0.15 * lips;
  return {static_cast<float>(r), static_cast<float>(g), static_cast<float>(b), 1.0f};
}

} // namespace

double sample_face_height(double x, double y) {
  // Head: curved across (a cylinder of radius 85 mm) and gently down the face.
  const double r = 85.0;
  const double ax = std::min(std::abs(x), 0.98 * r);
  double z = std::sqrt(r * r - ax * ax) - r - (y + 10.0) * (y + 10.0) / 450.0;

  z += 4.0 * bump(x, y, 0.0, 62.0, 45.0, 22.0);                                         // forehead
  z += 3.5 * (bump(x, y, -30.0, 39.0, 16.0, 5.5) + bump(x, y, 30.0, 39.0, 16.0, 5.5));  // brow ridges
  z -= 10.0 * (bump(x, y, -32.0, 27.0, 12.0, 8.5) + bump(x, y, 32.0, 27.0, 12.0, 8.5)); // eye sockets
  z += 3.0 * (bump(x, y, -42.0, 4.0, 14.0, 12.0) + bump(x, y, 42.0, 4.0, 14.0, 12.0));  // cheekbones

  // Nose: a ridge from the root (y = 36) to the tip (origin), widening downwards, with a sharp
  // underside and two wings.
  const double t = std::clamp(y / 36.0, -1.0, 1.0);
  const double ridge =
      y >= 0.0 ? 24.0 - 14.0 * t * t * (3.0 - 2.0 * t) : 24.0 * std::exp(-0.5 * (y / 5.0) * (y / 5.0));
  const double width = 5.5 + 3.5 * (1.0 - std::clamp(y, 0.0, 36.0) / 36.0);
  const double fade = y > 36.0 ? std::exp(-0.5 * ((y - 36.0) / 6.0) * ((y - 36.0) / 6.0)) : 1.0;
  z += ridge * fade * std::exp(-0.5 * (x / width) * (x / width));
  z += 5.0 * (bump(x, y, -14.0, -5.0, 5.0, 5.0) + bump(x, y, 14.0, -5.0, 5.0, 5.0)); // nose wings

  z += 3.5 * (bump(x, y, -32.0, 26.0, 7.0, 5.0) + bump(x, y, 32.0, 26.0, 7.0, 5.0)); // eyeballs
  // Corners of the eyes and the mouth: small hollows, as on a real face (where landmarks are found).
  for (double side : {-1.0, 1.0}) {
    z -= 3.0 * bump(x, y, side * 17.0, 29.0, 2.5, 2.5);  // inner eye corner
    z -= 3.0 * bump(x, y, side * 46.0, 30.0, 2.5, 2.5);  // outer eye corner
    z -= 2.0 * bump(x, y, side * 23.0, -30.5, 2.5, 2.5); // mouth corner
  }
  // Lips and the mouth line between them span the mouth's width (46 mm) and fade out at its corners.
  const double across = mouth_span(x);
  z += across * 5.0 * bump(0.0, y, 0.0, -24.5, 1.0, 4.0); // upper lip
  z += across * 4.5 * bump(0.0, y, 0.0, -36.5, 1.0, 4.5); // lower lip
  z -= across * 2.5 * bump(0.0, y, 0.0, -30.5, 1.0, 1.4); // mouth line
  z += 6.0 * bump(x, y, 0.0, -64.0, 15.0, 8.0);           // chin
  return z;
}

SampleFaceLandmarks sample_face_landmarks() {
  SampleFaceLandmarks l;
  for (Vec3* p : {&l.nose_tip, &l.eye_inner_left, &l.eye_inner_right, &l.eye_outer_left, &l.eye_outer_right,
                  &l.mouth_left, &l.mouth_right})
    p->z() = sample_face_height(p->x(), p->y());
  return l;
}

Mesh sample_face(const SampleFaceOptions& options) {
  if (!(options.spacing_mm >= 0.2 && options.spacing_mm <= 20.0))
    throw std::invalid_argument("sample_face: spacing_mm must be in [0.2, 20]");
  if (!(options.noise_mm >= 0.0)) throw std::invalid_argument("sample_face: noise_mm must be >= 0");

  const double h = options.spacing_mm;
  const double x0 = -90.0, x1 = 90.0, y0 = -115.0, y1 = 100.0;
  const auto nx = static_cast<std::uint32_t>(std::floor((x1 - x0) / h)) + 1;
  const auto ny = static_cast<std::uint32_t>(std::floor((y1 - y0) / h)) + 1;
  constexpr std::uint32_t kNone = 0xFFFFFFFFU;
  std::vector<std::uint32_t> index(static_cast<std::size_t>(nx) * ny, kNone);

  Mesh mesh;
  mesh.name = "pdeface sample face";
  mesh.units = Units::Millimetres;
  // Rows from the top of the head down, as a range scanner writes them.
  for (std::uint32_t j = 0; j < ny; ++j) {
    const double y = y1 - j * h;
    for (std::uint32_t i = 0; i < nx; ++i) {
      const double x = x0 + i * h;
      if (!inside_outline(x, y, options.seed)) continue;
      if (options.holes) {
        bool in_hole = false;
        for (const Hole& hole : kHoles)
          in_hole |= (x - hole.x) * (x - hole.x) + (y - hole.y) * (y - hole.y) < hole.r * hole.r;
        if (in_hole) continue;
      }
      const double noise = options.noise_mm * (2.0 * unit_hash(i, j, options.seed) - 1.0);
      index[static_cast<std::size_t>(j) * nx + i] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.emplace_back(x, y, sample_face_height(x, y) + noise);
      if (options.colors) mesh.colors.push_back(skin_colour(x, y));
    }
  }
  // Two triangles per grid cell with all four corners; one where exactly three remain (a ragged edge).
  // Counter-clockwise seen from +z, so normals point towards the viewer.
  for (std::uint32_t j = 0; j + 1 < ny; ++j) {
    for (std::uint32_t i = 0; i + 1 < nx; ++i) {
      const std::uint32_t a = index[static_cast<std::size_t>(j) * nx + i];         // top left
      const std::uint32_t b = index[static_cast<std::size_t>(j) * nx + i + 1];     // top right
      const std::uint32_t c = index[static_cast<std::size_t>(j + 1) * nx + i];     // bottom left
      const std::uint32_t d = index[static_cast<std::size_t>(j + 1) * nx + i + 1]; // bottom right
      const int present = (a != kNone) + (b != kNone) + (c != kNone) + (d != kNone);
      if (present == 4) {
        mesh.triangles.push_back({a, c, d});
        mesh.triangles.push_back({a, d, b});
      } else if (present == 3) {
        if (a == kNone)
          mesh.triangles.push_back({b, c, d});
        else if (b == kNone)
          mesh.triangles.push_back({a, c, d});
        else if (c == kNone)
          mesh.triangles.push_back({a, d, b});
        else
          mesh.triangles.push_back({a, c, b});
      }
    }
  }
  mesh.normals = vertex_normals(mesh);
  return mesh;
}

} // namespace pdeface
