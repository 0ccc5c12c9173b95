#pragma once
// How far each curve reaches: from the nose tip's height down and up its plane's section, within the
// region (the face mask grown), through holes, stopping where the surface ends or turns away; notches
// closed from the neighbours, extents kept to the outline's slope. And what the scan lacks of the face.

#include "pdeface/slice/planes.hpp"
#include "pdeface/slice/profiles.hpp"

#include <span>
#include <string>
#include <vector>

namespace pdeface::slice::detail {

struct Extents {
  std::vector<std::array<double, 2>> extent;  //!< what each curve spans
  std::vector<std::array<double, 2>> surface; //!< the stretch of its own surface that holds the seed
  std::vector<std::array<ReachEnd, 2>> ends;  //!< why the bottom and the top are where they are
};

[[nodiscard]] Extents curve_extents(std::span<const Section> cuts, std::span<const ProfilePlane> planes,
                                    const FaceMask& region, const align::Landmarks& landmarks,
                                    const ProfileOptions& options, double max_hole);

//! The share of the face mask where the scan has surface: sections across the mask every 4 mm, each sampled
//! every 2 mm of height inside it.
[[nodiscard]] double mask_coverage(const Mesh& canonical, const FaceMask& mask,
                                   const SectionOptions& section);

//! The same judged on the curves' own sections, each standing for the stretch of the mask nearer to it than
//! to any other curve (the mask beyond the border curves counts as missing).
[[nodiscard]] double mask_coverage(std::span<const Section> cuts, std::span<const ProfilePlane> planes,
                                   const FaceMask& mask);

//! What the curves lack of the mask, in words: runs of curves that end short of the mask's outline because
//! the surface ends, and sides cut short.
[[nodiscard]] std::vector<std::string> missing_parts(const ProfileSet& set, const PlaneLayout& layout);

} // namespace pdeface::slice::detail
