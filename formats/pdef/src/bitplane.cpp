// Bit-plane coding of wavelet coefficients with an adaptive binary range coder (LZMA's: 11-bit
// probabilities adapted by 1/32 of the error, a 32-bit range renormalised a byte at a time).

#include "bitplane.hpp"

#include "wavelet.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace pdeface::pdef::detail {
namespace {

constexpr std::uint32_t kProbabilityBits = 11;
constexpr std::uint32_t kProbabilityOne = 1u << kProbabilityBits;
constexpr std::uint32_t kAdaptShift = 5;
constexpr std::uint32_t kTop = 1u << 24;
constexpr std::size_t kBlock = 16; // coefficients a side of a block whose significance is coded at once

// The contexts (each an adaptive probability of a 0).
constexpr std::size_t kSignificance = 0; // + 4 · kind + min(significant neighbours, 3): 12
constexpr std::size_t kBlockActive = 12; // + 2 · kind + (the block left or above is active): 6
constexpr std::size_t kSign = 18;
constexpr std::size_t kFirstRefinement = 19;
constexpr std::size_t kRefinement = 20;
constexpr std::size_t kContexts = 21;

class RangeEncoder {
public:
  int bit(std::uint16_t& p, int b) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p;
    if (b == 0) {
      range_ = bound;
      p = static_cast<std::uint16_t>(p + ((kProbabilityOne - p) >> kAdaptShift));
    } else {
      low_ += bound;
      range_ -= bound;
      p = static_cast<std::uint16_t>(p - (p >> kAdaptShift));
    }
    while (range_ < kTop) {
      range_ <<= 8;
      shift_low();
    }
    return b;
  }
  [[nodiscard]] static bool exhausted() { return false; }
  std::string finish() {
    for (int i = 0; i < 5; ++i)
      shift_low();
    if (out_.empty() || out_[0] != 0) throw std::logic_error("pdef: range coder's first byte is not 0");
    return out_.substr(1); // always 0: not stored
  }

private:
  void shift_low() {
    if (static_cast<std::uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
      const auto carry = static_cast<std::uint8_t>(low_ >> 32);
      std::uint8_t temp = cache_;
      do {
        out_.push_back(static_cast<char>(static_cast<std::uint8_t>(temp + carry)));
        temp = 0xFF;
      } while (--cache_size_ != 0);
      cache_ = static_cast<std::uint8_t>(low_ >> 24);
    }
    ++cache_size_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }
  std::uint64_t low_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
  std::uint8_t cache_ = 0;
  std::uint64_t cache_size_ = 1;
  std::string out_;
};

