#pragma once
// Helpers shared by the VRML tests.

#include "pdeface_test.hpp"

#include "pdeface/core/file.hpp"
#include "pdeface/vrml/vrml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>

namespace pdeface::test {

//! The bytes of tests/data/vrml/<name> (fails the test if it cannot be read).
inline std::string vrml_fixture(std::string_view name) {
  Result<std::string> bytes = read_file(fixtures() / "vrml" / name);
  EXPECT_TRUE(bytes.ok()) << "cannot read fixture " << name;
  return bytes ? std::move(bytes).value() : std::string();
}

//! Reads VRML text as the file "test.wrl".
inline Result<Mesh> read_vrml(std::string_view text, Notes* notes = nullptr) {
  return vrml::read(text, "test.wrl", notes);
}

//! The read failed with `code` at line:column.
inline ::testing::AssertionResult fails_at(const Result<Mesh>& result, ErrorCode code, std::uint64_t line,
                                           std::uint64_t column) {
  if (result.ok()) return ::testing::AssertionFailure() << "read succeeded, expected " << to_string(code);
  const Error& e = result.error();
  if (e.code != code || e.where.line != line || e.where.column != column || e.source != "test.wrl")
    return ::testing::AssertionFailure() << "got '" << e.to_string() << "', expected " << to_string(code)
                                         << " at " << line << ":" << column;
  return ::testing::AssertionSuccess() << e.to_string();
}

//! Some note contains `text`.
inline ::testing::AssertionResult has_note(const Notes& notes, std::string_view text) {
  if (std::any_of(notes.begin(), notes.end(),
                  [&](const std::string& n) { return n.find(text) != std::string::npos; }))
    return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure() << "no note contains '" << text << "'; notes:";
  for (const std::string& n : notes)
    failure << "\n  " << n;
  return failure;
}

//! Each of `texts` is contained in some note.
inline ::testing::AssertionResult has_notes(const Notes& notes,
                                            std::initializer_list<std::string_view> texts) {
  bool all = true;
  auto failure = ::testing::AssertionFailure();
  for (std::string_view text : texts)
    if (!has_note(notes, text)) {
      all = false;
      failure << "no note contains '" << text << "'\n";
    }
  if (all) return ::testing::AssertionSuccess();
  failure << "notes:";
  for (const std::string& n : notes)
    failure << "\n  " << n;
  return failure;
}

} // namespace pdeface::test
