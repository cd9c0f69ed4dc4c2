#include "load/text_repair.hpp"

#include <gtest/gtest.h>

namespace tourmap::load {
namespace {

TEST(TextRepair, RepairsDoubleEncodedUtf8) {
  EXPECT_EQ(repair_mojibake("Shakespeare\xC3\xA2\xE2\x82\xAC\xE2\x84\xA2s"), "Shakespeare\xE2\x80\x99s");  // â€™ -> ’
  EXPECT_EQ(repair_mojibake("Caf\xC3\x83\xC2\xA9"), "Caf\xC3\xA9");  // Ã© -> é
}

TEST(TextRepair, LeavesCorrectTextAlone) {
  EXPECT_EQ(repair_mojibake("Sigmund Freud Museum"), "Sigmund Freud Museum");
  EXPECT_EQ(repair_mojibake("Stra\xC3\x9F" "e"), "Stra\xC3\x9F" "e");          // Straße
  EXPECT_EQ(repair_mojibake("S\xC3\x83O SEBASTI\xC3\x83O"), "S\xC3\x83O SEBASTI\xC3\x83O");  // SÃO is real Portuguese
  EXPECT_EQ(repair_mojibake("\xE6\x9D\xB1\xE4\xBA\xAC"), "\xE6\x9D\xB1\xE4\xBA\xAC");        // 東京
}

TEST(TextRepair, Utf8Validation) {
  EXPECT_TRUE(is_valid_utf8("plain"));
  EXPECT_TRUE(is_valid_utf8("\xE2\x80\x99"));
  EXPECT_FALSE(is_valid_utf8("\xC3"));
  EXPECT_FALSE(is_valid_utf8("\xC0\xAF"));  // overlong
}

}  // namespace
}  // namespace tourmap::load
