#pragma once
// The simple patterns of the name rules (name_rules.hpp): literal text, except
//   *   any run of characters, also none
//   ?   any one character
//   #   one or more ASCII digits (a line number: " U#" matches " U2" and " U55")
//   \   takes the next character literally ("\*" is a star, "\\" a backslash)
// Matching works on UTF-8 code points and takes time linear in pattern length x text length
// (no backtracking), so hostile patterns or names cannot blow up.

#include <cstddef>
#include <string>
#include <string_view>

namespace tourmap::load {

// Why `pattern` is not a usable pattern (malformed UTF-8, a trailing '\', matches the empty
// text), or "" when it is.
std::string pattern_error(std::string_view pattern);

// True when the pattern matches the whole text.
bool pattern_matches(std::string_view pattern, std::string_view text);

// Bytes of the shortest non-empty prefix / suffix of `text` that the pattern matches, 0 if none.
std::size_t shortest_prefix_match(std::string_view pattern, std::string_view text);
std::size_t shortest_suffix_match(std::string_view pattern, std::string_view text);

}  // namespace tourmap::load
