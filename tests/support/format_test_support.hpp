#pragma once
// Helpers for the format tests: fixtures, binary packing, notes, errors and round-trip checks.

#include "pdeface/core/file.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::test {

static_assert(std::endian::native == std::endian::little, "the binary fixtures are packed little-endian");

//! Appends the bytes of `value` (little-endian).
template <class T> void put(std::string& out, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

//! The bytes of tests/data/<folder>/<name>.
inline std::string fixture(std::string_view folder, std::string_view name) {
  Result<std::string> bytes = read_file(fixtures() / folder / name);
  EXPECT_TRUE(bytes.ok()) << name;
  return bytes ? *bytes : std::string();
}

//! Whether some note contains `text`.
inline bool has_note(const Notes& notes, std::string_view text) {
  return std::ranges::any_of(notes, [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

//! The error of a result that must have failed.
template <class T> Error error_of(const Result<T>& result) {
  EXPECT_FALSE(result.ok()) << "expected an error";
  return result.ok() ? Error{} : result.error();
}

//! A bad input and the error reading it must give: its code, line and column.
struct ErrorCase {
  std::string text;
  ErrorCode code;
  std::uint64_t line;
  std::uint64_t column;
};

//! Each case read by `read` (a format's reader, the input named `source`) fails with the case's error at
//! its line and column, naming `source`.
template <class Read>
void expect_errors_at(Read read, std::string_view source, const std::vector<ErrorCase>& cases) {
  for (const ErrorCase& c : cases) {
    const Error e = error_of(read(c.text, source, nullptr));
    EXPECT_EQ(e.code, c.code) << c.text << ": " << e.message;
    EXPECT_EQ(e.where.line, c.line) << c.text << ": " << e.message;
    EXPECT_EQ(e.where.column, c.column) << c.text << ": " << e.message;
    EXPECT_EQ(e.source, source) << c.text;
  }
}

//! `mesh` with every coordinate rounded to float32, as a float format stores it.
inline Mesh float_rounded(Mesh mesh) {
  for (Vec3& p : mesh.positions)
    p = p.cast<float>().cast<double>();
  return mesh;
}

//! Colours as 8-bit channels store them.
inline std::vector<Vec4f> byte_rounded(std::vector<Vec4f> colors) {
  for (Vec4f& c : colors)
    c = ((c * 255.0f).array().round() / 255.0f).matrix();
  return colors;
}

//! Positions equal to the float-rounded originals; triangles identical.
inline void expect_same_geometry(const Mesh& original, const Mesh& read) {
  const Mesh expected = float_rounded(original);
  ASSERT_EQ(read.vertex_count(), expected.vertex_count());
  ASSERT_EQ(read.triangle_count(), expected.triangle_count());
  EXPECT_EQ(read.positions, expected.positions);
  EXPECT_EQ(read.triangles, expected.triangles);
}

} // namespace pdeface::test
