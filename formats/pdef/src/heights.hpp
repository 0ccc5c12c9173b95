#pragma once
// y as heights (docs/pdef-format.md, "Heights"): each curve's extent, the relative heights of every s-th
// curve (the anchors), blended between anchors by the planes, and what is left per sample on the grid.

#include "bytes.hpp"
#include "codec.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pdeface::pdef::detail {

//! The blend's weights are whole multiples of 2^-kBlendBits.
inline constexpr int kBlendBits = 12;
//! The finest relative heights' grid: 2^-kMaxHeightBits.
inline constexpr std::uint32_t kMaxHeightBits = 16;
//! A curve may span at most 2^kMaxSpanBits step units (4 m): the blend stays within 64 bits.
inline constexpr int kMaxSpanBits = 32;

//! The heights' y of sample (j, k) in step units (2^-20 mm) before its residual.
[[nodiscard]] std::int64_t height_units(const Heights& h, std::span<const std::int64_t> planes,
                                        std::size_t samples, std::uint32_t step, std::size_t j,
                                        std::size_t k);

//! The cheapest layout for the face's y on `grid` (`y`: its samples' y in mm, J × K), with the residuals of
//! its interior samples in `residuals` (J × K, zero at the ends) and its size in bytes; nullopt when no
//! layout fits (a curve that does not rise, samples outside their curve's extent, a curve over 4 m).
struct HeightsFit {
  Heights heights;
  std::vector<std::int64_t> residuals;
  std::size_t bytes = 0;
};
//! `only`: try just this stride and grid (a decoded file's own).
struct Layout {
  std::uint32_t stride = 0, bits = 0;
};
[[nodiscard]] std::optional<HeightsFit> fit_heights(std::span<const double> y,
                                                    std::span<const std::int64_t> planes, std::size_t samples,
                                                    const Grid& grid,
                                                    std::optional<Layout> only = std::nullopt);

//! The layout's and the residuals' bytes as the file holds them (after the y kind).
[[nodiscard]] std::string write_heights(const Heights& h, std::span<const std::int64_t> residuals,
                                        std::size_t curves, std::size_t samples);

//! Reads a layout and its residuals (J × K, zero at the ends) written by `write_heights`; false, with the
//! failure recorded in `r`, when its fields break the rules of docs/pdef-format.md or its streams do not
//! decode.
[[nodiscard]] bool read_heights(Reader& r, std::span<const std::int64_t> planes, std::size_t samples,
                                std::uint32_t step, Heights& h, std::vector<std::int64_t>& residuals);

} // namespace pdeface::pdef::detail