// Decodes the decisions that the bytes it has determine: once a renormalisation needs a byte beyond them it
// is exhausted, and every decision before that is the encoder's.
class RangeDecoder {
public:
  explicit RangeDecoder(std::string_view in) : in_(in) {
    for (int i = 0; i < 4; ++i)
      code_ = (code_ << 8) | next();
  }
  int bit(std::uint16_t& p, int /*unused*/) {
    ++symbols_;
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p;
    int b;
    if (code_ < bound) {
      range_ = bound;
      p = static_cast<std::uint16_t>(p + ((kProbabilityOne - p) >> kAdaptShift));
      b = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      p = static_cast<std::uint16_t>(p - (p >> kAdaptShift));
      b = 1;
    }
    while (range_ < kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
    return b;
  }
  [[nodiscard]] bool exhausted() const { return exhausted_; }
  [[nodiscard]] std::size_t used() const { return std::min(pos_, in_.size()); }
  [[nodiscard]] std::size_t symbols() const { return symbols_; }

private:
  std::uint32_t next() {
    if (pos_ >= in_.size()) {
      exhausted_ = true;
      ++pos_;
      return 0;
    }
    return static_cast<std::uint8_t>(in_[pos_++]);
  }
  std::string_view in_;
  std::size_t pos_ = 0;
  std::uint32_t code_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
  bool exhausted_ = false;
  std::size_t symbols_ = 0;
};

struct Band {
  std::size_t x0, y0, w, h, kind; // kind: 0 low, 1 HL or LH, 2 HH
  std::size_t bx, by;             // blocks across and down
  std::size_t first_block;        // index of its first block
};

std::vector<Band> bands_of(std::size_t width, std::size_t height, std::size_t levels) {
  const Bands b(width, height, levels);
  std::vector<Band> out;
  auto add = [&](std::size_t x0, std::size_t y0, std::size_t w, std::size_t h, std::size_t kind) {
    if (w == 0 || h == 0) return;
    const std::size_t first = out.empty() ? 0 : out.back().first_block + out.back().bx * out.back().by;
    out.push_back({x0, y0, w, h, kind, (w + kBlock - 1) / kBlock, (h + kBlock - 1) / kBlock, first});
  };
  add(0, 0, b.widths[levels], b.heights[levels], 0);
  for (std::size_t l = levels; l >= 1; --l) {
    const std::size_t wl = b.widths[l], hl = b.heights[l], wp = b.widths[l - 1], hp = b.heights[l - 1];
    add(wl, 0, wp - wl, hl, 1); // high across, low along
    add(0, hl, wl, hp - hl, 1); // low across, high along
    add(wl, hl, wp - wl, hp - hl, 2);
  }
  return out;
}

// The traversal both sides share: `magnitudes` (encoder: the integers to code; decoder: filled in).
template <typename Coder> struct Planes {
  Coder& coder;
  std::size_t width, height;
  std::vector<Band> bands;
  std::vector<std::uint64_t> magnitude; // known so far
  std::vector<std::uint8_t> negative;
  std::vector<std::uint8_t> significant;
  std::vector<std::uint8_t> neighbours; // significant neighbours in the same band (at most 8)
  std::vector<std::uint8_t> lowest;     // a significant coefficient's lowest plane known
  std::vector<std::uint8_t> just;       // became significant in the plane above this one
  std::vector<std::uint8_t> active;     // per block
  std::array<std::uint16_t, kContexts> p{};
  const std::vector<std::int64_t>* source = nullptr; // encoder only

  Planes(Coder& c, std::size_t w, std::size_t h, std::size_t levels)
      : coder(c), width(w), height(h), bands(bands_of(w, h, levels)), magnitude(w * h, 0), negative(w * h, 0),
        significant(w * h, 0), neighbours(w * h, 0), lowest(w * h, 0), just(w * h, 0) {
    active.assign(bands.back().first_block + bands.back().bx * bands.back().by, 0);
    p.fill(kProbabilityOne / 2);
  }

  [[nodiscard]] int truth(std::size_t c, std::size_t plane) const {
    if (source == nullptr) return 0;
    const std::int64_t v = (*source)[c];
    const std::uint64_t m = static_cast<std::uint64_t>(v < 0 ? -v : v);
    return static_cast<int>((m >> plane) & 1);
  }

  void mark(const Band& band, std::size_t x, std::size_t y) {
    for (std::size_t yy = y == band.y0 ? y : y - 1; yy <= std::min(y + 1, band.y0 + band.h - 1); ++yy)
      for (std::size_t xx = x == band.x0 ? x : x - 1; xx <= std::min(x + 1, band.x0 + band.w - 1); ++xx)
        if (xx != x || yy != y) ++neighbours[yy * width + xx];
  }

  // Returns false when the coder ran out of bytes (decoder).
  bool plane(std::size_t b) {
    for (const Band& band : bands)
      for (std::size_t by = 0; by < band.by; ++by)
        for (std::size_t bx = 0; bx < band.bx; ++bx) {
          const std::size_t block = band.first_block + by * band.bx + bx;
          const std::size_t x0 = band.x0 + bx * kBlock, y0 = band.y0 + by * kBlock;
          const std::size_t x1 = std::min(x0 + kBlock, band.x0 + band.w);
          const std::size_t y1 = std::min(y0 + kBlock, band.y0 + band.h);
          if (!active[block]) {
            int truth_bit = 0;
            if (source != nullptr)
              for (std::size_t y = y0; y < y1 && !truth_bit; ++y)
                for (std::size_t x = x0; x < x1 && !truth_bit; ++x)
                  truth_bit = truth(y * width + x, b);
            const bool near = (bx > 0 && active[block - 1]) || (by > 0 && active[block - band.bx]);
            if (coder.exhausted()) return false;
            if (!coder.bit(p[kBlockActive + 2 * band.kind + (near ? 1 : 0)], truth_bit)) continue;
            active[block] = 1;
          }
          for (std::size_t y = y0; y < y1; ++y)
            for (std::size_t x = x0; x < x1; ++x) {
              const std::size_t c = y * width + x;
              if (coder.exhausted()) return false;
              if (significant[c]) {
                const int bit = coder.bit(p[just[c] ? kFirstRefinement : kRefinement], truth(c, b));
                just[c] = 0;
                magnitude[c] |= static_cast<std::uint64_t>(bit) << b;
                lowest[c] = static_cast<std::uint8_t>(b);
                continue;
              }
              const std::size_t context =
                  kSignificance + 4 * band.kind + std::min<std::size_t>(neighbours[c], 3);
              if (!coder.bit(p[context], truth(c, b))) continue;
              if (coder.exhausted()) return false; // its sign is beyond the bytes: not reached
              const int sign = coder.bit(p[kSign], source != nullptr && (*source)[c] < 0 ? 1 : 0);
              negative[c] = static_cast<std::uint8_t>(sign);
              significant[c] = 1;
              just[c] = 1;
              magnitude[c] = std::uint64_t{1} << b;
              lowest[c] = static_cast<std::uint8_t>(b);
              mark(band, x, y);
            }
        }
    return true;
  }
};

} // namespace

std::string encode_planes(const std::vector<std::int64_t>& coefficients, std::size_t width,
                          std::size_t height, std::size_t levels, std::size_t planes) {
  if (coefficients.size() != width * height)
    throw std::invalid_argument("pdef: coefficients of another size");
  RangeEncoder coder;
  Planes<RangeEncoder> state(coder, width, height, levels);
  state.source = &coefficients;
  for (std::size_t b = planes; b-- > 0;)
    state.plane(b);
  return coder.finish();
}

DecodedPlanes decode_planes(std::string_view stream, std::size_t width, std::size_t height,
                            std::size_t levels, std::size_t planes) {
  RangeDecoder coder(stream);
  Planes<RangeDecoder> state(coder, width, height, levels);
  DecodedPlanes out;
  out.complete = true;
  for (std::size_t b = planes; b-- > 0;) {
    out.lowest_plane = b;
    if (!state.plane(b)) {
      out.complete = false;
      break;
    }
  }
  out.coefficients.assign(width * height, 0.0);
  for (std::size_t c = 0; c < width * height; ++c) {
    if (!state.significant[c]) continue;
    const double half = static_cast<double>(std::uint64_t{1} << state.lowest[c]) * 0.5;
    const double v = static_cast<double>(state.magnitude[c]) + half;
    out.coefficients[c] = state.negative[c] ? -v : v;
  }
  out.symbols = coder.symbols();
  out.bytes_used = coder.used();
  return out;
}

} // namespace pdeface::pdef::detail
