#include "load/csv.hpp"
#include "load/load_error.hpp"

#include <gtest/gtest.h>

namespace tourmap::load {
namespace {

TEST(Csv, ParsesQuotesCommasNewlinesAndCrlf) {
  auto t = parse_csv("\xEF\xBB\xBFid,name,note\r\n1,\"Acton, Town\",\"said \"\"hi\"\"\"\r\n2,B,\"two\nlines\"\r\n", "t.csv");
  ASSERT_EQ(t.header.size(), 3u);
  EXPECT_EQ(t.header[0], "id");  // BOM stripped
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][1], "Acton, Town");
  EXPECT_EQ(t.rows[0][2], "said \"hi\"");
  EXPECT_EQ(t.rows[1][2], "two\nlines");
  EXPECT_EQ(t.row_lines[0], 2u);
  EXPECT_EQ(t.row_lines[1], 3u);
}

TEST(Csv, EmptyTrailingFieldsAndBlankLines) {
  auto t = parse_csv("a,b\n1,\n\n2,3\n", "t.csv");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][1], "");
  EXPECT_EQ(t.row_lines[1], 4u);
}

TEST(Csv, FieldCountMismatchNamesTheLine) {
  try {
    parse_csv("a,b\n1,2\n3\n", "x.csv");
    FAIL() << "expected LoadError";
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "x.csv line 3");
    EXPECT_NE(std::string(e.what()).find("expected 2 fields, found 1"), std::string::npos);
  }
}

TEST(Csv, UnterminatedQuoteIsAnError) {
  EXPECT_THROW(parse_csv("a,b\n1,\"open\n", "x.csv"), LoadError);
}

TEST(Csv, MissingColumnNamesTheColumn) {
  auto t = parse_csv("Latitude,Name\n1,x\n", "m.csv");
  EXPECT_EQ(t.column({"latitude"}), 0u);  // case-insensitive
  try {
    t.column({"longitude", "lon"});
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("missing column 'longitude'"), std::string::npos);
  }
}

TEST(Csv, NumbersMustBeFinite) {
  EXPECT_DOUBLE_EQ(parse_number(" -0.25 ", "w", "c"), -0.25);
  EXPECT_THROW(parse_number("abc", "w", "c"), LoadError);
  EXPECT_THROW(parse_number("", "w", "c"), LoadError);
  EXPECT_THROW(parse_number("inf", "w", "c"), LoadError);
  EXPECT_THROW(parse_number("1.5x", "w", "c"), LoadError);
  EXPECT_TRUE(is_null_field("NULL"));
  EXPECT_TRUE(is_null_field(" "));
}

TEST(Csv, EmptyFileIsAnError) { EXPECT_THROW(parse_csv("", "e.csv"), LoadError); }

}  // namespace
}  // namespace tourmap::load
