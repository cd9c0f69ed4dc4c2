#include "load/text_pattern.hpp"

#include <gtest/gtest.h>

#include <string>

namespace tourmap::load {
namespace {

TEST(TextPattern, WholeMatches) {
  EXPECT_TRUE(pattern_matches("U55bau", "U55bau"));
  EXPECT_FALSE(pattern_matches("U55bau", "U55"));
  EXPECT_TRUE(pattern_matches("*bau", "U55bau"));
  EXPECT_FALSE(pattern_matches("*bau", "U55bau2"));
  EXPECT_TRUE(pattern_matches("U#", "U2"));
  EXPECT_TRUE(pattern_matches("U#", "U55"));
  EXPECT_FALSE(pattern_matches("U#", "U"));   // '#' needs a digit
  EXPECT_FALSE(pattern_matches("U#", "U5a"));
  EXPECT_TRUE(pattern_matches("?5", "U5"));
  EXPECT_TRUE(pattern_matches("?5", "\xC3\x9C" "5"));   // '?' is one character: Ü, two bytes
  EXPECT_FALSE(pattern_matches("??5", "\xC3\x9C" "5"));
  EXPECT_TRUE(pattern_matches("a*b*c", "axxbyyc"));
  EXPECT_FALSE(pattern_matches("a*b*c", "axxcyyb"));
}

TEST(TextPattern, EscapesTakeCharactersLiterally) {
  EXPECT_TRUE(pattern_matches("\\*bau", "*bau"));
  EXPECT_FALSE(pattern_matches("\\*bau", "U5bau"));
  EXPECT_TRUE(pattern_matches("Line \\#1", "Line #1"));
  EXPECT_FALSE(pattern_matches("Line \\#1", "Line 11"));
  EXPECT_TRUE(pattern_matches("a\\\\b", "a\\b"));
}

TEST(TextPattern, ShortestPrefixAndSuffix) {
  EXPECT_EQ(shortest_prefix_match("U ", "U Alt-Tegel"), 2u);
  EXPECT_EQ(shortest_prefix_match("U ", "Ullsteinstr."), 0u);
  EXPECT_EQ(shortest_prefix_match("*, ", "Berlin, U Stadtmitte, Mitte"), 8u);  // the first ", "
  EXPECT_EQ(shortest_suffix_match(" (Berlin)", "U Alt-Tegel (Berlin)"), 9u);
  EXPECT_EQ(shortest_suffix_match(" U#", "Stadtmitte U2"), 3u);
  EXPECT_EQ(shortest_suffix_match(" U#", "Stadtmitte U55"), 4u);
  EXPECT_EQ(shortest_suffix_match(" U#", "Stadtmitte"), 0u);
  EXPECT_EQ(shortest_suffix_match(", *", "Leinfelden Bahnhof, Leinfelden-Echterdingen"),
            std::string(", Leinfelden-Echterdingen").size());  // the last ", "
  // Never inside a character: "?" at the end takes the whole ü (two bytes).
  EXPECT_EQ(shortest_suffix_match("?", "M\xC3\xBC"), 2u);
  EXPECT_EQ(shortest_prefix_match("?", "\xC3\xBC" "x"), 2u);
}

TEST(TextPattern, Errors) {
  EXPECT_EQ(pattern_error(" (Berlin)"), "");
  EXPECT_EQ(pattern_error("U#"), "");
  EXPECT_NE(pattern_error("*"), "");    // would match every name's empty prefix
  EXPECT_NE(pattern_error("**"), "");
  EXPECT_NE(pattern_error("abc\\"), "");  // lone trailing backslash
  EXPECT_EQ(pattern_error("abc\\\\"), "");
  EXPECT_NE(pattern_error("\xC3"), "");   // not UTF-8
}

TEST(TextPattern, LongInputsStayFast) {
  // Many stars against a long name without the final letter: a backtracking matcher would
  // take exponential time here.
  std::string pattern;
  for (int i = 0; i < 50; ++i) pattern += "a*";
  pattern += "b";
  const std::string name(1024, 'a');
  EXPECT_FALSE(pattern_matches(pattern, name));
  EXPECT_EQ(shortest_suffix_match(pattern, name), 0u);
  EXPECT_EQ(shortest_prefix_match(pattern, name), 0u);
}

}  // namespace
}  // namespace tourmap::load
