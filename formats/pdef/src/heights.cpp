// y as heights: the layout's arithmetic (integers only, so that every platform decodes the same values), the
// encoder's search for the cheapest layout, and its bytes.

#include "heights.hpp"

#include "entropy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pdeface::pdef::detail {
namespace {

std::size_t anchors(const Heights& h, std::size_t curves) { return (curves - 1) / h.stride + 1; }

constexpr std::uint8_t kSymmetric = 0x01;

// The extents as symbols: each of bottom and top as its first value, its first difference, then second
// differences (the chin's and the forehead's lines are smooth across the curves).
std::vector<std::uint32_t> extent_symbols(const Heights& h) {
  std::vector<std::uint32_t> out;
  for (const std::vector<std::int64_t>* line : {&h.bottom, &h.top})
    for (std::size_t j = 0; j < line->size(); ++j) {
      const auto& v = *line;
      out.push_back(zigzag32(j == 0 ? v[0] : j == 1 ? v[1] - v[0] : v[j] - 2 * v[j - 1] + v[j - 2]));
    }
  return out;
}

// The prediction of anchor a's interior height k (1..K−2) from those decoded before it: its mirror's (the
// anchors' heights of a face are symmetric), else the previous anchor's plus the difference one sample down,
// else (the first anchor) straight on from the two below. Heights 0 and 2^bits stand at k = 0 and K − 1.
std::int64_t predict_height(const Heights& h, std::size_t count, std::size_t samples, std::size_t a,
                            std::size_t k) {
  const std::size_t inner = samples - 2;
  const auto at = [&](std::size_t aa, std::size_t kk) { return kk == 0 ? 0 : h.table[aa * inner + kk - 1]; };
  const std::size_t mirror = count - 1 - a;
  if (mirror < a) return at(mirror, k);
  if (a > 0) return at(a - 1, k) + at(a, k - 1) - at(a - 1, k - 1);
  const std::int64_t unit = rounded_div(std::int64_t{1} << h.bits, static_cast<std::int64_t>(samples - 1));
  return k == 1 ? unit : 2 * at(0, k - 1) - at(0, k - 2);
}

} // namespace

std::int64_t height_units(const Heights& h, std::span<const std::int64_t> planes, std::size_t samples,
                          std::uint32_t step, std::size_t j, std::size_t k) {
  const std::int64_t bottom = h.bottom[j] * step, top = h.top[j] * step;
  if (k == 0) return bottom;
  if (k + 1 == samples) return top;
  const std::size_t inner = samples - 2, a = j / h.stride;
  std::int64_t weight = 0; // of the next anchor, in 2^-kBlendBits
  if (j % h.stride != 0) {
    const std::int64_t from = planes[a * h.stride], to = planes[(a + 1) * h.stride];
    weight = rounded_div((planes[j] - from) << kBlendBits, to - from);
  }
  const std::int64_t here = h.table[a * inner + k - 1];
  const std::int64_t next = weight == 0 ? 0 : h.table[(a + 1) * inner + k - 1];
  const std::int64_t blend = ((std::int64_t{1} << kBlendBits) - weight) * here + weight * next;
  return bottom + rounded_div((top - bottom) * blend, std::int64_t{1} << (h.bits + kBlendBits));
}

