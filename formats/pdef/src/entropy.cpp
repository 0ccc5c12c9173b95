#include "entropy.hpp"

#include <draco/compression/entropy/ans.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <limits>
#include <stdexcept>

namespace pdeface::pdef::detail {

namespace {

constexpr int kPrecisionBits = 12;
constexpr std::uint32_t kPrecision = 1U << kPrecisionBits;
constexpr std::uint32_t kClasses = 64; // 0-3, then two per power of two up to 2^32
constexpr std::uint32_t kMaxLevel = 31;

// The class of a symbol, its lower bits' count and their value.
struct Split {
  std::uint32_t klass;
  int bits;
  std::uint32_t rest;
};
Split split(std::uint32_t s) {
  if (s < 4) return {s, 0, 0};
  const int b = static_cast<int>(std::bit_width(s)) - 1; // s in [2^b, 2^(b+1)), b >= 2
  const std::uint32_t half = (s >> (b - 1)) & 1U;
  return {4 + 2 * static_cast<std::uint32_t>(b - 2) + half, b - 1, s & ((1U << (b - 1)) - 1)};
}
// The smallest symbol of a class and its lower bits' count.
std::pair<std::uint32_t, int> class_base(std::uint32_t klass) {
  if (klass < 4) return {klass, 0};
  const int b = static_cast<int>((klass - 4) / 2) + 2;
  return {((2U + ((klass - 4) & 1U)) << (b - 1)), b - 1};
}

// Half-octave weights: level q (1..31) stands for a relative frequency of 2^(q/2); 0 for none.
constexpr std::array<std::uint32_t, kMaxLevel + 1> kLevelWeight = [] {
  std::array<std::uint32_t, kMaxLevel + 1> w{};
  for (std::uint32_t q = 1; q <= kMaxLevel; ++q) {
    // round(2^(q/2) * 4): 2^(q/2) = 2^(q div 2) * (q odd ? sqrt 2 : 1), with sqrt 2 * 2^20 = 1482910.4
    const std::uint64_t root2 = 1482910;
    const std::uint64_t scaled = (q % 2 == 1 ? root2 : std::uint64_t{1} << 20) << (q / 2);
    w[q] = static_cast<std::uint32_t>((scaled * 4 + (std::uint64_t{1} << 19)) >> 20);
  }
  return w;
}();

// The frequencies (summing to kPrecision, each present class at least 1) the levels stand for.
std::array<std::uint32_t, kClasses> frequencies(const std::array<std::uint8_t, kClasses>& levels) {
  std::array<std::uint32_t, kClasses> f{};
  std::uint64_t total = 0;
  for (std::uint32_t c = 0; c < kClasses; ++c)
    total += kLevelWeight[levels[c]];
  if (total == 0) return f;
  std::uint32_t sum = 0, largest = 0;
  for (std::uint32_t c = 0; c < kClasses; ++c) {
    if (levels[c] == 0) continue;
    f[c] = std::max<std::uint32_t>(
        1, static_cast<std::uint32_t>(kLevelWeight[levels[c]] * std::uint64_t{kPrecision} / total));
    sum += f[c];
    if (f[c] > f[largest] || levels[largest] == 0) largest = c;
  }
  f[largest] = f[largest] + kPrecision - sum; // the rounding, on the most frequent class (stays >= 1)
  return f;
}

// The level of a class seen `count` times among `n`: 2 log2(count / n) + 29 in half octaves, at least 1.
std::uint8_t level_of(std::uint64_t count, std::uint64_t n) {
  if (count == 0) return 0;
  const std::uint64_t r = (count << 28) / n; // (0, 2^28]
  if (r == 0) return 1;
  const int b = static_cast<int>(std::bit_width(r)) - 1;
  const bool upper_half = r * r >= (std::uint64_t{2} << (2 * b)); // r >= 2^(b + 1/2)
  const int q = 2 * b + (upper_half ? 1 : 0) - 27;
  return static_cast<std::uint8_t>(std::clamp(q, 1, static_cast<int>(kMaxLevel)));
}

} // namespace

std::string encode_classes(std::span<const std::uint32_t> symbols) {
  std::array<std::uint64_t, kClasses> counts{};
  for (const std::uint32_t s : symbols)
    ++counts[split(s).klass];
  std::uint32_t used = 0;
  std::array<std::uint8_t, kClasses> levels{};
  for (std::uint32_t c = 0; c < kClasses; ++c) {
    levels[c] = level_of(counts[c], std::max<std::size_t>(symbols.size(), 1));
    if (levels[c] != 0) used = c + 1;
  }
  // The table: how many classes, then a 5-bit level for each, packed.
  std::string out(1, static_cast<char>(used));
  std::uint32_t acc = 0;
  int filled = 0;
  for (std::uint32_t c = 0; c < used; ++c) {
    acc |= std::uint32_t{levels[c]} << filled;
    filled += 5;
    while (filled >= 8) {
      out.push_back(static_cast<char>(acc & 0xff));
      acc >>= 8;
      filled -= 8;
    }
  }
  if (filled > 0) out.push_back(static_cast<char>(acc & 0xff));
  if (symbols.empty()) return out;

  // The classes by rANS, last symbol first (the decoder reads them first to last).
  const std::array<std::uint32_t, kClasses> f = frequencies(levels);
  std::array<std::uint32_t, kClasses> cumulative{};
  for (std::uint32_t c = 1; c < kClasses; ++c)
    cumulative[c] = cumulative[c - 1] + f[c - 1];
  std::vector<std::uint8_t> coded(symbols.size() * 2 + 16);
  draco::RAnsEncoder<kPrecisionBits> rans;
  rans.write_init(coded.data());
  for (std::size_t i = symbols.size(); i-- > 0;) {
    const std::uint32_t c = split(symbols[i]).klass;
    const draco::rans_sym sym{f[c], cumulative[c]};
    rans.rans_write(&sym);
  }
  const int size = rans.write_end();
  std::string lengths;
  for (auto v = static_cast<std::uint32_t>(size);; v >>= 7) { // a varint
    lengths.push_back(static_cast<char>((v & 0x7f) | (v >= 0x80 ? 0x80 : 0)));
    if (v < 0x80) break;
  }
  out += lengths;
  out.append(reinterpret_cast<const char*>(coded.data()), static_cast<std::size_t>(size));

  // The lower bits, least significant first.
  std::uint64_t bits = 0;
  int count = 0;
  for (const std::uint32_t s : symbols) {
    const Split p = split(s);
    for (int b = 0; b < p.bits; ++b) {
      bits |= std::uint64_t{(p.rest >> b) & 1U} << count;
      if (++count == 8) {
        out.push_back(static_cast<char>(bits & 0xff));
        bits = 0;
        count = 0;
      }
    }
  }
  if (count > 0) out.push_back(static_cast<char>(bits & 0xff));
  return out;
}

std::optional<std::size_t> decode_classes(std::string_view bytes, std::span<std::uint32_t> out) {
  std::size_t pos = 0;
  if (bytes.empty()) return std::nullopt;
  const auto used = static_cast<std::uint8_t>(bytes[pos++]);
  if (used > kClasses) return std::nullopt;
  const std::size_t table = (std::size_t{used} * 5 + 7) / 8;
  if (bytes.size() - pos < table) return std::nullopt;
  std::array<std::uint8_t, kClasses> levels{};
  for (std::uint32_t c = 0; c < used; ++c) {
    const std::size_t bit = std::size_t{c} * 5;
    std::uint32_t v = static_cast<std::uint8_t>(bytes[pos + bit / 8]);
    if (bit / 8 + 1 < table) v |= std::uint32_t{static_cast<std::uint8_t>(bytes[pos + bit / 8 + 1])} << 8;
    levels[c] = static_cast<std::uint8_t>((v >> (bit % 8)) & 0x1f);
  }
  // Padding bits after the last level are zero, and the last class listed is present.
  if (used > 0 &&
      (levels[used - 1] == 0 || (std::size_t{used} * 5 % 8 != 0 &&
                                 (static_cast<std::uint8_t>(bytes[pos + table - 1]) >> (used * 5 % 8)) != 0)))
    return std::nullopt;
  pos += table;
  if (out.empty()) return used == 0 ? std::optional<std::size_t>(pos) : std::nullopt;
  if (used == 0) return std::nullopt;

  std::uint32_t size = 0;
  for (int i = 0;; ++i) { // a varint of at most 4 bytes
    if (pos >= bytes.size() || i == 4) return std::nullopt;
    const auto b = static_cast<std::uint8_t>(bytes[pos++]);
    size |= std::uint32_t{b & 0x7fU} << (7 * i);
    if ((b & 0x80) == 0) break;
  }
  if (size < 1 || size > bytes.size() - pos) return std::nullopt;
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data() + pos);
  // Draco's read_init trusts the length its last byte claims for the final state (1-4 bytes).
  if ((data[size - 1] >> 6) + 1U > size) return std::nullopt;
  const std::array<std::uint32_t, kClasses> f = frequencies(levels);
  draco::RAnsDecoder<kPrecisionBits> rans;
  if (!rans.rans_build_look_up_table(f.data(), kClasses) || rans.read_init(data, static_cast<int>(size)) != 0)
    return std::nullopt;
  std::uint64_t lower_bits = 0;
  for (std::uint32_t& s : out) {
    s = static_cast<std::uint32_t>(rans.rans_read());
    lower_bits += static_cast<std::uint64_t>(class_base(s).second);
  }
  // (Draco's coder does not always end in the state it started from: when the last symbol is rare its
  // encoder already renormalises the initial state, so the final state is no integrity check.)
  pos += size;
  if ((lower_bits + 7) / 8 > bytes.size() - pos) return std::nullopt;
  std::uint64_t bit = 0;
  for (std::uint32_t& s : out) {
    const auto [base, n] = class_base(s);
    std::uint32_t rest = 0;
    for (int b = 0; b < n; ++b, ++bit)
      rest |= std::uint32_t{(static_cast<std::uint8_t>(bytes[pos + bit / 8]) >> (bit % 8)) & 1U} << b;
    s = base + rest;
  }
  pos += (lower_bits + 7) / 8;
  if (lower_bits % 8 != 0 && (static_cast<std::uint8_t>(bytes[pos - 1]) >> (lower_bits % 8)) != 0)
    return std::nullopt;
  return pos;
}

