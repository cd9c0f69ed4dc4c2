#include "load/utf8.hpp"

#include <gtest/gtest.h>

namespace tourmap::load {
namespace {

TEST(Utf8, DecodesAndEncodesEveryLength) {
  const std::string text = "A\xC3\xA9\xE2\x82\xAC\xF0\x9F\x9A\x87";  // A é € 🚇
  std::size_t i = 0;
  std::string again;
  for (std::uint32_t expected : {0x41u, 0xE9u, 0x20ACu, 0x1F687u}) {
    auto cp = decode_utf8(text, i);
    ASSERT_TRUE(cp);
    EXPECT_EQ(*cp, expected);
    append_utf8(again, *cp);
  }
  EXPECT_EQ(i, text.size());
  EXPECT_EQ(again, text);
  std::size_t at = 0;
  EXPECT_FALSE(decode_utf8("\xC3", at));  // cut short
  EXPECT_EQ(at, 0u);
  EXPECT_FALSE(decode_utf8("\xED\xA0\x80", at));  // a surrogate
}

TEST(Utf8, CaseOfAccentedLatinCapitals) {
  // Portuguese, German, French, Polish, Czech, Romanian capitals and their small letters.
  const std::pair<std::uint32_t, std::uint32_t> pairs[] = {
      {'A', 'a'},       {0xC3, 0xE3} /* Ã ã */, {0xC7, 0xE7} /* Ç ç */, {0xCA, 0xEA} /* Ê ê */,
      {0xD3, 0xF3} /* Ó ó */, {0xDC, 0xFC} /* Ü ü */, {0x0141, 0x0142} /* Ł ł */, {0x0160, 0x0161} /* Š š */,
      {0x0179, 0x017A} /* Ź ź */, {0x0218, 0x0219} /* Ș ș */, {0x0178, 0xFF} /* Ÿ ÿ */};
  for (auto [upper, lower] : pairs) {
    EXPECT_TRUE(is_upper(upper)) << upper;
    EXPECT_TRUE(is_lower(lower)) << lower;
    EXPECT_EQ(to_lower(upper), lower) << upper;
    EXPECT_EQ(to_upper(lower), upper) << lower;
  }
  EXPECT_FALSE(is_upper(0xD7));  // × is not a letter
  EXPECT_TRUE(is_lower(0xDF));   // ß: no simple capital, stays as it is
  EXPECT_EQ(to_upper(0xDF), 0xDFu);
  EXPECT_EQ(to_upper('i'), static_cast<std::uint32_t>('I'));  // not the Turkish İ
}

TEST(Utf8, CaseOfGreekAndCyrillic) {
  EXPECT_EQ(to_lower(0x0391), 0x03B1u);  // Α α
  EXPECT_EQ(to_lower(0x0386), 0x03ACu);  // Ά ά
  EXPECT_EQ(to_upper(0x03C2), 0x03A3u);  // ς Σ
  EXPECT_EQ(to_lower(0x0416), 0x0436u);  // Ж ж
  EXPECT_EQ(to_lower(0x0401), 0x0451u);  // Ё ё
  EXPECT_EQ(to_upper(0x0451), 0x0401u);
  EXPECT_FALSE(is_upper(0x6771));  // 東 has no case
  EXPECT_FALSE(is_lower(0x6771));
}

TEST(Utf8, LowerCasesWholeStrings) {
  EXPECT_EQ(lower_utf8("S\xC3\x83O SEBASTI\xC3\x83O"), "s\xC3\xA3o sebasti\xC3\xA3o");  // SÃO SEBASTIÃO
  EXPECT_EQ(lower_utf8("\xC3"), "\xC3");  // malformed: unchanged
}

}  // namespace
}  // namespace tourmap::load
