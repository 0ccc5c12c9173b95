#pragma once
//! \file
//! The whole method on one scan: aligned scan → profile curves → PDE surface → a mesh in the scan's frame.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/slice/profiles.hpp"

#include <cstddef>
#include <optional>

namespace pdeface::pipeline {

//! A scan moved into the canonical frame (mm) with its landmarks there and the frame back to the scan:
//! what slicing, reconstructing and measuring work on.
struct CanonicalScan {
  Mesh mesh;
  align::Landmarks landmarks;
  align::FaceFrame frame;
};
//! (`scan` by value: a scan moved in is mapped in place, not copied.)
[[nodiscard]] CanonicalScan canonical_scan(Mesh scan, const align::Alignment& alignment);

//! `slice::extract_profiles` on a canonical scan.
[[nodiscard]] Result<slice::ProfileSet> extract_profiles(const CanonicalScan& scan,
                                                         const slice::ProfileOptions& options = {});

//! The profile curves as the PDE's boundary data: curve j is `profiles.curves[j].points` (K × 3, chin to
//! forehead, so v = 0 at the bottom), in the canonical frame, mm.
[[nodiscard]] pde::Curves to_curves(const slice::ProfileSet& profiles);

//! The size of the grid a surface is evaluated on: `u` points across the face, `v` along its height
//! (`u = 0`: as many as keep the cells square on average, `resolution_for(profiles, v)`). The one a decoded
//! `.pdef` uses too.
using Resolution = pdef::Resolution;

//! The most vertices a reconstruction grid may have (a 2000 × 2000 grid, ~300 MB of mesh): a mistyped
//! resolution must not exhaust the machine.
inline constexpr std::size_t kMaxGridVertices = pdef::kMaxGridVertices;

//! A grid with about `spacing_mm` between neighbouring points across (border to border) and along (the
//! height range) the face, at least 2 × 2.
[[nodiscard]] Resolution resolution_for(const slice::ProfileSet& profiles, double spacing_mm);

//! `v` points along the face's height and as many across as keep the grid's cells square on average.
[[nodiscard]] Resolution resolution_for(const slice::ProfileSet& profiles, std::size_t v);

struct ReconstructOptions {
  slice::ProfileOptions profiles;
  //! Curves placed in u by their physical spacing: the 28 planes are not evenly spaced (joints at
  //! features), and on the facefuns scans this lowers the spline's mean surface distance at 10 % from
  //! 0.234 to 0.194 mm (docs/paper-table.md).
  pde::Options pde{.spacing = pde::Spacing::Physical};
  std::optional<Resolution> resolution; //!< default: `resolution_for(profiles, grid_spacing_mm)`
  double grid_spacing_mm = 1.0;
};

//! What reconstruction made, from the curves to the mesh.
struct Reconstruction {
  slice::ProfileSet profiles; //!< the curves (canonical frame, mm): all the representation needs
  pde::Surface surface;       //!< solved once; evaluate it at any other resolution
  Resolution grid;            //!< what the surface was evaluated on
  Mesh canonical;             //!< the surface as a mesh with normals, canonical frame, mm
  Mesh scan;                  //!< the same mesh in the scan's own frame and units
};

//! The surface through `profiles` (`to_curves`) with `options`; errors name `source`.
[[nodiscard]] Result<pde::Surface> surface_from(const slice::ProfileSet& profiles,
                                                const pde::Options& options, std::string_view source = {});

//! The method on `scan` (any frame and units) with its `alignment`: the scan moved into the canonical
//! frame, sliced into curves (`slice::extract_profiles`), the PDE surface solved through them and
//! triangulated, and the mesh mapped back with the alignment's frame (`pdef::surface_mesh`: what a decoded
//! `.pdef` does, so that a lossless file gives this mesh exactly). Errors: those of each stage, and
//! `InvalidArgument` for a grid of more than `kMaxGridVertices`; `source` (the scan's name) set.
[[nodiscard]] Result<Reconstruction> reconstruct(const Mesh& scan, const align::Alignment& alignment,
                                                 const ReconstructOptions& options = {},
                                                 std::string_view source = {});
//! The same on a scan already in the canonical frame (`canonical_scan`).
[[nodiscard]] Result<Reconstruction>
reconstruct(const CanonicalScan& scan, const ReconstructOptions& options = {}, std::string_view source = {});

} // namespace pdeface::pipeline
