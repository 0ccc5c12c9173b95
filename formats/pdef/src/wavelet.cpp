// CDF 9/7 lifting (Daubechies & Sweldens 1998; the JPEG 2000 irreversible transform's steps) on rows, then
// columns, of the low band, level after level. Every operation is a separate multiply and add in double
// (the file is compiled without contraction), so every platform decodes the same offsets.

#include "wavelet.hpp"

#include <algorithm>

namespace pdeface::pdef::detail {
namespace {

constexpr double kAlpha = -1.586134342059924;
constexpr double kBeta = -0.052980118572961;
constexpr double kGamma = 0.882911075530934;
constexpr double kDelta = 0.443506852043971;
// Low and high coefficients scaled by the norms of one level's synthesis functions (computed from the
// steps above), so that each has unit norm at the first level and 0.95-1.16 at every level down to the
// fifth: one quantisation step then suits every subband within a fifth of a bit.
constexpr double kLowScale = 1.139764007654642;
constexpr double kHighScale = 0.887277075635907;

// One-dimensional lifting on `n` values `x[0], x[stride], ...`, using `tmp` (n values).
void forward_line(double* x, std::size_t n, std::size_t stride, std::vector<double>& tmp) {
  if (n < 2) return;
  tmp.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    tmp[i] = x[i * stride];
  double* t = tmp.data();
  const std::size_t last = n - 1;
  auto lift_odd = [&](double c) { // x[2i+1] += c (x[2i] + x[2i+2]), x[n] = x[n-2]
    for (std::size_t i = 1; i < n; i += 2)
      t[i] = t[i] + c * (t[i - 1] + t[i + 1 <= last ? i + 1 : i - 1]);
  };
  auto lift_even = [&](double c) { // x[2i] += c (x[2i-1] + x[2i+1]), x[-1] = x[1], x[n] = x[n-2]
    for (std::size_t i = 0; i < n; i += 2)
      t[i] = t[i] + c * (t[i == 0 ? 1 : i - 1] + t[i + 1 <= last ? i + 1 : i - 1]);
  };
  lift_odd(kAlpha);
  lift_even(kBeta);
  lift_odd(kGamma);
  lift_even(kDelta);
  const std::size_t lows = (n + 1) / 2;
  for (std::size_t i = 0; i < n; i += 2)
    x[(i / 2) * stride] = t[i] * kLowScale;
  for (std::size_t i = 1; i < n; i += 2)
    x[(lows + i / 2) * stride] = t[i] * kHighScale;
}

void inverse_line(double* x, std::size_t n, std::size_t stride, std::vector<double>& tmp) {
  if (n < 2) return;
  tmp.resize(n);
  const std::size_t lows = (n + 1) / 2;
  double* t = tmp.data();
  for (std::size_t i = 0; i < n; i += 2)
    t[i] = x[(i / 2) * stride] / kLowScale;
  for (std::size_t i = 1; i < n; i += 2)
    t[i] = x[(lows + i / 2) * stride] / kHighScale;
  const std::size_t last = n - 1;
  auto lift_odd = [&](double c) {
    for (std::size_t i = 1; i < n; i += 2)
      t[i] = t[i] - c * (t[i - 1] + t[i + 1 <= last ? i + 1 : i - 1]);
  };
  auto lift_even = [&](double c) {
    for (std::size_t i = 0; i < n; i += 2)
      t[i] = t[i] - c * (t[i == 0 ? 1 : i - 1] + t[i + 1 <= last ? i + 1 : i - 1]);
  };
  lift_even(kDelta);
  lift_odd(kGamma);
  lift_even(kBeta);
  lift_odd(kAlpha);
  for (std::size_t i = 0; i < n; ++i)
    x[i * stride] = t[i];
}

} // namespace

Bands::Bands(std::size_t width, std::size_t height, std::size_t levels) {
  widths.push_back(width);
  heights.push_back(height);
  for (std::size_t l = 0; l < levels; ++l) {
    widths.push_back((widths.back() + 1) / 2);
    heights.push_back((heights.back() + 1) / 2);
  }
}

std::size_t levels_for(std::size_t width, std::size_t height) {
  std::size_t levels = 0;
  while (levels < kMaxLevels && std::min(width, height) >= 8) {
    width = (width + 1) / 2;
    height = (height + 1) / 2;
    ++levels;
  }
  return levels;
}

void forward_97(std::vector<double>& image, std::size_t width, std::size_t height, std::size_t levels) {
  const Bands bands(width, height, levels);
  std::vector<double> tmp;
  for (std::size_t l = 0; l < levels; ++l) {
    const std::size_t w = bands.widths[l], h = bands.heights[l];
    for (std::size_t k = 0; k < h; ++k)
      forward_line(image.data() + k * width, w, 1, tmp);
    for (std::size_t i = 0; i < w; ++i)
      forward_line(image.data() + i, h, width, tmp);
  }
}

void inverse_97(std::vector<double>& image, std::size_t width, std::size_t height, std::size_t levels) {
  const Bands bands(width, height, levels);
  std::vector<double> tmp;
  for (std::size_t l = levels; l-- > 0;) {
    const std::size_t w = bands.widths[l], h = bands.heights[l];
    for (std::size_t i = 0; i < w; ++i)
      inverse_line(image.data() + i, h, width, tmp);
    for (std::size_t k = 0; k < h; ++k)
      inverse_line(image.data() + k * width, w, 1, tmp);
  }
}

} // namespace pdeface::pdef::detail
