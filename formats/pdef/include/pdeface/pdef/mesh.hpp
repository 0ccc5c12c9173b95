#pragma once
//! \file
//! From curves to a mesh in the scan's frame: the one path both `pipeline::reconstruct` and a decoded
//! `.pdef` take (solve the PDE surface, evaluate it on a grid, triangulate with normals, map back), so that
//! a lossless file gives the reconstruction's mesh exactly.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/pde/mesher.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/pdef.hpp"

#include <cstddef>
#include <optional>
#include <string_view>

namespace pdeface::pdef {

//! The size of the grid a surface is evaluated on: `u` points across the face, `v` along its height
//! (`u = 0`: as many as keep the cells square on average).
struct Resolution {
  std::size_t u = 0;
  std::size_t v = 0;
};

//! The most vertices a grid may have (a 2000 × 2000 grid, ~300 MB of mesh): a mistyped resolution must not
//! exhaust the machine.
inline constexpr std::size_t kMaxGridVertices = 4'000'000;

//! The default spacing between grid points (mm): about 1 mm across and along the face.
inline constexpr double kDefaultGridSpacing = 1.0;

//! A grid with about `spacing_mm` between neighbouring points across a face `width_mm` wide (border curve
//! to border curve) and `height_mm` tall (lowest to highest curve end), at least 2 × 2.
[[nodiscard]] Resolution grid_for(double width_mm, double height_mm, double spacing_mm);
//! `v` points along the height and as many across as keep the cells square on average.
[[nodiscard]] Resolution grid_for(double width_mm, double height_mm, std::size_t v);
//! The grid asked for: `asked` (u = 0: square cells for its v), else about `kDefaultGridSpacing`.
[[nodiscard]] Resolution grid_for(double width_mm, double height_mm, std::optional<Resolution> asked);

//! The face's width (first to last plane) and height (lowest to highest curve end), mm.
[[nodiscard]] std::array<double, 2> face_size(const Face& face);

//! A solved surface as a mesh with normals, in the canonical frame (mm) and mapped into the scan's frame
//! and units.
struct SurfaceMesh {
  Mesh canonical;
  Mesh scan;
};

//! `Frame::to_scan` as an affine map, p ↦ (Rᵀ/scale) p − Rᵀt/scale: what a mesher folds into the
//! surface's coefficients to make its points in the scan's frame directly.
[[nodiscard]] pde::AffineMap scan_map(const Frame& frame);

//! `surface` on `grid` (at least 2 × 2) as meshes with normals (`pde::GridMesher`): in the canonical frame,
//! and made directly in the scan's frame by `scan_map(frame)` (positions, and normals from them; units
//! those of the scan). Errors (naming `source`): `InvalidArgument` for a grid of more than
//! `kMaxGridVertices`, `NonFinite` for a frame whose map is not finite.
[[nodiscard]] Result<SurfaceMesh> surface_mesh(const pde::Surface& surface, Resolution grid,
                                               const Frame& frame, std::string_view source = {});

//! The surface a face describes, built with its own PDE options. Errors: those of `pde::Surface::build`.
[[nodiscard]] Result<pde::Surface> surface_of(const Face& face, std::string_view source = {});

//! Whether the face holds a residual layer with offsets (a version 3 file cut after its layer's header).
[[nodiscard]] bool has_offsets(const Face& face);

//! What makes `to_mesh`'s mesh: `surface` (the face's, `surface_of`) on `resolution` (default about 1 mm
//! spacing; a face with a residual layer: the layer's grid) in the scan's frame, for writers that stream the
//! mesh row by row instead of holding it (the residual's offsets are not applied: see `to_mesh`).
//! Errors: `InvalidArgument` for a grid of more than `kMaxGridVertices`, `NonFinite` for a frame whose map
//! is not finite (a scale so small that 1/scale overflows).
[[nodiscard]] Result<pde::GridMesher> scan_mesher(const Face& face, const pde::Surface& surface,
                                                  std::optional<Resolution> resolution = std::nullopt,
                                                  std::string_view source = {});

//! The face's surface as a mesh in the scan's frame and units, on `resolution` (default about 1 mm
//! spacing; with a residual layer its own grid): `scan_mesher(face, surface_of(face),
//! resolution).mesh(face.frame.scan_units)`, then each vertex moved along its normal by the layer's offset
//! there (`pde::GridMesher::displaced_mesh`; the layer's values at its nodes, bilinear between them, given
//! the moved grid's normals), named after the face; with a texture layer, textured (`with_texture`); then
//! the cells the layer's trim leaves out dropped with the vertices no triangle uses (`pde::trim_grid`).
//! Its scan mesh is `surface_mesh`'s to the bit. Errors: those of `surface_of` and `scan_mesher`; `Empty`
//! for a trim that leaves no triangle.
[[nodiscard]] Result<Mesh> to_mesh(const Face& face, std::optional<Resolution> resolution = std::nullopt,
                                   std::string_view source = {});

//! A grid mesh of the face's surface (u_count × v_count vertices, vertex (i, k) at k·u_count + i, as
//! `to_mesh` and `pde::GridMesher` make it) given the texture layer: every vertex the texture coordinate
//! (i / (u_count − 1), k / (v_count − 1)) (docs/pdef-format.md, "The texture layer"), and a material whose
//! base-colour image is `texture`. `to_mesh` does this for a face with a texture layer.
//! 	hrow std::invalid_argument for a mesh that is not such a grid
void with_texture(Mesh& mesh, std::size_t u_count, std::size_t v_count, const Image& texture);

} // namespace pdeface::pdef
