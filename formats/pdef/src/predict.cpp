// Prediction of the lossy samples from their neighbours along and across curves (integers only, so that
// every platform decodes the same values).

#include "codec.hpp"

namespace pdeface::pdef::detail {

std::int64_t predict(std::span<const std::int64_t> a, std::size_t samples, std::size_t j, std::size_t k) {
  const auto at = [&](std::size_t jj, std::size_t kk) { return a[jj * samples + kk]; };
  if (j > 0 && k > 1) // the previous curve's value, corrected by how this curve's last two steps differ
    return at(j - 1, k) + 2 * at(j, k - 1) - at(j, k - 2) - 2 * at(j - 1, k - 1) + at(j - 1, k - 2);
  if (j > 0 && k == 1) return at(j - 1, k) + at(j, k - 1) - at(j - 1, k - 1);
  if (j > 0) return at(j - 1, k);
  if (k > 1) return 2 * at(j, k - 1) - at(j, k - 2);
  if (k == 1) return at(j, k - 1);
  return 0;
}

std::vector<std::uint32_t> to_symbols(std::span<const std::int64_t> values, std::size_t samples) {
  std::vector<std::uint32_t> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::int64_t r = values[i] - predict(values, samples, i / samples, i % samples);
    const auto u = static_cast<std::uint64_t>((r << 1) ^ (r >> 63));
    out[i] = static_cast<std::uint32_t>(u); // |r| < 2^31 for |values| ≤ kMaxQuantised
  }
  return out;
}

bool from_symbols(std::span<const std::uint32_t> symbols, std::size_t samples,
                  std::span<std::int64_t> values) {
  for (std::size_t i = 0; i < symbols.size(); ++i) {
    const std::uint32_t u = symbols[i];
    const std::int64_t r = static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
    const std::int64_t v = predict(values, samples, i / samples, i % samples) + r;
    if (v > kMaxQuantised || v < -kMaxQuantised) return false;
    values[i] = v;
  }
  return true;
}

} // namespace pdeface::pdef::detail
