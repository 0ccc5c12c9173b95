#pragma once
//! \file
//! The one similarity transform every layer uses (landmark search, alignment, the `.pdef` codec, the
//! pipeline), and the face frame built on it.
//!
//! Canonical face frame: origin at the nose tip, +x across the face from its right to its left (the
//! normal of the symmetry plane), +y up (chin to forehead), +z out of the face towards the viewer,
//! millimetres. A `FaceFrame` takes a scan into it and remembers the scan's units, so that results made
//! in the canonical frame (profiles, a PDE surface) can be mapped back into the scan's own frame and units.

#include "pdeface/core/mesh.hpp"

#include <Eigen/Core>

namespace pdeface {

//! q = scale · rotation · p + translation.
struct Similarity {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); //!< proper rotation (det +1)
  Vec3 translation = Vec3::Zero();                        //!< in the target frame's units
  double scale = 1.0;                                     //!< target units per source unit

  //! q = scale · rotation · p + translation.
  [[nodiscard]] Vec3 apply(const Vec3& p) const { return scale * (rotation * p) + translation; }
  //! The p that `apply` takes to q: rotationᵀ · (q − translation) / scale. Computed from this similarity
  //! as it is (not through `inverse()`), so that mapping back gives the same bits wherever it is done.
  [[nodiscard]] Vec3 apply_inverse(const Vec3& q) const {
    return rotation.transpose() * ((q - translation) / scale);
  }

  //! The similarity that undoes this one: `inverse().apply(apply(p))` is p up to rounding.
  [[nodiscard]] Similarity inverse() const {
    const Eigen::Matrix3d back = rotation.transpose();
    return {back, -(back * translation) / scale, 1.0 / scale};
  }
  //! This similarity after `first`: `second.after(first).apply(p)` is `second.apply(first.apply(p))` up to
  //! rounding.
  [[nodiscard]] Similarity after(const Similarity& first) const {
    return {rotation * first.rotation, scale * (rotation * first.translation) + translation,
            scale * first.scale};
  }
  //! The same rotation and the same source point at the target's origin, at another scale: what a search
  //! that tries a face at several sizes moves between (translation × new_scale / scale).
  [[nodiscard]] Similarity with_scale(double new_scale) const {
    Similarity out = *this;
    out.translation *= new_scale / scale;
    out.scale = new_scale;
    return out;
  }
};

//! A scan's frame: the similarity from the scan into the canonical face frame (p_canonical = scale ·
//! rotation · p_scan + translation; translation in mm, scale in millimetres per scan unit) and the units
//! the scan was found to be in. `align` finds it; a `.pdef` stores it (as `pdef::Frame`).
struct FaceFrame : Similarity {
  Units scan_units = Units::Unknown; //!< the units of the scan's frame

  [[nodiscard]] Vec3 to_canonical(const Vec3& p) const { return apply(p); }
  [[nodiscard]] Vec3 to_scan(const Vec3& q) const { return apply_inverse(q); }
  //! The canonical frame's axes and origin expressed in the scan's frame.
  [[nodiscard]] Vec3 axis_in_scan(int axis) const { return rotation.row(axis).transpose(); }
  [[nodiscard]] Vec3 origin_in_scan() const { return to_scan(Vec3::Zero()); }
};

} // namespace pdeface
