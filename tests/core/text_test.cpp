// Text from files made safe to show and to store: excerpts for messages, names for writers.
#include "pdeface/core/text.hpp"

#include "pdeface_test.hpp"

#include <string>
#include <vector>

namespace pdeface {
namespace {

TEST(Text, ExcerptKeepsShortTextAndCutsLongText) {
  EXPECT_EQ(excerpt("facet"), "facet");
  const std::string long_word(1 << 20, 'x');
  EXPECT_EQ(excerpt(long_word), std::string(kMaxExcerpt, 'x') + "...");
  EXPECT_EQ(excerpt("abcdef", 3), "abc...");
}

TEST(Text, ExcerptIsOneLineOfValidUtf8) {
  // Control characters (a terminal escape, a newline) are written out; invalid bytes become U+FFFD.
  EXPECT_EQ(excerpt("a\x1b[2Jb\nc"), "a\\x1b[2Jb\\x0ac");
  EXPECT_EQ(excerpt("ok\xff"), "ok\xEF\xBF\xBD");
  // A cut never splits a character: 29 two-byte characters in 59 bytes.
  std::string accents;
  for (int i = 0; i < 40; ++i)
    accents += "\xC3\xA9"; // é
  const std::string cut = excerpt(accents, 59);
  EXPECT_TRUE(is_valid_utf8(cut)) << cut;
  EXPECT_EQ(cut.size(), 58U + 3U);
}

TEST(Text, ExcerptListNamesAFew) {
  const std::vector<std::string> items{"a", "b", "c"};
  EXPECT_EQ(excerpt_list(items), "a, b, c");
  EXPECT_EQ(excerpt_list(items, 2), "a, b and 1 more");
  const std::vector<std::string> many(1000, std::string(1000, 'n'));
  EXPECT_LT(excerpt_list(many).size(), kMaxListed * (kMaxExcerpt + 5) + 20);
}

TEST(Text, ValidUtf8ReplacesOnlyWhatIsInvalid) {
  EXPECT_EQ(valid_utf8("na\xC3\xAFve"), "na\xC3\xAFve");
  EXPECT_EQ(valid_utf8("bad\xff"), "bad\xEF\xBF\xBD");
  EXPECT_TRUE(is_valid_utf8(valid_utf8("\xC3\x28\xA0\xA1\xE2\x28\xA1")));
  EXPECT_FALSE(is_valid_utf8("\xC3\x28"));
}

TEST(Text, CleanNameIsOneTrimmedLineOfBoundedUtf8) {
  EXPECT_EQ(clean_name("  face\tscan\n "), "face scan");
  EXPECT_EQ(clean_name("x\xffy"), "x\xEF\xBF\xBDy");
  EXPECT_EQ(clean_name("\n\n"), "");
  std::string accents;
  for (int i = 0; i < 1000; ++i)
    accents += "\xC3\xA9";
  const std::string cut = clean_name(accents);
  EXPECT_EQ(cut.size(), kMaxNameBytes);
  EXPECT_TRUE(is_valid_utf8(cut));
}

} // namespace
} // namespace pdeface
