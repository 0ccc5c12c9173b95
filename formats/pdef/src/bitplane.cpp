// Bit-plane coding of wavelet coefficients with an adaptive binary range coder (LZMA's: 11-bit
// probabilities adapted by 1/32 of the error, a 32-bit range renormalised a byte at a time). Significance is
// coded by quadtrees (16 × 16 blocks split down to single coefficients, as in SPECK), so that a run of
// insignificant coefficients costs one decision, not one each; refinement bits follow in a pass of their own.

#include "bitplane.hpp"

#include "wavelet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace pdeface::pdef::detail {
namespace {

constexpr std::uint32_t kProbabilityBits = 11;
constexpr std::uint32_t kProbabilityOne = 1u << kProbabilityBits;
constexpr std::uint32_t kAdaptShift = 5;
constexpr std::uint32_t kTop = 1u << 24;
// Nodes and coefficients mostly stay insignificant: their contexts start at 5/8 for a 0.
constexpr std::uint16_t kFirstProbability = 1280;
constexpr std::size_t kTreeLevels = 4;                        // node sizes 2, 4, 8, 16 (level t: 2^t a side)
constexpr std::size_t kBlock = std::size_t{1} << kTreeLevels; // a band's roots: 16 × 16

// The contexts (each an adaptive probability of a 0).
constexpr std::size_t kNode = 0; // + 8 (3 (t − 1) + kind) + 4 · parent's + 2 · fresh + neighbour active: 96
constexpr std::size_t kSignificance = 96;     // + 8 (2 kind + fresh) + 4 · parent's + min(neighbours, 3): 48
constexpr std::size_t kFirstRefinement = 144; // signs and later refinement bits: even, not adapted
constexpr std::size_t kContexts = 145;

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
  int even(int b) {
    range_ >>= 1;
    if (b != 0) low_ += range_;
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
// is exhausted, and every decision before that is the encoder's. Branch-free but for the renormalisation.
class RangeDecoder {
public:
  explicit RangeDecoder(std::string_view in) : in_(in) {
    for (int i = 0; i < 4; ++i)
      code_ = (code_ << 8) | next();
  }
  int bit(std::uint16_t& p, int /*unused*/) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p;
    const bool one = code_ >= bound;
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(one);
    code_ -= bound & mask;
    range_ = one ? range_ - bound : bound;
    const std::uint32_t down = p - (p >> kAdaptShift), up = p + ((kProbabilityOne - p) >> kAdaptShift);
    p = static_cast<std::uint16_t>(one ? down : up);
    while (range_ < kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
    return one ? 1 : 0;
  }
  int even(int /*unused*/) {
    range_ >>= 1;
    const bool one = code_ >= range_;
    code_ -= one ? range_ : 0;
    while (range_ < kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
    return one ? 1 : 0;
  }
  [[nodiscard]] bool exhausted() const { return exhausted_; }
  [[nodiscard]] std::size_t used() const { return std::min(pos_, in_.size()); }

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
};

struct Band {
  std::size_t x0, y0, w, h, kind;                  // kind: 0 low, 1 HL or LH, 2 HH
  std::array<std::size_t, kTreeLevels + 1> across; // nodes of level t across the band
  std::array<std::size_t, kTreeLevels + 1> first;  // index of its first node of level t
  std::array<std::size_t, kTreeLevels + 1> down;   // nodes of level t down the band
  std::size_t parent;                              // the band one level coarser, same orientation
};
constexpr std::size_t kNone = ~std::size_t{0};

std::vector<Band> bands_of(std::size_t width, std::size_t height, std::size_t levels) {
  const Bands b(width, height, levels);
  std::vector<Band> out;
  std::array<std::size_t, kTreeLevels + 1> nodes{};
  auto add = [&](std::size_t x0, std::size_t y0, std::size_t w, std::size_t h, std::size_t kind) {
    if (w == 0 || h == 0) return;
    Band band{x0, y0, w, h, kind, {}, {}, {}, out.size() >= 4 ? out.size() - 3 : kNone};
    for (std::size_t t = 1; t <= kTreeLevels; ++t) {
      const std::size_t side = std::size_t{1} << t;
      band.across[t] = (w + side - 1) / side;
      band.down[t] = (h + side - 1) / side;
      band.first[t] = nodes[t];
      nodes[t] += band.across[t] * band.down[t];
    }
    out.push_back(band);
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

// A coefficient or a node of the lists: its index (a coefficient's in the image, a node's among its
// level's), that of what lies below it in its band's parent band (a coefficient, or a node one level down;
// a zero sentinel when the band has no parent), its band-relative position (a node's top left corner) and
// its band.
struct Entry {
  std::uint32_t at, parent;
  std::uint16_t x, y;
  std::uint16_t band, kind;
};

// The traversal both sides share. `Encoding`: the encoder, which knows the coefficients (`source`).
template <typename Coder, bool Encoding> struct Planes {
  Coder coder;
  std::size_t width, height;
  std::vector<Band> bands;
  // What is known of each coefficient: 0 until significant, then ±(m + 2^l / 2), m the magnitude known
  // and l the lowest plane known (exact in a double); one more, always 0, for the parents of the bands
  // that have none.
  std::vector<double> value;
  std::vector<std::uint8_t> neighbours; // significant neighbours in the same band (at most 8)
  std::array<std::vector<std::uint8_t>, kTreeLevels + 1> active; // per node of level t ≥ 1, and a 0 sentinel
  std::array<std::vector<std::uint64_t>, kTreeLevels + 1> peak;  // encoder: the largest magnitude in a node
  std::array<std::vector<Entry>, kTreeLevels + 1> sets; // nodes not active (t ≥ 1), coefficients (0)
  std::vector<std::uint32_t> found; // significant coefficients in the order they became so
  std::size_t first_refine = 0;     // found[first_refine, …): significant from the plane above
  std::array<std::uint16_t, kContexts> p{};
  const std::vector<std::int64_t>* source = nullptr; // encoder only
  std::uint64_t threshold = 0;                       // 2^b
  double found_value = 0;                            // 1.5 · 2^b
  double half = 0;                                   // 2^b / 2
  bool stopped = false;

  Planes(Coder c, std::size_t w, std::size_t h, std::size_t levels,
         const std::vector<std::int64_t>* values = nullptr)
      : coder(std::move(c)), width(w), height(h), bands(bands_of(w, h, levels)), value(w * h + 1, 0.0),
        neighbours(w * h, 0), source(values) {
    for (std::size_t t = 1; t <= kTreeLevels; ++t) {
      const Band& last = bands.back();
      active[t].assign(last.first[t] + last.across[t] * last.down[t] + 1, 0);
      sets[t].reserve(active[t].size());
      if constexpr (Encoding) peak[t].assign(active[t].size(), 0);
    }
    sets[0].reserve(w * h);
    found.reserve(w * h);
    for (std::size_t i = 0; i < bands.size(); ++i)
      for (std::size_t y = 0; y < bands[i].h; y += kBlock)
        for (std::size_t x = 0; x < bands[i].w; x += kBlock)
          sets[kTreeLevels].push_back(node_entry<kTreeLevels>(i, x, y));
    std::fill(p.begin(), p.begin() + kFirstRefinement, kFirstProbability);
    p[kFirstRefinement] = kProbabilityOne / 2;
    if constexpr (Encoding)
      for (const Band& band : bands)
        for (std::size_t y = 0; y < band.h; ++y)
          for (std::size_t x = 0; x < band.w; ++x) {
            const std::uint64_t m = magnitude_of((band.y0 + y) * width + band.x0 + x);
            for (std::size_t t = 1; t <= kTreeLevels; ++t) {
              std::uint64_t& top = peak[t][band.first[t] + (y >> t) * band.across[t] + (x >> t)];
              top = std::max(top, m);
            }
          }
  }

  [[nodiscard]] std::uint64_t magnitude_of(std::size_t c) const {
    const std::int64_t v = (*source)[c];
    return static_cast<std::uint64_t>(v < 0 ? -v : v);
  }

  // The coefficient of `band` (its index) at band-relative (x, y), and the one below it in the parent band.
  [[nodiscard]] Entry coefficient_entry(std::size_t b, std::size_t x, std::size_t y) const {
    const Band& band = bands[b];
    std::size_t parent = width * height;
    if (band.parent != kNone) {
      const Band& up = bands[band.parent];
      parent = (up.y0 + std::min(y / 2, up.h - 1)) * width + up.x0 + std::min(x / 2, up.w - 1);
    }
    return {static_cast<std::uint32_t>((band.y0 + y) * width + band.x0 + x),
            static_cast<std::uint32_t>(parent),
            static_cast<std::uint16_t>(x),
            static_cast<std::uint16_t>(y),
            static_cast<std::uint16_t>(b),
            static_cast<std::uint16_t>(band.kind)};
  }
  // The node of level T of `band` at band-relative (x, y), and the node of level T − 1 (a coefficient when
  // T = 1) below it in the parent band.
  template <std::size_t T> [[nodiscard]] Entry node_entry(std::size_t b, std::size_t x, std::size_t y) const {
    const Band& band = bands[b];
    Entry e{static_cast<std::uint32_t>(band.first[T] + (y >> T) * band.across[T] + (x >> T)),
            0,
            static_cast<std::uint16_t>(x),
            static_cast<std::uint16_t>(y),
            static_cast<std::uint16_t>(b),
            static_cast<std::uint16_t>(band.kind)};
    if constexpr (T == 1) {
      e.parent = coefficient_entry(b, x, y).parent;
    } else {
      std::size_t parent = active[T - 1].size() - 1;
      if (band.parent != kNone) {
        const Band& up = bands[band.parent];
        parent = up.first[T - 1] + std::min(y >> T, up.down[T - 1] - 1) * up.across[T - 1] +
                 std::min(x >> T, up.across[T - 1] - 1);
      }
      e.parent = static_cast<std::uint32_t>(parent);
    }
    return e;
  }

  // One decision, or none once the decoder has run out of bytes (then everything stops).
  [[gnu::always_inline]] bool decide(Coder& rc, std::size_t context, bool truth, bool& bit) {
    if (rc.exhausted()) {
      stopped = true;
      return false;
    }
    bit = rc.bit(p[context], truth ? 1 : 0) != 0;
    return true;
  }
  [[gnu::always_inline]] bool decide_even(Coder& rc, bool truth, bool& bit) {
    if (rc.exhausted()) {
      stopped = true;
      return false;
    }
    bit = rc.even(truth ? 1 : 0) != 0;
    return true;
  }

  void mark(const Band& band, std::size_t x, std::size_t y) { // band-relative
    if (x > 0 && y > 0 && x + 1 < band.w && y + 1 < band.h) {
      std::uint8_t* n = neighbours.data() + (band.y0 + y) * width + band.x0 + x;
      ++n[-1];
      ++n[1];
      n -= width;
      ++n[-1];
      ++n[0];
      ++n[1];
      n += 2 * width;
      ++n[-1];
      ++n[0];
      ++n[1];
      return;
    }
    const std::size_t y_first = y == 0 ? 0 : y - 1, y_last = std::min(y + 1, band.h - 1);
    const std::size_t x_first = x == 0 ? 0 : x - 1, x_last = std::min(x + 1, band.w - 1);
    for (std::size_t yy = y_first; yy <= y_last; ++yy)
      for (std::size_t xx = x_first; xx <= x_last; ++xx)
        if (xx != x || yy != y) ++neighbours[(band.y0 + yy) * width + band.x0 + xx];
  }

  [[gnu::always_inline]] std::size_t significance_context(const Entry& e, bool fresh) const {
    return kSignificance + 8 * (2 * std::size_t{e.kind} + (fresh ? 1 : 0)) + (value[e.parent] != 0 ? 4 : 0) +
           std::min<std::size_t>(neighbours[e.at], 3);
  }

  // The coefficient `e` tests significant (decided or inferred): its sign, and it joins the significant.
  // False when the sign is beyond the bytes.
  [[gnu::always_inline]] bool become_significant(Coder& rc, const Entry& e) {
    bool sign = false;
    if (!decide_even(rc, Encoding && (*source)[e.at] < 0, sign)) return false;
    value[e.at] = sign ? -found_value : found_value;
    found.push_back(e.at);
    mark(bands[e.band], e.x, e.y);
    return true;
  }

  // A coefficient of a group of 2 × 2 that became active in this plane (`inferred`: the group's others
  // did not become significant, so it must). Returns whether it is significant now; one that is not joins
  // the coefficients to test in later planes.
  [[gnu::always_inline]] bool fresh_coefficient(Coder& rc, const Entry& e, bool inferred) {
    if (!inferred) {
      bool now = false;
      if (!decide(rc, significance_context(e, true), Encoding && magnitude_of(e.at) >= threshold, now))
        return false;
      if (!now) {
        sets[0].push_back(e);
        return false;
      }
    }
    return become_significant(rc, e);
  }

  template <std::size_t T> [[gnu::always_inline]] std::size_t node_context(const Entry& e, bool fresh) const {
    const Band& band = bands[e.band];
    const std::uint8_t* a = active[T].data() + e.at;
    const std::size_t across = band.across[T];
    const bool near = (e.x > 0 && a[-1] != 0) || (e.y > 0 && a[-static_cast<std::ptrdiff_t>(across)] != 0) ||
                      (e.x + (std::size_t{1} << T) < band.w && a[1] != 0) ||
                      (e.y + (std::size_t{1} << T) < band.h && a[across] != 0);
    bool parent = false;
    if constexpr (T == 1)
      parent = value[e.parent] != 0;
    else
      parent = active[T - 1][e.parent] != 0;
    return kNode + 8 * (3 * (T - 1) + band.kind) + (parent ? 4 : 0) + (fresh ? 2 : 0) + (near ? 1 : 0);
  }

  // A node of level T that became active: its children, each decided (a node) or tested (a coefficient)
  // in this plane; the last one inferred when none before it became active.
  template <std::size_t T> [[gnu::always_inline]] void split(Coder& rc, const Entry& e) {
    const Band& band = bands[e.band];
    constexpr std::size_t side = std::size_t{1} << (T - 1); // a child's
    const bool right = e.x + side < band.w, down = e.y + side < band.h;
    const std::size_t children = std::size_t{right ? 2u : 1u} * (down ? 2u : 1u);
    const std::size_t corner = (band.y0 + e.y) * width + band.x0 + e.x; // T = 1: the first child
    bool any = false;
    for (std::size_t i = 0; i < children; ++i) {
      const std::size_t dx = right ? i & 1 : 0, dy = right ? i >> 1 : i;
      const bool must = !any && i + 1 == children;
      if constexpr (T == 1) { // the four share their parent
        const Entry child{static_cast<std::uint32_t>(corner + dy * width + dx),
                          e.parent,
                          static_cast<std::uint16_t>(e.x + dx),
                          static_cast<std::uint16_t>(e.y + dy),
                          e.band,
                          e.kind};
        any = fresh_coefficient(rc, child, must) || any;
      } else {
        any = fresh_node<T - 1>(rc, node_entry<T - 1>(e.band, e.x + dx * side, e.y + dy * side), must) || any;
      }
      if (stopped) return;
    }
  }

  // A node of level T whose parent became active in this plane. Returns whether it is active now; one
  // that is not joins the nodes to decide in later planes.
  template <std::size_t T> [[gnu::always_inline]] bool fresh_node(Coder& rc, const Entry& e, bool inferred) {
    if (!inferred) {
      bool now = false;
      if (!decide(rc, node_context<T>(e, true), Encoding && peak[T][e.at] >= threshold, now)) return false;
      if (!now) {
        sets[T].push_back(e);
        return false;
      }
    }
    active[T][e.at] = 1;
    split<T>(rc, e);
    return true;
  }

  // The nodes of level T not active before this plane, in their order: each decided, split when active.
  template <std::size_t T> void node_pass(Coder& shared) {
    Coder rc = shared; // a local copy: its state stays in registers
    std::vector<Entry>& list = sets[T];
    const std::size_t n = list.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n && !stopped; ++i) {
      const Entry e = list[i];
      bool now = false;
      if (!decide(rc, node_context<T>(e, false), Encoding && peak[T][e.at] >= threshold, now)) break;
      if (!now) {
        list[kept++] = e;
        continue;
      }
      active[T][e.at] = 1;
      split<T>(rc, e);
    }
    // Entries appended while splitting belong to lower levels: this list only shrinks.
    if (!stopped) list.resize(kept);
    shared = rc;
  }

  // The coefficients not significant in active groups, in their order.
  void coefficient_pass(Coder& shared) {
    Coder rc = shared;
    std::vector<Entry>& list = sets[0];
    const std::size_t n = list.size();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Entry e = list[i];
      bool now = false;
      if (!decide(rc, significance_context(e, false), Encoding && magnitude_of(e.at) >= threshold, now))
        break;
      if (!now) {
        list[kept++] = e;
        continue;
      }
      if (!become_significant(rc, e)) break;
    }
    if (!stopped) list.resize(kept);
    shared = rc;
  }

  // The refinement bits at plane b of the coefficients significant before it (found[0, end)).
  void refinement_pass(Coder& shared, std::size_t b, std::size_t end) {
    Coder rc = shared;
    for (std::size_t i = 0; i < end; ++i) {
      const std::uint32_t c = found[i];
      const bool truth = Encoding && ((magnitude_of(c) >> b) & 1) != 0;
      bool bit = false;
      if (i >= first_refine ? !decide(rc, kFirstRefinement, truth, bit) : !decide_even(rc, truth, bit)) break;
      const double v = value[c];
      const double change = std::copysign(half, v); // away from 0 for a 1, towards it for a 0
      value[c] = bit ? v + change : v - change;
    }
    shared = rc;
  }

  // Plane b: the coefficients near significant ones, the small sets, the refinement bits, the large sets
  // (in the order of how much error a bit removes, measured). Returns false when the coder ran out of bytes
  // (decoder).
  bool plane(std::size_t b) {
    threshold = std::uint64_t{1} << b;
    found_value = 1.5 * static_cast<double>(threshold);
    half = 0.5 * static_cast<double>(threshold);
    const std::size_t refine_end = found.size();
    coefficient_pass(coder);
    if (!stopped) node_pass<1>(coder);
    if (!stopped) node_pass<2>(coder);
    if (!stopped) refinement_pass(coder, b, refine_end); // before the larger sets: more error per bit
    if (!stopped) node_pass<3>(coder);
    if (!stopped) node_pass<4>(coder);
    first_refine = refine_end;
    return !stopped;
  }
};

} // namespace

std::string encode_planes(const std::vector<std::int64_t>& coefficients, std::size_t width,
                          std::size_t height, std::size_t levels, std::size_t planes) {
  if (coefficients.size() != width * height)
    throw std::invalid_argument("pdef: coefficients of another size");
  Planes<RangeEncoder, true> state(RangeEncoder{}, width, height, levels, &coefficients);
  for (std::size_t b = planes; b-- > 0;)
    state.plane(b);
  return state.coder.finish();
}

DecodedPlanes decode_planes(std::string_view stream, std::size_t width, std::size_t height,
                            std::size_t levels, std::size_t planes) {
  Planes<RangeDecoder, false> state(RangeDecoder(stream), width, height, levels);
  DecodedPlanes out;
  out.complete = true;
  for (std::size_t b = planes; b-- > 0;) {
    out.lowest_plane = b;
    if (!state.plane(b)) {
      out.complete = false;
      break;
    }
  }
  out.coefficients = std::move(state.value);
  out.coefficients.pop_back(); // the sentinel
  out.bytes_used = state.coder.used();
  return out;
}

} // namespace pdeface::pdef::detail
