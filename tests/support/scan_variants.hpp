#pragma once
// Held-out scans made from the shared ones: what a user's first scan may look like and ours do not. A
// shared scan in the canonical frame (mm) with its landmarks is given a back of the head with hair, a neck,
// shoulders and a plinth, a side cut short, holes, noise, a child's proportions, a smile or an open mouth,
// and then an arbitrary pose and units. The truth travels with it: the modified face in the canonical frame
// and the similarity from the variant's frame into it. No GoogleTest here (the benchmarks may use it).

#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

namespace pdeface::test {

//! A face scan in the canonical frame (mm) and its landmarks there: the truth a variant is judged by.
struct FaceScan {
  Mesh mesh;
  align::Landmarks landmarks;
};

namespace variants_detail {

inline double outer_eye_x(const align::Landmarks& l) {
  using align::Landmark;
  return 0.5 * (std::abs(l[Landmark::EyeOuterLeft]->x()) + std::abs(l[Landmark::EyeOuterRight]->x()));
}
inline double eye_y(const align::Landmarks& l) {
  using align::Landmark;
  return 0.5 * (l[Landmark::EyeOuterLeft]->y() + l[Landmark::EyeOuterRight]->y());
}
inline double mouth_y(const align::Landmarks& l) {
  using align::Landmark;
  return 0.5 * (l[Landmark::MouthLeft]->y() + l[Landmark::MouthRight]->y());
}

} // namespace variants_detail

//! `m` without the triangles for whose centroid `drop` holds, and without the vertices no triangle uses
//! any more (a point cloud: without the points for which `drop` holds).
inline Mesh without(const Mesh& m, const std::function<bool(const Vec3&)>& drop) {
  Mesh out;
  out.units = m.units;
  if (m.is_point_cloud()) {
    for (const Vec3& p : m.positions)
      if (!drop(p)) out.positions.push_back(p);
    return out;
  }
  std::vector<std::int64_t> index(m.positions.size(), -1);
  for (const Triangle& t : m.triangles) {
    const Vec3 c = (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0;
    if (drop(c)) continue;
    Triangle kept;
    for (int k = 0; k < 3; ++k) {
      std::int64_t& i = index[t[k]];
      if (i < 0) {
        i = static_cast<std::int64_t>(out.positions.size());
        out.positions.push_back(m.positions[t[k]]);
      }
      kept[k] = static_cast<std::uint32_t>(i);
    }
    out.triangles.push_back(kept);
  }
  return out;
}

//! Appends `part` (positions and triangles) to `m`.
inline void append(Mesh& m, const Mesh& part) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), part.positions.begin(), part.positions.end());
  if (m.is_point_cloud() && !m.positions.empty() && base > 0) return; // a cloud takes the points only
  for (const Triangle& t : part.triangles)
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

