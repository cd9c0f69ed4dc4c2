#include "load/text_pattern.hpp"

#include "load/text_repair.hpp"

#include <vector>

namespace tourmap::load {
namespace {

enum class Kind { byte, one, digits, run };
struct Token {
  Kind kind;
  char byte = 0;  // Kind::byte
};

// A trailing lone '\' is taken literally (pattern_error reports it; matching never fails).
std::vector<Token> tokenize(std::string_view p) {
  std::vector<Token> tokens;
  for (std::size_t i = 0; i < p.size(); ++i) {
    char c = p[i];
    if (c == '\\' && i + 1 < p.size()) tokens.push_back({Kind::byte, p[++i]});
    else if (c == '*') tokens.push_back({Kind::run});
    else if (c == '?') tokens.push_back({Kind::one});
    else if (c == '#') tokens.push_back({Kind::digits});
    else tokens.push_back({Kind::byte, c});
  }
  return tokens;
}

bool continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }
bool boundary(std::string_view s, std::size_t i) { return i >= s.size() || !continuation(s[i]); }
bool digit(char c) { return c >= '0' && c <= '9'; }
// Bytes of the character starting at s[i].
std::size_t char_len(std::string_view s, std::size_t i) {
  std::size_t j = i + 1;
  while (j < s.size() && continuation(s[j])) ++j;
  return j - i;
}

// ends[k]: the pattern matches s[0, k). One pass per token over the reachable positions.
std::vector<char> match_ends(const std::vector<Token>& tokens, std::string_view s) {
  const std::size_t n = s.size();
  std::vector<char> cur(n + 1, 0), next(n + 1);
  cur[0] = 1;
  for (const auto& t : tokens) {
    std::fill(next.begin(), next.end(), 0);
    switch (t.kind) {
      case Kind::byte:
        for (std::size_t i = 0; i < n; ++i) next[i + 1] = cur[i] && s[i] == t.byte;
        break;
      case Kind::one:
        for (std::size_t i = 0; i < n; ++i)
          if (cur[i] && boundary(s, i)) next[i + char_len(s, i)] = 1;
        break;
      case Kind::digits: {
        bool run = false;
        for (std::size_t j = 1; j <= n; ++j) next[j] = run = (run || cur[j - 1]) && digit(s[j - 1]);
        break;
      }
      case Kind::run: {
        bool any = false;
        for (std::size_t j = 0; j <= n; ++j) next[j] = (any = any || cur[j]) && boundary(s, j);
        break;
      }
    }
    cur.swap(next);
  }
  return cur;
}

// starts[i]: the pattern matches s[i, n). The same passes, backwards.
std::vector<char> match_starts(const std::vector<Token>& tokens, std::string_view s) {
  const std::size_t n = s.size();
  std::vector<char> cur(n + 1, 0), prev(n + 1);
  cur[n] = 1;
  for (auto t = tokens.rbegin(); t != tokens.rend(); ++t) {
    std::fill(prev.begin(), prev.end(), 0);
    switch (t->kind) {
      case Kind::byte:
        for (std::size_t i = 0; i < n; ++i) prev[i] = s[i] == t->byte && cur[i + 1];
        break;
      case Kind::one:
        for (std::size_t i = 0; i < n; ++i) prev[i] = boundary(s, i) && cur[i + char_len(s, i)];
        break;
      case Kind::digits:
        for (std::size_t i = n; i-- > 0;) prev[i] = digit(s[i]) && (cur[i + 1] || prev[i + 1]);
        break;
      case Kind::run: {
        bool any = false;
        for (std::size_t i = n + 1; i-- > 0;) prev[i] = (any = any || (cur[i] && boundary(s, i))) && boundary(s, i);
        break;
      }
    }
    cur.swap(prev);
  }
  return cur;
}

}  // namespace

std::string pattern_error(std::string_view pattern) {
  if (!is_valid_utf8(pattern)) return "not valid UTF-8";
  std::size_t backslashes = 0;
  for (auto it = pattern.rbegin(); it != pattern.rend() && *it == '\\'; ++it) ++backslashes;
  if (backslashes % 2 == 1) return "ends in a lone '\\' (write '\\\\' for a backslash)";
  if (pattern_matches(pattern, "")) return "matches the empty text (a pattern needs a character, '?' or '#')";
  return "";
}

bool pattern_matches(std::string_view pattern, std::string_view text) {
  return match_ends(tokenize(pattern), text)[text.size()] != 0;
}

std::size_t shortest_prefix_match(std::string_view pattern, std::string_view text) {
  auto ends = match_ends(tokenize(pattern), text);
  for (std::size_t k = 1; k <= text.size(); ++k)
    if (ends[k] && boundary(text, k)) return k;
  return 0;
}

std::size_t shortest_suffix_match(std::string_view pattern, std::string_view text) {
  auto starts = match_starts(tokenize(pattern), text);
  for (std::size_t i = text.size(); i-- > 0;)
    if (starts[i] && boundary(text, i)) return text.size() - i;
  return 0;
}

}  // namespace tourmap::load
