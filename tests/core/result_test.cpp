#include "pdeface/core/result.hpp"

#include <gtest/gtest.h>

#include <set>
#include <utility>
#include <vector>

namespace pdeface {
namespace {

TEST(Error, NamesSourceLineAndColumn) {
  const Error e = make_error(ErrorCode::Malformed, "expected '}'", "face.wrl", Location::at_line(12, 5));
  EXPECT_EQ(e.to_string(), "face.wrl:12:5: malformed: expected '}'");
}

TEST(Error, NamesByteOffsetForBinaryData) {
  const Error e =
      make_error(ErrorCode::Truncated, "vertex 7 ends past the data", "scan.ply", Location::at_byte(1234));
  EXPECT_EQ(e.to_string(), "scan.ply: byte 1234: truncated: vertex 7 ends past the data");
}

TEST(Error, WithoutLocationOrSource) {
  EXPECT_EQ(make_error(ErrorCode::Io, "cannot open").to_string(), "<input>: i/o error: cannot open");
}

TEST(Result, HoldsValueOrError) {
  Result<int> good = 42;
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 42);
  Result<int> bad = make_error(ErrorCode::Empty, "nothing");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::Empty);
  Result<void> fine;
  EXPECT_TRUE(fine.ok());
  Result<void> broken = make_error(ErrorCode::NonFinite, "nan");
  EXPECT_FALSE(broken);
  EXPECT_EQ(broken.error().message, "nan");
}

TEST(Result, DereferencingAnRvalueMovesTheValueOut) {
  // The same buffer after `*std::move(r)`: moved, not copied (a copy has its own).
  Result<std::vector<int>> made = std::vector<int>(1000, 7);
  const int* buffer = made->data();
  const std::vector<int> taken = *std::move(made);
  EXPECT_EQ(taken.data(), buffer);
  EXPECT_EQ(taken.size(), 1000U);
  // An lvalue still copies.
  Result<std::vector<int>> kept = std::vector<int>(10, 1);
  const std::vector<int> copy = *kept;
  EXPECT_NE(copy.data(), kept->data());
  EXPECT_EQ(kept->size(), 10U);
}

TEST(ErrorCode, EveryCodeHasItsOwnName) {
  std::set<std::string_view> names;
  for (int c = 0; c <= static_cast<int>(ErrorCode::ChecksumMismatch); ++c)
    names.insert(to_string(static_cast<ErrorCode>(c)));
  EXPECT_EQ(names.size(), static_cast<std::size_t>(ErrorCode::ChecksumMismatch) + 1);
}

} // namespace
} // namespace pdeface

namespace pdeface {
namespace {

TEST(Location, LineAndColumnOfAByteOffset) {
  const std::string_view text = "ab\ncde\n\nf";
  auto at = [&](std::uint64_t offset) {
    const Location l = Location::in_text(text, offset);
    return std::pair{l.line, l.column};
  };
  EXPECT_EQ(at(0), (std::pair<std::uint64_t, std::uint64_t>{1, 1}));
  EXPECT_EQ(at(1), (std::pair<std::uint64_t, std::uint64_t>{1, 2}));
  EXPECT_EQ(at(3), (std::pair<std::uint64_t, std::uint64_t>{2, 1}));
  EXPECT_EQ(at(5), (std::pair<std::uint64_t, std::uint64_t>{2, 3}));
  EXPECT_EQ(at(8), (std::pair<std::uint64_t, std::uint64_t>{4, 1}));
  EXPECT_EQ(at(100),
            (std::pair<std::uint64_t, std::uint64_t>{4, 2})); // past the end: just after the last byte
}

} // namespace
} // namespace pdeface
