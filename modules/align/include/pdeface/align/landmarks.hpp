#pragma once
//! \file
//! Named facial landmarks as data: read and written as JSON, and read from menpo's LJSON (iBUG 68 points).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace pdeface::align {

//! The landmarks of the paper. Left and right are the face's own (its left eye is at +x in the
//! canonical frame, on the viewer's right).
enum class Landmark {
  NoseTip,
  EyeInnerLeft,
  EyeInnerRight,
  EyeOuterLeft,
  EyeOuterRight,
  MouthLeft,
  MouthRight,
  FaceTop,    //!< top of the face region on the symmetry line (forehead)
  FaceBottom, //!< bottom of the face region on the symmetry line (chin)
};
inline constexpr std::size_t kLandmarkCount = 9;

//! "nose_tip", "eye_inner_left", ...
[[nodiscard]] std::string_view name(Landmark landmark) noexcept;
[[nodiscard]] std::optional<Landmark> landmark_from_name(std::string_view name) noexcept;
//! The landmark's mirror image across the symmetry plane (left <-> right; itself on the midline).
[[nodiscard]] Landmark mirrored(Landmark landmark) noexcept;

//! A set of landmark positions, any of which may be missing.
struct Landmarks {
  std::array<std::optional<Vec3>, kLandmarkCount> points;
  Units units = Units::Unknown;

  [[nodiscard]] const std::optional<Vec3>& operator[](Landmark l) const {
    return points[static_cast<std::size_t>(l)];
  }
  [[nodiscard]] std::optional<Vec3>& operator[](Landmark l) { return points[static_cast<std::size_t>(l)]; }
  [[nodiscard]] bool has(Landmark l) const { return (*this)[l].has_value(); }
  [[nodiscard]] std::size_t count() const;
};

//! Parses our landmark JSON:
//! `{"format": "pdeface-landmarks", "version": 1, "units": "mm", "landmarks": {"nose_tip": [x, y, z], ...}}`.
//! Unknown landmark names, non-numeric or non-finite coordinates are errors with the JSON position.
[[nodiscard]] Result<Landmarks> read_landmarks_json(std::string_view bytes, std::string_view source);
[[nodiscard]] std::string write_landmarks_json(const Landmarks& landmarks);

//! Parses menpo's LJSON (version 1-3: `groups` -> `labels` -> `mask` into `landmarks.points`, or the flat
//! version-1 layout) with the 68-point iBUG convention and maps it onto our names: nose tip, eye and mouth
//! corners by position inside their labelled groups, face bottom = the chin point of the jaw line. The
//! iBUG set has no forehead point: `face_top` stays missing.
[[nodiscard]] Result<Landmarks> read_ljson(std::string_view bytes, std::string_view source);

//! Either format, told apart by content: menpo LJSON (has "groups" or a top-level "landmarks" with
//! "points") or ours.
[[nodiscard]] Result<Landmarks> read_landmarks(std::string_view bytes, std::string_view source);

} // namespace pdeface::align
