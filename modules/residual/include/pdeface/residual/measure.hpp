#pragma once
//! \file
//! How far a scan lies from a PDE surface along the surface's normal, over the surface's whole (u, v)
//! domain: the image a `.pdef` residual layer codes (docs/pdef-format.md, "The residual layer";
//! docs/residual.md). Geometry only: the layer's bytes are `formats/pdef`'s.

#include "pdeface/core/mesh.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/pde/displacement.hpp"
#include "pdeface/pde/surface.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pdeface::residual {

struct MeasureOptions {
  //! Offsets beyond this (mm) are not the surface's own: the line along the normal found no scan near it.
  double max_offset_mm = 6.0;
  //! A node is measured when the point found along its normal lies within this of the scan (mm).
  double tolerance_mm = 0.02;
  //! Where the line along the normal meets no scan but the scan lies within this (mm) of the surface
  //! point (a hole's rim, the scan's edge), the offset is that of the scan's nearest point along the
  //! normal; 0: such nodes are filled from their neighbours.
  double rim_reach_mm = 0.0;
};

//! The offsets of a scan from a surface on a grid (`pde::Displacement`), and which nodes found the scan.
struct Measured {
  pde::Displacement field;         //!< measured offsets; elsewhere filled smoothly (`fill`)
  std::vector<std::uint8_t> found; //!< 1 where the node's normal line met the scan
  [[nodiscard]] double found_share() const;
};

//! Where the line through `x` along the unit normal `n` meets `scan` nearest to `x` (within
//! `options.max_offset_mm`; a hole's rim within `options.rim_reach_mm` when that is set): the point, the
//! triangle holding it (a point cloud: the point's index) and its signed offset along `n`. `distance` is
//! `scan`'s. Not found for a zero normal or a line that meets no scan.
struct Hit {
  Vec3 point = Vec3::Zero();
  std::size_t triangle = 0;
  double offset = 0.0;
  bool found = false;
};
[[nodiscard]] Hit along_normal(const metrics::SurfaceDistance& distance, const Mesh& scan, const Vec3& x,
                               const Vec3& n, const MeasureOptions& options = {});

//! A width × height grid over the surface's domain (node (i, k) at u = i·u_max/(width − 1), v =
//! k·π/(height − 1)): at each node, the signed distance t along the unit normal n from X(u, v) to the scan
//! (`scan`, a mesh or point cloud in the surface's frame and units) nearest to t = 0, |t| ≤
//! `max_offset_mm`; nodes whose line meets no scan (holes, beyond the scan's edge) are filled smoothly
//! from their neighbours (`fill`), so that they cost next to nothing to code.
//! \throw std::invalid_argument for fewer than 2 nodes either way or an empty scan
[[nodiscard]] Measured measure(const pde::Surface& surface, const Mesh& scan, std::size_t width,
                               std::size_t height, const MeasureOptions& options = {});

//! When a cell of a measured grid holds no surface (`trimmed`). The surface X + d·n over a cell is the
//! scan's where the normal lines found it and the scan is continuous between them; elsewhere the layer
//! spans what the scan does not have: a hole (an eye of a morphable model, an open mouth, a capture gap),
//! beyond the scan's edge, a cavity the normal lines cannot enter (a nostril), or a cell between two sheets
//! of a fold.
struct TrimOptions {
  //! A point of the measured surface farther than this from the scan (mm) is off it.
  double off_scan_mm = 0.1;
  //! A cell is torn (its corners on two sheets of the scan) where the offsets of two of its corners differ
  //! by more than this times their distance on the curves' surface (a slope of 2: 63° from it).
  double tear_slope = 2.0;
};

//! The cells of `measured`'s grid (cell (i, k) between nodes (i, k) and (i + 1, k + 1), at k·(width − 1) +
//! i) that hold no surface of `scan` (1): a cell with a corner whose normal line found no scan and whose
//! filled position lies off the scan, and a torn cell whose centre or the middle of a side lies off the
//! scan. Every other cell is kept, however far its surface lies from the scan between its corners (curved
//! scan, a coarse grid): its error is counted, not hidden. `surface` and `scan` as given to `measure`.
[[nodiscard]] std::vector<std::uint8_t> trim(const pde::Surface& surface, const Mesh& scan,
                                             const Measured& measured, const TrimOptions& options = {});

//! The offsets to code for `measured` with `trimmed` (`trim`'s cells): the measured value at every node a
//! kept cell uses, filled smoothly (`fill`) at the nodes only trimmed cells use — their values shape no
//! surface once trimmed, and where a writer leaves the trim out (too few bytes) the surface there is the
//! smooth fill instead of the crossings of a fold or a cavity.
[[nodiscard]] pde::Displacement kept_field(const Measured& measured,
                                           const std::vector<std::uint8_t>& trimmed);

//! Replaces the values where `found` is 0 by a smooth continuation of the others (a pull-push pyramid
//! then relaxation towards a harmonic fill); all zero when nothing was found.
void fill(pde::Displacement& field, const std::vector<std::uint8_t>& found);

//! The grid a layer of about `spacing_mm` between nodes takes on a surface (border curve to border curve
//! across, the longest curve along; at least 2 × 2).
struct GridSize {
  std::size_t width = 2;
  std::size_t height = 2;
};
[[nodiscard]] GridSize grid_for(const pde::Surface& surface, double spacing_mm);

} // namespace pdeface::residual
