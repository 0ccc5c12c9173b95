#pragma once
// What the encoder and decoder share: the format's constants, the lossy grid and the samples as integers
// on it, and the prediction that turns them into small residuals.

#include "pdeface/pdef/pdef.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pdeface::pdef::detail {

inline constexpr std::uint8_t kVersion = 2;
inline constexpr std::uint8_t kFlagLossless = 0x01;
inline constexpr std::uint8_t kKnownFlags = kFlagLossless;
inline constexpr std::size_t kHeaderBytes = 10; // magic, version, flags, length
inline constexpr std::size_t kChecksumBytes = 4;
inline constexpr std::size_t kMinFileBytes = kHeaderBytes + kChecksumBytes;

//! The sections' tags.
inline constexpr std::uint8_t kTagFace = 1;
inline constexpr std::uint8_t kTagCurves = 2;
inline constexpr std::uint8_t kTagLandmarks = 3;
inline constexpr std::uint8_t kTagName = 4;
inline constexpr std::uint8_t kFirstAncillaryTag = 0x80;
//! The texture layer: an ancillary section (readers of shape alone skip it), at most once.
inline constexpr std::uint8_t kTagTexture = 0x80;
inline constexpr std::uint8_t kTextureJpeg = 1;

//! Lossy steps are whole multiples of 2^-20 mm, so that every decoded value is an exact binary fraction.
inline constexpr double kStepUnit = 1.0 / 1048576.0;
//! The planes' grid is this many times finer than the samples' (28 numbers: almost free).
inline constexpr std::uint32_t kPlaneRefinement = 8;
//! The largest magnitude of a quantised coordinate (in steps): far beyond any face, and small enough
//! that predictions and residuals stay well inside 64 (and zigzagged residuals inside 32) bits.
inline constexpr std::int64_t kMaxQuantised = std::int64_t{1} << 26;

//! Steps stay below 2^26 units (64 mm), so that a value (at most 2^26 steps) times its step is an exact
//! integer below 2^52 before it is scaled by 2^-20: decoding involves no rounding at all.
inline constexpr std::uint32_t kMaxStepUnits = std::uint32_t{1} << 26;

//! The lossy grid, in multiples of `kStepUnit`.
struct Grid {
  std::uint32_t step = 1;
  std::uint32_t plane_step = 1;
  [[nodiscard]] double step_mm() const { return step * kStepUnit; }
  [[nodiscard]] double plane_step_mm() const { return plane_step * kStepUnit; }
};

//! A layout of heights on a grid (`Quantised::heights`); `stride` 0 when y is predicted sample by sample.
struct Heights {
  std::uint32_t stride = 0; //!< anchors: the curves j with j mod stride = 0 (stride divides J − 1)
  std::uint32_t bits = 0;   //!< relative heights in units of 2^-bits
  std::vector<std::int64_t> bottom, top; //!< each curve's extent, in steps
  std::vector<std::int64_t> table;       //!< anchor a's interior heights k = 1..K−2 at a·(K−2) + k − 1
  bool symmetric = false;                //!< anchor A − 1 − a's heights are anchor a's (not stored)
  [[nodiscard]] bool used() const { return stride != 0; }
};

//! The samples on a grid: planes[j], y[j·K + k], z[j·K + k] in steps; with `heights` used, y holds each
//! sample's residual from its height (zero at the curves' ends).
struct Quantised {
  std::size_t curves = 0;
  std::size_t samples = 0;
  std::vector<std::int64_t> planes;
  std::vector<std::int64_t> y;
  std::vector<std::int64_t> z;
  Heights heights;
};

//! round(n / d) for d > 0, halves away from zero (n ± d/2 stays within 64 bits where 2n might not).
[[nodiscard]] inline std::int64_t rounded_div(std::int64_t n, std::int64_t d) {
  return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

//! Signed ↔ unsigned symbols (0, −1, 1, −2, … ↔ 0, 1, 2, 3, …), for values within ±2^31.
[[nodiscard]] inline std::uint32_t zigzag32(std::int64_t v) {
  return static_cast<std::uint32_t>((static_cast<std::uint64_t>(v) << 1) ^
                                    static_cast<std::uint64_t>(v >> 63));
}
[[nodiscard]] inline std::int64_t unzigzag32(std::uint32_t u) {
  return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
}

//! The prediction's weights (fixed point, kWeightBits fractional bits), one set per coordinate.
inline constexpr std::size_t kFeatures = 7;
inline constexpr int kWeightBits = 12;
inline constexpr std::int32_t kMaxWeight = (1 << 15) - 1;
using Weights = std::array<std::int32_t, kFeatures>;
//! The weights a file uses unless it stores its own: least squares on ten of the shared scans at 10 %
//! (docs/pdef-format.md, "Prediction"), good from 5 to 15 %.
inline constexpr std::array<Weights, 2> kDefaultWeights{
    {{3621, 82, 3395, -3123, 141, 292, -324}, {3635, -744, 225, -101, 897, 310, -659}}};

//! The prediction of sample (j, k) of one coordinate from those decoded before it (curves 0..j−1 whole,
//! samples 0..k−1 of curve j) and the planes: docs/pdef-format.md, "Prediction".
[[nodiscard]] std::int64_t predict(std::span<const std::int64_t> values, std::span<const std::int64_t> planes,
                                   std::size_t samples, const Weights& w, std::size_t j, std::size_t k);
//! The weights that predict `values` best (least squares over the curves from the third on), rounded.
[[nodiscard]] Weights fit_weights(std::span<const std::int64_t> values, std::span<const std::int64_t> planes,
                                  std::size_t samples);

//! Residuals ↔ values (zigzag symbols), in the order samples are coded.
[[nodiscard]] std::vector<std::uint32_t> to_symbols(std::span<const std::int64_t> values,
                                                    std::span<const std::int64_t> planes, std::size_t samples,
                                                    const Weights& w);
//! One coordinate's values predicted sample by sample as a file holds them: the weights' kind (0: the
//! default weights of `coordinate`, 1: the file's own, which follow) and the residuals' classes, whichever
//! is smaller.
[[nodiscard]] std::string write_predicted(std::span<const std::int64_t> values,
                                          std::span<const std::int64_t> planes, std::size_t samples,
                                          std::size_t coordinate);
//! The y kind of a file whose y is stored as heights (after kinds 0 and 1 of `write_predicted`).
inline constexpr std::uint8_t kHeightsKind = 2;

//! False when a value leaves ±kMaxQuantised (a corrupt stream): `values` is then incomplete.
[[nodiscard]] bool from_symbols(std::span<const std::uint32_t> symbols, std::span<const std::int64_t> planes,
                                std::size_t samples, const Weights& w, std::span<std::int64_t> values);

} // namespace pdeface::pdef::detail
