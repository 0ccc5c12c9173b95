#pragma once
// The residual layer's transform (docs/pdef-format.md, "The residual layer"): a two-dimensional CDF 9/7
// lifting wavelet with symmetric borders, scaled to be close to orthonormal, on any width and height.

#include <cstddef>
#include <vector>

namespace pdeface::pdef::detail {

//! The subbands of a width × height image after `levels` levels (Mallat layout): widths[l], heights[l]
//! are the low band's size after l levels (widths[0] = width).
struct Bands {
  std::vector<std::size_t> widths, heights;
  Bands(std::size_t width, std::size_t height, std::size_t levels);
};

//! The most levels a width × height grid takes (each level halves both sizes, the low band stays at least
//! 4 × 4 where the grid is), at most `kMaxLevels`.
inline constexpr std::size_t kMaxLevels = 8;
[[nodiscard]] std::size_t levels_for(std::size_t width, std::size_t height);

//! In place, row-major (node (i, k) at k·width + i). Forward: image → coefficients; inverse: back.
void forward_97(std::vector<double>& image, std::size_t width, std::size_t height, std::size_t levels);
void inverse_97(std::vector<double>& image, std::size_t width, std::size_t height, std::size_t levels);

} // namespace pdeface::pdef::detail