std::string zstd_compress(std::string_view bytes, int level) {
  std::string out(ZSTD_compressBound(bytes.size()), '\0');
  const std::size_t n = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), level);
  if (ZSTD_isError(n) != 0U) throw std::invalid_argument(std::string("pdef: zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::optional<std::string> zstd_decompress(std::string_view frame, std::size_t expected) {
  if (ZSTD_findFrameCompressedSize(frame.data(), frame.size()) != frame.size()) return std::nullopt;
  if (ZSTD_getFrameContentSize(frame.data(), frame.size()) != expected) return std::nullopt;
  std::string out(expected, '\0');
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), frame.data(), frame.size());
  if (ZSTD_isError(n) != 0U || n != expected) return std::nullopt;
  return out;
}

std::string shuffle(std::string_view values, std::size_t width) {
  const std::size_t n = values.size() / width;
  std::string out(values.size(), '\0');
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < width; ++b)
      out[b * n + i] = values[i * width + b];
  return out;
}

std::string unshuffle(std::string_view planes, std::size_t width) {
  const std::size_t n = planes.size() / width;
  std::string out(planes.size(), '\0');
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < width; ++b)
      out[i * width + b] = planes[b * n + i];
  return out;
}

std::uint32_t crc32(std::string_view bytes) {
  uLong crc = ::crc32(0L, Z_NULL, 0);
  while (!bytes.empty()) {
    const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size(), UINT_MAX));
    crc = ::crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), n);
    bytes.remove_prefix(n);
  }
  return static_cast<std::uint32_t>(crc);
}

} // namespace pdeface::pdef::detail
