#pragma once
//! \file
//! A synthetic face scan made by code: the built-in sample for the README's main job and for tests that
//! must run without real scans.
//!
//! A height field z = f(x, y) in millimetres, in the canonical face frame (x across the face from its
//! right to its left, y up, z towards the viewer, nose tip near the origin), with a forehead, brows, eye
//! sockets, nose with wings, lips, chin and cheekbones at adult proportions. It is sampled like a range
//! scanner: a regular grid seen from +z, a ragged outline, a little noise and a few holes.

#include "pdeface/core/mesh.hpp"

#include <cstdint>

namespace pdeface {

struct SampleFaceOptions {
  double spacing_mm = 1.25; //!< grid step; 1.25 mm gives ~15k vertices, inside the paper's 12k-51k range
  double noise_mm = 0.05;   //!< amplitude of the deterministic depth noise (uniform in ±noise_mm)
  bool holes = true;        //!< punch a few small holes, as dropouts in a real scan
  bool colors = true;       //!< per-vertex skin colours (lips redder, brows darker)
  std::uint32_t seed = 1;   //!< changes the outline and noise, never the shape
};

//! Where the sample's landmarks are, in mm (the same frame as the height field; z on the surface).
struct SampleFaceLandmarks {
  Vec3 nose_tip{0.0, 0.0, 0.0};
  Vec3 eye_inner_left{17.0, 29.0, 0.0}, eye_inner_right{-17.0, 29.0, 0.0};
  Vec3 eye_outer_left{46.0, 30.0, 0.0}, eye_outer_right{-46.0, 30.0, 0.0};
  Vec3 mouth_left{23.0, -30.5, 0.0}, mouth_right{-23.0, -30.5, 0.0};
};
//! The landmarks of the sample face, z filled in from the height field.
[[nodiscard]] SampleFaceLandmarks sample_face_landmarks();

//! The noiseless height field, in mm: z of the face at (x, y).
[[nodiscard]] double sample_face_height(double x, double y);

//! The sample scan. Deterministic: the same options give the same bytes on every platform.
//! \throw std::invalid_argument if spacing_mm is not in [0.2, 20] or noise_mm is negative.
[[nodiscard]] Mesh sample_face(const SampleFaceOptions& options = {});

} // namespace pdeface
