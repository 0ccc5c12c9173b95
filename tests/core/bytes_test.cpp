// The one little-endian reader and writer: fields round-trip, the byte order is little-endian whatever the
// machine's, and varints are in their shortest form.

#include "pdeface/core/bytes.hpp"

#include <gtest/gtest.h>

namespace pdeface {
namespace {

TEST(Bytes, WritesLittleEndianAndLoadsItBack) {
  ByteWriter w;
  w.u8(0x01);
  w.u16(0x0302);
  w.u32(0x07060504);
  w.u64(0x0f0e0d0c0b0a0908);
  w.f32(1.5F);
  w.f64(-2.25);
  const std::string& b = w.str();
  ASSERT_EQ(b.size(), 1U + 2 + 4 + 8 + 4 + 8);
  for (int i = 0; i < 15; ++i) // the integers' bytes: 1, 2, ..., 15
    EXPECT_EQ(static_cast<int>(static_cast<unsigned char>(b[i])), i + 1) << i;
  EXPECT_EQ(load_le<std::uint16_t>(b, 1), 0x0302U);
  EXPECT_EQ(load_le<std::uint32_t>(b, 3), 0x07060504U);
  EXPECT_EQ(load_le<std::uint64_t>(b, 7), 0x0f0e0d0c0b0a0908ULL);
  EXPECT_EQ(load_le_f32(b.data() + 15), 1.5F);
  EXPECT_EQ(load_le_f64(b.data() + 19), -2.25);
  static_assert(load_le<std::uint16_t>("\x34\x12") == 0x1234); // the same at compile time
}

TEST(Bytes, StoresInPlace) {
  char out[4] = {};
  store_le<std::uint32_t>(out, 0xdeadbeef);
  EXPECT_EQ(load_le<std::uint32_t>(out), 0xdeadbeefU);
  EXPECT_EQ(static_cast<unsigned char>(out[0]), 0xefU);
  store_le_f32(out, 0.5F);
  EXPECT_EQ(load_le_f32(out), 0.5F);
}

TEST(Bytes, VarintsAreLeb128InTheirShortestForm) {
  ByteWriter w;
  w.varint(0);
  w.varint(127);
  w.varint(128);
  w.varint(300);
  EXPECT_EQ(w.str(), std::string("\x00\x7f\x80\x01\xac\x02", 6));
}

} // namespace
} // namespace pdeface
