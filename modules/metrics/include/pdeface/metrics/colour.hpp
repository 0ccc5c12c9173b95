#pragma once
//! \file
//! The colour of a mesh's surface where a point lies on it (its photograph through its texture coordinates,
//! else its vertex colours), and how far one surface's colours are from another's: PSNR over 8-bit sRGB
//! and ΔE₀₀ (CIEDE2000) in CIELAB, as image and colour scientists measure them.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/image/image.hpp"
#include "pdeface/metrics/surface_distance.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace pdeface::metrics {

//! Where a mesh's colour comes from.
enum class ColourSource { None, Texture, VertexColours };

//! The colour of a mesh at points of its surface, 8-bit sRGB as [0, 1]. Built once (its photograph
//! decoded, its corners' texture coordinates gathered); queries are const and thread-safe. A mesh with a
//! texture (an image with bytes and texture coordinates) is coloured by it, else by its vertex colours
//! (linear, turned into sRGB), else it has none.
class SurfaceColour {
public:
  //! \pre `mesh` outlives the object. Errors: those of decoding the mesh's image (naming `source`).
  static Result<SurfaceColour> of(const Mesh& mesh, std::string_view source);

  [[nodiscard]] ColourSource source() const { return source_; }
  //! The colour at `point`, which lies on (or near) triangle `triangle` (a point cloud: at point
  //! `triangle`): barycentric in the triangle's corners' texture coordinates or colours.
  [[nodiscard]] std::optional<Eigen::Vector3f> at(const Vec3& point, std::size_t triangle) const;

private:
  explicit SurfaceColour(const Mesh& mesh) : mesh_(&mesh) {}
  const Mesh* mesh_;
  ColourSource source_ = ColourSource::None;
  image::Pixels pixels_;
  std::vector<Vec2f> corners_; //!< texture coordinates per corner (3 a triangle)
};

//! CIELAB (D65 white, the CIE 1976 formulas) of an sRGB colour in [0, 1].
[[nodiscard]] Eigen::Vector3d srgb_to_lab(const Eigen::Vector3f& srgb);
//! The CIEDE2000 colour difference of two CIELAB colours (kL = kC = kH = 1; Sharma, Wu and Dalal 2005).
[[nodiscard]] double delta_e2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2);

//! How far one surface's colours are from a reference's at the same places.
struct ColourError {
  double psnr_db = 0.0; //!< 10 log10(255² / MSE) over the R, G and B of every point (8-bit); +inf: equal
  double mean_delta_e = 0.0; //!< ΔE₀₀
  double p95_delta_e = 0.0;
  std::size_t samples = 0;    //!< points measured
  std::size_t uncoloured = 0; //!< points where the tested surface had no colour
};

//! The colours of `reference` at `points` (each on it: found by its nearest point) against those of `test`
//! at its nearest points to them. Points `test` has no colour at count as black (and in `uncoloured`).
//! \throw std::invalid_argument for an empty list of points or a reference without colour
[[nodiscard]] ColourError colour_error(const SurfaceColour& reference, const SurfaceDistance& on_reference,
                                       const SurfaceColour& test, const SurfaceDistance& on_test,
                                       std::span<const Vec3> points);

} // namespace pdeface::metrics
