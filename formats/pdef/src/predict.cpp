// Prediction of the lossy samples from their neighbours along and across curves: integers only, so that
// every platform decodes the same values (docs/pdef-format.md, "Prediction").

#include "codec.hpp"

#include "bytes.hpp"
#include "entropy.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace pdeface::pdef::detail {
namespace {

constexpr std::int64_t kFeatureLimit = std::int64_t{1} << 30;

// The features of sample (j, k), j >= 2 (docs/pdef-format.md): differences between the curve and the one
// before along the curve, and the previous two curves' difference scaled by the planes' spacing.
std::array<std::int64_t, kFeatures> features(std::span<const std::int64_t> a,
                                             std::span<const std::int64_t> planes, std::size_t samples,
                                             std::size_t j, std::size_t k) {
  const auto at = [&](std::size_t jj, std::size_t kk) { return a[jj * samples + kk]; };
  const std::int64_t near = planes[j] - planes[j - 1], far = planes[j - 1] - planes[j - 2];
  const auto across = [&](std::size_t kk) {
    return std::clamp(rounded_div((at(j - 1, kk) - at(j - 2, kk)) * near, far), -kFeatureLimit,
                      kFeatureLimit);
  };
  std::array<std::int64_t, kFeatures> f{};
  f[2] = across(k);
  if (k >= 1) {
    f[0] = at(j, k - 1) - at(j - 1, k - 1);
    f[3] = across(k - 1);
    f[6] = at(j - 1, k) - at(j - 1, k - 1);
  }
  if (k >= 2) f[1] = at(j, k - 2) - at(j - 1, k - 2);
  if (k + 1 < samples) {
    f[4] = across(k + 1);
    f[5] = at(j - 1, k + 1) - at(j - 1, k);
  }
  return f;
}

std::int64_t unclamped(std::span<const std::int64_t> a, std::span<const std::int64_t> planes,
                       std::size_t samples, const Weights& w, std::size_t j, std::size_t k) {
  const auto at = [&](std::size_t jj, std::size_t kk) { return a[jj * samples + kk]; };
  if (j >= 2) {
    const std::array<std::int64_t, kFeatures> f = features(a, planes, samples, j, k);
    std::int64_t sum = 0;
    for (std::size_t i = 0; i < kFeatures; ++i)
      sum += w[i] * f[i];
    return at(j - 1, k) + (sum >= 0 ? (sum + (1 << (kWeightBits - 1))) >> kWeightBits
                                    : -((-sum + (1 << (kWeightBits - 1))) >> kWeightBits));
  }
  if (j == 1) return k >= 1 ? at(1, k - 1) + at(0, k) - at(0, k - 1) : at(0, k);
  if (k >= 2) return 2 * at(0, k - 1) - at(0, k - 2);
  return k == 1 ? at(0, 0) : 0;
}

} // namespace

std::int64_t predict(std::span<const std::int64_t> a, std::span<const std::int64_t> planes,
                     std::size_t samples, const Weights& w, std::size_t j, std::size_t k) {
  return std::clamp(unclamped(a, planes, samples, w, j, k), -kMaxQuantised, kMaxQuantised);
}

Weights fit_weights(std::span<const std::int64_t> a, std::span<const std::int64_t> planes,
                    std::size_t samples) {
  const std::size_t curves = planes.size();
  Weights w{};
  if (curves < 3) return w;
  const auto rows = static_cast<Eigen::Index>((curves - 2) * samples);
  Eigen::MatrixXd m(rows, static_cast<Eigen::Index>(kFeatures));
  Eigen::VectorXd t(rows);
  Eigen::Index r = 0;
  for (std::size_t j = 2; j < curves; ++j)
    for (std::size_t k = 0; k < samples; ++k, ++r) {
      const std::array<std::int64_t, kFeatures> f = features(a, planes, samples, j, k);
      for (std::size_t i = 0; i < kFeatures; ++i)
        m(r, static_cast<Eigen::Index>(i)) = static_cast<double>(f[i]);
      t(r) = static_cast<double>(a[j * samples + k] - a[(j - 1) * samples + k]);
    }
  const Eigen::VectorXd x = m.colPivHouseholderQr().solve(t);
  for (std::size_t i = 0; i < kFeatures; ++i) {
    const double v = x(static_cast<Eigen::Index>(i)) * (1 << kWeightBits);
    w[i] = std::isfinite(v)
               ? static_cast<std::int32_t>(std::clamp(std::round(v), -double(kMaxWeight), double(kMaxWeight)))
               : 0;
  }
  return w;
}

std::vector<std::uint32_t> to_symbols(std::span<const std::int64_t> values,
                                      std::span<const std::int64_t> planes, std::size_t samples,
                                      const Weights& w) {
  std::vector<std::uint32_t> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::int64_t r = values[i] - predict(values, planes, samples, w, i / samples, i % samples);
    out[i] = static_cast<std::uint32_t>((static_cast<std::uint64_t>(r) << 1) ^
                                        static_cast<std::uint64_t>(r >> 63));
  }
  return out;
}

bool from_symbols(std::span<const std::uint32_t> symbols, std::span<const std::int64_t> planes,
                  std::size_t samples, const Weights& w, std::span<std::int64_t> values) {
  for (std::size_t i = 0; i < symbols.size(); ++i) {
    const std::uint32_t u = symbols[i];
    const std::int64_t r = static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
    const std::int64_t v = predict(values, planes, samples, w, i / samples, i % samples) + r;
    if (v > kMaxQuantised || v < -kMaxQuantised) return false;
    values[i] = v;
  }
  return true;
}

std::string write_predicted(std::span<const std::int64_t> values, std::span<const std::int64_t> planes,
                            std::size_t samples, std::size_t coordinate) {
  const Weights own = fit_weights(values, planes, samples);
  Writer with_default, with_own;
  with_default.u8(0);
  with_default.bytes(encode_classes(to_symbols(values, planes, samples, kDefaultWeights.at(coordinate))));
  with_own.u8(1);
  for (const std::int32_t weight : own)
    with_own.svarint(weight);
  with_own.bytes(encode_classes(to_symbols(values, planes, samples, own)));
  return with_own.size() < with_default.size() ? std::move(with_own.str()) : std::move(with_default.str());
}

} // namespace pdeface::pdef::detail