std::optional<HeightsFit> fit_heights(std::span<const double> y, std::span<const std::int64_t> planes,
                                      std::size_t samples, const Grid& grid, std::optional<Layout> only) {
  const std::size_t curves = planes.size();
  if (curves < 2 || samples < 3) return std::nullopt;
  // The extents on the grid; every curve must rise, by less than 4 m.
  Heights base;
  for (std::size_t j = 0; j < curves; ++j) {
    const double lo = y[j * samples], hi = y[j * samples + samples - 1];
    const double b = std::round(lo / grid.step_mm()), t = std::round(hi / grid.step_mm());
    if (!(std::abs(b) <= static_cast<double>(kMaxQuantised)) ||
        !(std::abs(t) <= static_cast<double>(kMaxQuantised)))
      return std::nullopt;
    base.bottom.push_back(static_cast<std::int64_t>(b));
    base.top.push_back(static_cast<std::int64_t>(t));
    const std::int64_t span = (base.top[j] - base.bottom[j]) * grid.step;
    if (span <= 0 || span >= (std::int64_t{1} << kMaxSpanBits)) return std::nullopt;
  }
  std::optional<HeightsFit> best;
  for (std::uint32_t stride = 1; stride < curves; ++stride) {
    if ((curves - 1) % stride != 0 || (only && only->stride != stride)) continue;
    for (std::uint32_t bits = 4; bits <= kMaxHeightBits; ++bits) {
      if (only && only->bits != bits) continue;
      HeightsFit fit{base, std::vector<std::int64_t>(curves * samples, 0), 0};
      Heights& h = fit.heights;
      h.stride = stride;
      h.bits = bits;
      const std::int64_t one = std::int64_t{1} << bits;
      for (std::size_t j = 0; j < curves; j += stride) {
        const double lo = static_cast<double>(h.bottom[j] * grid.step) * kStepUnit;
        const double hi = static_cast<double>(h.top[j] * grid.step) * kStepUnit;
        for (std::size_t k = 1; k + 1 < samples; ++k) {
          const double relative = (y[j * samples + k] - lo) / (hi - lo);
          h.table.push_back(
              std::clamp<std::int64_t>(std::llround(relative * static_cast<double>(one)), 0, one));
        }
      }
      const std::size_t count = anchors(h, curves), inner = samples - 2;
      h.symmetric = true;
      for (std::size_t a = 0; a < count && h.symmetric; ++a)
        h.symmetric = std::equal(h.table.begin() + static_cast<std::ptrdiff_t>(a * inner),
                                 h.table.begin() + static_cast<std::ptrdiff_t>((a + 1) * inner),
                                 h.table.begin() + static_cast<std::ptrdiff_t>((count - 1 - a) * inner));
      bool fits = true;
      for (std::size_t j = 0; j < curves && fits; ++j)
        for (std::size_t k = 1; k + 1 < samples; ++k) {
          const double at =
              static_cast<double>(height_units(h, planes, samples, grid.step, j, k)) * kStepUnit;
          const double r = std::round((y[j * samples + k] - at) / grid.step_mm());
          if (!(std::abs(r) <= static_cast<double>(kMaxQuantised))) {
            fits = false;
            break;
          }
          fit.residuals[j * samples + k] = static_cast<std::int64_t>(r);
        }
      if (!fits) continue;
      fit.bytes = write_heights(h, fit.residuals, curves, samples).size();
      if (!best || fit.bytes < best->bytes) best = std::move(fit);
    }
  }
  return best;
}

std::string write_heights(const Heights& h, std::span<const std::int64_t> residuals, std::size_t curves,
                          std::size_t samples) {
  Writer w;
  w.varint(h.stride);
  w.u8(static_cast<std::uint8_t>(h.bits));
  w.u8(h.symmetric ? kSymmetric : 0);
  w.bytes(encode_classes(extent_symbols(h)));
  const std::size_t count = anchors(h, curves), inner = samples - 2;
  std::vector<std::uint32_t> table;
  for (std::size_t a = 0; a < (h.symmetric ? (count + 1) / 2 : count); ++a)
    for (std::size_t k = 1; k + 1 < samples; ++k)
      table.push_back(zigzag32(h.table[a * inner + k - 1] - predict_height(h, count, samples, a, k)));
  w.bytes(encode_classes(table));
  std::vector<std::uint32_t> rest;
  for (std::size_t j = 0; j < curves; ++j)
    for (std::size_t k = 1; k + 1 < samples; ++k)
      rest.push_back(zigzag32(residuals[j * samples + k]));
  w.bytes(encode_classes(rest));
  return std::move(w.str());
}