//! A triangulated patch (u, v) ∈ [0, 1]² → `at(u, v)`, `nu` × `nv` cells, kept where `keep(point)` holds.
inline Mesh patch(int nu, int nv, const std::function<Vec3(double, double)>& at,
                  const std::function<bool(const Vec3&)>& keep = {}) {
  Mesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      m.positions.push_back(at(static_cast<double>(i) / nu, static_cast<double>(j) / nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const auto v = static_cast<std::uint32_t>(j * (nu + 1) + i);
      const auto w = static_cast<std::uint32_t>(nu + 1);
      m.triangles.push_back({v, v + 1, v + w + 1});
      m.triangles.push_back({v, v + w + 1, v + w});
    }
  return keep ? without(m, [&](const Vec3& p) { return !keep(p); }) : m;
}

//! The back of the head (an ellipsoid from the ears back, closing the scan), hair on it (bumps 4–12 mm
//! high over the crown and the back) and a neck under the chin: a full head.
inline FaceScan with_back_of_head(FaceScan face) {
  using align::Landmark;
  const align::Landmarks& l = face.landmarks;
  const double a = 1.75 * variants_detail::outer_eye_x(l); // half the head's width
  const double height = l[Landmark::FaceTop]->y() - l[Landmark::FaceBottom]->y();
  const double yc = variants_detail::eye_y(l) + 5.0, b = 0.62 * height, c = 100.0, zc = -100.0;
  const double pi = std::numbers::pi;
  const Mesh head = patch(
      180, 90,
      [&](double u, double v) {
        const double theta = 2.0 * pi * u, phi = pi * (v - 0.5); // round the head, chin to crown
        Vec3 n(std::cos(phi) * std::sin(theta), std::sin(phi), std::cos(phi) * std::cos(theta));
        // Hair: bumps over the crown and the back.
        const double crown = std::clamp((n.y() + 0.2) / 0.4, 0.0, 1.0) * std::clamp(0.5 - n.z(), 0.0, 1.0);
        const double hair = crown * (8.0 + 4.0 * std::sin(9.0 * theta) * std::sin(7.0 * phi));
        return Vec3(a * n.x() + hair * n.x(), yc + b * n.y() + hair * n.y(), zc + c * n.z() + hair * n.z());
      },
      [&](const Vec3& p) { return p.z() < zc + 0.3 * c; });
  append(face.mesh, head);
  const double bottom = l[Landmark::FaceBottom]->y();
  const Mesh neck = patch(90, 40, [&](double u, double v) {
    const double t = 2.0 * pi * u;
    return Vec3(0.62 * a * std::sin(t), bottom + 25.0 - 120.0 * v, -90.0 + 45.0 * std::cos(t));
  });
  append(face.mesh, neck);
  return face;
}

//! Shoulders and a plinth under the neck: a bust on its base (`with_back_of_head` first for the neck).
inline FaceScan on_pedestal(FaceScan face) {
  using align::Landmark;
  const double bottom = face.landmarks[Landmark::FaceBottom]->y();
  const double pi = std::numbers::pi;
  const double top = bottom - 95.0;
  const Mesh shoulders = patch(120, 40, [&](double u, double v) {
    const double theta = 2.0 * pi * u, phi = 0.5 * pi * v; // the upper half of a flat ellipsoid
    return Vec3(190.0 * std::cos(phi) * std::sin(theta), top - 70.0 + 70.0 * std::sin(phi),
                -90.0 + 105.0 * std::cos(phi) * std::cos(theta));
  });
  append(face.mesh, shoulders);
  // The plinth: a box's sides and top, 240 x 60 x 160 mm.
  const double y0 = top - 130.0, y1 = top - 70.0;
  const auto side = [&](const Vec3& o, const Vec3& du, const Vec3& dv) {
    append(face.mesh, patch(40, 10, [&](double u, double v) { return Vec3(o + u * du + v * dv); }));
  };
  side(Vec3(-120, y0, 70), Vec3(240, 0, 0), Vec3(0, y1 - y0, 0));   // front
  side(Vec3(120, y0, -250), Vec3(-240, 0, 0), Vec3(0, y1 - y0, 0)); // back
  side(Vec3(-120, y0, -250), Vec3(0, 0, 320), Vec3(0, y1 - y0, 0)); // right
  side(Vec3(120, y0, 70), Vec3(0, 0, -320), Vec3(0, y1 - y0, 0));   // left
  side(Vec3(-120, y1, 70), Vec3(240, 0, 0), Vec3(0, 0, -320));      // top
  return face;
}

//! The face cut short on one side (`side` +1: its left, −1: its right), `beyond` mm past the outer eye
//! corner: a capture that missed a cheek.
inline FaceScan cut_side(FaceScan face, double side, double beyond = 8.0) {
  const double x = variants_detail::outer_eye_x(face.landmarks) + beyond;
  face.mesh = without(face.mesh, [&](const Vec3& p) { return side * p.x() > x; });
  return face;
}

//! The chin cut short: nothing below `above` mm over the chin.
inline FaceScan cut_chin(FaceScan face, double above = 12.0) {
  const double y = face.landmarks[align::Landmark::FaceBottom]->y() + above;
  face.mesh = without(face.mesh, [&](const Vec3& p) { return p.y() < y; });
  return face;
}

//! `count` round holes of 4–12 mm radius where capture fails (cheeks, forehead, beside the nose, the
//! chin), none within 12 mm of the nose tip.
inline FaceScan with_holes(FaceScan face, unsigned seed, int count = 4) {
  std::mt19937 random(seed);
  const double w = variants_detail::outer_eye_x(face.landmarks);
  const double top = face.landmarks[align::Landmark::FaceTop]->y();
  const double bottom = face.landmarks[align::Landmark::FaceBottom]->y();
  std::uniform_real_distribution<double> x(-1.1 * w, 1.1 * w), y(bottom + 10.0, top - 10.0), r(4.0, 12.0);
  std::vector<std::pair<Eigen::Vector2d, double>> holes;
  while (static_cast<int>(holes.size()) < count) {
    const Eigen::Vector2d centre(x(random), y(random));
    const double radius = r(random);
    if (centre.norm() < 12.0 + radius) continue;
    holes.emplace_back(centre, radius);
  }
  face.mesh = without(face.mesh, [&](const Vec3& p) {
    return p.z() > -60.0 && std::ranges::any_of(holes, [&](const auto& h) {
             return (p.head<2>() - h.first).norm() < h.second;
           });
  });
  return face;
}

//! Gaussian noise of `sigma` mm on every vertex (a noisy capture).
inline FaceScan with_noise(FaceScan face, double sigma, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> n(0.0, sigma);
  for (Vec3& p : face.mesh.positions)
    p += Vec3(n(random), n(random), n(random));
  return face;
}

//! A smooth warp of the face and its landmarks alike.
inline FaceScan warped(FaceScan face, const std::function<Vec3(const Vec3&)>& warp) {
  for (Vec3& p : face.mesh.positions)
    p = warp(p);
  for (auto& l : face.landmarks.points)
    if (l) l = warp(*l);
  return face;
}

//! A child's proportions: the whole face 0.72 as large, the face below the eyes shorter still and the
//! nose and chin less prominent (a flatter profile).
inline FaceScan child_like(FaceScan face) {
  const double eyes = variants_detail::eye_y(face.landmarks);
  return warped(std::move(face), [&](const Vec3& p) {
    Vec3 q = p;
    if (q.y() < eyes) q.y() = eyes + 0.85 * (q.y() - eyes);
    const double front = std::exp(-(q.head<2>().squaredNorm()) / (2.0 * 40.0 * 40.0));
    q.z() -= 0.25 * front * std::max(0.0, q.z() + 20.0); // nose and chin back towards the cheeks
    return Vec3(0.72 * q);
  });
}

//! A broad smile: the mouth corners up 7 mm, out 4 mm and back 4 mm, the cheeks beside them raised.
inline FaceScan smiling(FaceScan face) {
  using align::Landmark;
  const Vec3 left = *face.landmarks[Landmark::MouthLeft], right = *face.landmarks[Landmark::MouthRight];
  return warped(std::move(face), [&](const Vec3& p) {
    Vec3 q = p;
    for (const Vec3& corner : {left, right}) {
      const double w = std::exp(-(p - corner).squaredNorm() / (2.0 * 12.0 * 12.0));
      const double out = corner.x() > 0 ? 1.0 : -1.0;
      q += w * Vec3(4.0 * out, 7.0, -4.0);
    }
    return q;
  });
}

//! The mouth open: the lips parted by a hole along the mouth line, the jaw below it dropped 12 mm.
inline FaceScan open_mouth(FaceScan face) {
  using align::Landmark;
  const Vec3 left = *face.landmarks[Landmark::MouthLeft], right = *face.landmarks[Landmark::MouthRight];
  const double y = variants_detail::mouth_y(face.landmarks), half = 0.5 * std::abs(left.x() - right.x());
  face.mesh = without(face.mesh, [&](const Vec3& p) {
    return std::abs(p.y() - y) < 1.2 && std::abs(p.x()) < half - 1.0 && p.z() > -40.0;
  });
  return warped(std::move(face), [&](const Vec3& p) {
    if (p.y() >= y || p.z() < -70.0) return p;
    const double across = std::clamp(1.0 - (std::abs(p.x()) - half) / 30.0, 0.0, 1.0);
    const double down = std::clamp((y - p.y()) / 4.0, 0.0, 1.0);
    return Vec3(p + Vec3(0.0, -12.0 * across * down, -3.0 * across * down));
  });
}

//! A face in some scan's frame and units: the variant's mesh, and the frame from it into the truth's
//! canonical frame.
struct Posed {
  Mesh mesh;
  align::FaceFrame truth; //!< variant → canonical (mm)
};

//! `face` turned by up to `max_turn_deg` about a random axis, moved up to 300 mm, and stated in units of
//! `mm_per_unit` millimetres (`units` recorded in the mesh: Unknown for arbitrary units).
inline Posed posed(const FaceScan& face, unsigned seed, double mm_per_unit, Units units,
                   double max_turn_deg = 40.0) {
  std::mt19937 random(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> turn(0.0, max_turn_deg * std::numbers::pi / 180.0), shift(-300, 300);
  const Vec3 axis = Vec3(n(random), n(random), n(random)).normalized();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turn(random), axis).toRotationMatrix();
  const Vec3 t(shift(random), shift(random), shift(random));
  // scan = r · canonical / mm_per_unit + t / mm_per_unit; canonical = mm_per_unit · rᵀ · scan − rᵀ t.
  Posed out;
  out.mesh.units = units;
  out.mesh.positions.reserve(face.mesh.positions.size());
  for (const Vec3& p : face.mesh.positions)
    out.mesh.positions.push_back((r * p + t) / mm_per_unit);
  out.mesh.triangles = face.mesh.triangles;
  out.truth.rotation = r.transpose();
  out.truth.translation = -(r.transpose() * t);
  out.truth.scale = mm_per_unit;
  out.truth.scan_units = units;
  return out;
}

} // namespace pdeface::test
