// The trim's quadtree (docs/pdef-format.md, "The trim"): blocks of 2^l × 2^l cells, each said to hold a
// trimmed cell and then a kept one, level by level from the whole grid down to single cells.

#include "trim.hpp"

#include "range_coder.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>

namespace pdeface::pdef::detail {
namespace {

constexpr std::size_t kLevelContexts = 12; // levels 0 … 11 and above share the last
// Each decision's context: which question (a trimmed cell, a kept one), the level, and how many of the
// block's left and upper neighbours hold what it asks about (0 … 2).
constexpr std::size_t kContexts = 2 * kLevelContexts * 3;
// What is known of a block: nothing yet, all kept, all trimmed, both.
constexpr std::uint8_t kUnknown = 0, kAllKept = 1, kAllTrimmed = 2, kMixed = 3;
constexpr std::uint16_t kFirstProbability = 1024;

struct Block {
  std::uint32_t p = 0, q = 0; // block (p, q) of its level: cells x from p·2^l, y from q·2^l
};

template <class Coder, bool Encoding> struct Quadtree {
  Coder rc;
  std::size_t across, down;
  std::vector<std::uint32_t> sums; // encoder: trimmed cells in [0, x) × [0, y), (across + 1) per row
  std::vector<std::uint8_t> cells;
  std::vector<std::vector<std::uint8_t>> known; // per level, per block: kUnknown … kMixed
  std::vector<std::size_t> blocks_across;       // per level
  std::size_t top = 0;                          // the level of the block that is the whole grid
  std::array<std::uint16_t, kContexts> p{};
  bool stopped = false;

  Quadtree(Coder coder, std::size_t w, std::size_t h, const std::vector<std::uint8_t>* truth)
      : rc(std::move(coder)), across(w), down(h), cells(w * h, 0) {
    p.fill(kFirstProbability);
    while ((std::size_t{1} << top) < std::max(across, down))
      ++top;
    for (std::size_t l = 0; l <= top; ++l) {
      const std::size_t a = ((across - 1) >> l) + 1, d = ((down - 1) >> l) + 1;
      blocks_across.push_back(a);
      known.emplace_back(a * d, kUnknown);
    }
    if constexpr (Encoding) {
      sums.assign((w + 1) * (h + 1), 0);
      for (std::size_t y = 0; y < h; ++y)
        for (std::size_t x = 0; x < w; ++x)
          sums[(y + 1) * (w + 1) + x + 1] = sums[y * (w + 1) + x + 1] + sums[(y + 1) * (w + 1) + x] -
                                            sums[y * (w + 1) + x] + ((*truth)[y * w + x] != 0 ? 1U : 0U);
    }
  }

  // The cells of block (p, q) at level l, clipped to the grid: [x0, x1) × [y0, y1).
  [[nodiscard]] std::array<std::size_t, 4> extent(const Block& b, std::size_t l) const {
    const std::size_t x0 = std::size_t{b.p} << l, y0 = std::size_t{b.q} << l;
    return {x0, std::min(across, x0 + (std::size_t{1} << l)), y0, std::min(down, y0 + (std::size_t{1} << l))};
  }
  [[nodiscard]] bool exists(const Block& b, std::size_t l) const {
    return (std::size_t{b.p} << l) < across && (std::size_t{b.q} << l) < down;
  }
  // Encoder: how many of the block's cells are trimmed, and how many it has.
  [[nodiscard]] std::array<std::size_t, 2> count(const Block& b, std::size_t l) const {
    const auto [x0, x1, y0, y1] = extent(b, l);
    const std::size_t row = across + 1;
    const std::size_t trimmed =
        sums[y1 * row + x1] - sums[y0 * row + x1] - sums[y1 * row + x0] + sums[y0 * row + x0];
    return {trimmed, (x1 - x0) * (y1 - y0)};
  }
  void fill(const Block& b, std::size_t l) {
    const auto [x0, x1, y0, y1] = extent(b, l);
    for (std::size_t y = y0; y < y1; ++y)
      std::fill(cells.begin() + static_cast<std::ptrdiff_t>(y * across + x0),
                cells.begin() + static_cast<std::ptrdiff_t>(y * across + x1), 1);
  }
  // One adaptive decision, or none once the decoder has run out of bytes (then everything stops).
  bool decide(std::size_t context, bool truth, bool& bit) {
    if (rc.exhausted()) {
      stopped = true;
      return false;
    }
    bit = rc.bit(p[context], truth ? 1 : 0) != 0;
    return true;
  }

  // What is known of block (x, y) of level l: its own state, or a uniform block above it.
  [[nodiscard]] std::uint8_t state(std::size_t l, std::size_t x, std::size_t y) const {
    for (std::size_t m = l; m <= top; ++m, x >>= 1, y >>= 1) {
      const std::uint8_t s = known[m][y * blocks_across[m] + x];
      if (s == kAllKept || s == kAllTrimmed) return s;
      if (s == kMixed) return m == l ? kMixed : kUnknown;
    }
    return kUnknown;
  }
  // How many of the left and upper neighbours of `b` (level l) are known to hold a trimmed cell
  // (`trimmed`) or a kept one.
  [[nodiscard]] std::size_t neighbours(const Block& b, std::size_t l, bool trimmed) const {
    std::size_t n = 0;
    const auto holds = [&](std::uint8_t s) {
      return s == kMixed || (trimmed ? s == kAllTrimmed : s == kAllKept);
    };
    if (b.p > 0 && holds(state(l, b.p - 1, b.q))) ++n;
    if (b.q > 0 && holds(state(l, b.p, b.q - 1))) ++n;
    return n;
  }

  // Decides `b` at level l: whether it holds a trimmed cell (`has_trimmed`, unless inferred), then, above
  // single cells, whether it holds a kept one (`has_kept`, unless inferred). Returns false when stopped.
  bool block(const Block& b, std::size_t l, std::optional<bool> trimmed_known, std::optional<bool> kept_known,
             bool& has_trimmed, bool& has_kept) {
    const std::size_t level = std::min(l, kLevelContexts - 1);
    std::array<std::size_t, 2> truth{0, 0};
    if constexpr (Encoding) truth = count(b, l);
    if (trimmed_known) {
      has_trimmed = *trimmed_known;
    } else if (!decide((2 * level) * 3 + neighbours(b, l, true), truth[0] > 0, has_trimmed)) {
      return false;
    }
    if (l == 0 || !has_trimmed) {
      has_kept = !has_trimmed;
    } else if (kept_known) {
      has_kept = *kept_known;
    } else if (!decide((2 * level + 1) * 3 + neighbours(b, l, false), truth[0] < truth[1], has_kept)) {
      return false;
    }
    known[l][b.q * blocks_across[l] + b.p] = has_trimmed && has_kept ? kMixed
                                             : has_trimmed           ? kAllTrimmed
                                                                     : kAllKept;
    if (has_trimmed && !has_kept) fill(b, l);
    return true;
  }

  void run() {
    bool has_trimmed = false, has_kept = false;
    if (!block({0, 0}, top, std::nullopt, std::nullopt, has_trimmed, has_kept)) return;
    if (!(has_trimmed && has_kept)) return;
    std::vector<Block> mixed{{0, 0}}, next;
    for (std::size_t l = top; l-- > 0;) { // the children of level l + 1's mixed blocks
      next.clear();
      for (const Block& parent : mixed) {
        std::array<Block, 4> children;
        std::size_t n = 0;
        for (std::uint32_t dy = 0; dy < 2; ++dy)
          for (std::uint32_t dx = 0; dx < 2; ++dx)
            if (const Block c{2 * parent.p + dx, 2 * parent.q + dy}; exists(c, l)) children[n++] = c;
        bool any_trimmed = false, any_kept = false;
        for (std::size_t i = 0; i < n; ++i) {
          // The parent holds both: its last child holds what none before it did.
          const bool last = i + 1 == n;
          std::optional<bool> trimmed_known, kept_known;
          if (last && !any_trimmed) trimmed_known = true;
          if (last && !any_kept) {
            if (l == 0)
              trimmed_known = false;
            else
              kept_known = true;
          }
          bool t = false, k = false;
          if (!block(children[i], l, trimmed_known, kept_known, t, k)) return;
          any_trimmed = any_trimmed || t;
          any_kept = any_kept || k;
          if (t && k) next.push_back(children[i]);
        }
      }
      std::swap(mixed, next);
    }
  }
};

} // namespace

std::string encode_trim(const std::vector<std::uint8_t>& cells, std::size_t across, std::size_t down) {
  if (cells.size() != across * down || across == 0 || down == 0)
    throw std::invalid_argument("pdef: a trim of another size");
  if (std::ranges::none_of(cells, [](std::uint8_t c) { return c != 0; })) return {};
  Quadtree<range::RangeEncoder, true> tree(range::RangeEncoder{}, across, down, &cells);
  tree.run();
  return tree.rc.finish();
}

DecodedTrim decode_trim(std::string_view stream, std::size_t across, std::size_t down) {
  DecodedTrim out;
  if (stream.empty()) {
    out.cells.assign(across * down, 0);
    return out;
  }
  Quadtree<range::RangeDecoder, false> tree(range::RangeDecoder(stream), across, down, nullptr);
  tree.run();
  out.complete = !tree.stopped;
  out.cells = std::move(tree.cells);
  return out;
}

} // namespace pdeface::pdef::detail