bool read_heights(Reader& r, std::span<const std::int64_t> planes, std::size_t samples, std::uint32_t step,
                  Heights& h, std::vector<std::int64_t>& residuals) {
  const std::size_t curves = planes.size();
  const std::size_t at = r.offset();
  const std::uint64_t stride = r.varint("the heights' anchor stride");
  const std::size_t bits_at = r.offset();
  const std::uint8_t bits = r.u8("the heights' grid");
  const std::uint8_t flags = r.u8("the heights' flags");
  if (!r.ok()) return false;
  if (stride == 0 || stride >= curves || (curves - 1) % stride != 0)
    return r.fail(ErrorCode::Malformed,
                  fmt::format("an anchor stride of {} (it must divide {} curves − 1)", stride, curves), at);
  if (bits < 1 || bits > kMaxHeightBits)
    return r.fail(ErrorCode::Malformed,
                  fmt::format("a heights' grid of 2^-{} (1 to {} bits)", bits, kMaxHeightBits), bits_at);
  if ((flags & ~kSymmetric) != 0)
    return r.fail(ErrorCode::Malformed, fmt::format("unknown heights' flags 0x{:02x}", flags), bits_at + 1);
  h.symmetric = (flags & kSymmetric) != 0;
  h.stride = static_cast<std::uint32_t>(stride);
  h.bits = bits;
  const auto stream = [&](std::vector<std::uint32_t>& symbols, std::string_view what) {
    const std::size_t from = r.offset();
    const std::optional<std::size_t> used = decode_classes(r.rest(), symbols);
    if (!used) return r.fail(ErrorCode::Malformed, fmt::format("the {} do not decode", what), from);
    r.take(*used, what);
    return r.ok();
  };
  std::vector<std::uint32_t> extents(2 * curves);
  if (!stream(extents, "extents")) return false;
  for (std::vector<std::int64_t>* line : {&h.bottom, &h.top}) {
    const std::size_t first = line == &h.bottom ? 0 : curves;
    line->resize(curves);
    auto& v = *line;
    for (std::size_t j = 0; j < curves; ++j) {
      const std::int64_t d = unzigzag32(extents[first + j]);
      v[j] = j == 0 ? d : j == 1 ? v[0] + d : d + 2 * v[j - 1] - v[j - 2];
      if (v[j] > kMaxQuantised || v[j] < -kMaxQuantised)
        return r.fail(ErrorCode::Malformed, fmt::format("curve {}'s extent is beyond the grid's range", j),
                      at);
    }
  }
  for (std::size_t j = 0; j < curves; ++j) {
    const std::int64_t span = (h.top[j] - h.bottom[j]) * step;
    if (span <= 0 || span >= (std::int64_t{1} << kMaxSpanBits))
      return r.fail(ErrorCode::Malformed,
                    fmt::format("curve {} must rise by less than {} mm from its bottom to its top", j,
                                std::ldexp(1.0, kMaxSpanBits) * kStepUnit),
                    at);
  }
  const std::size_t count = anchors(h, curves), inner = samples - 2;
  std::vector<std::uint32_t> table((h.symmetric ? (count + 1) / 2 : count) * inner);
  if (!stream(table, "anchors' heights")) return false;
  h.table.assign(count * inner, 0);
  const std::int64_t one = std::int64_t{1} << bits;
  for (std::size_t a = 0; a < count; ++a)
    for (std::size_t k = 1; k + 1 < samples; ++k) {
      if (h.symmetric && 2 * a >= count) {
        h.table[a * inner + k - 1] = h.table[(count - 1 - a) * inner + k - 1];
        continue;
      }
      const std::int64_t v = predict_height(h, count, samples, a, k) + unzigzag32(table[a * inner + k - 1]);
      if (v < 0 || v > one)
        return r.fail(ErrorCode::Malformed,
                      fmt::format("anchor {}'s height {} is outside 0..2^{}", a, k, bits), at);
      h.table[a * inner + k - 1] = v;
    }
  std::vector<std::uint32_t> rest(curves * inner);
  if (!stream(rest, "heights' residuals")) return false;
  residuals.assign(curves * samples, 0);
  for (std::size_t j = 0; j < curves; ++j)
    for (std::size_t k = 1; k + 1 < samples; ++k) {
      const std::int64_t v = unzigzag32(rest[j * inner + k - 1]);
      if (v > kMaxQuantised || v < -kMaxQuantised)
        return r.fail(ErrorCode::Malformed,
                      fmt::format("sample {} of curve {}: a residual beyond the grid", k, j), at);
      residuals[j * samples + k] = v;
    }
  return true;
}

} // namespace pdeface::pdef::detail
