#include "load/utf8.hpp"

namespace tourmap::load {
namespace {

// Where the lower-case letter of an upper-case one is not cp + 0x20 or cp + 1: the pairs of
// Latin-1's odd ones and of Greek accented capitals.
struct CasePair {
  std::uint32_t upper, lower;
};
constexpr CasePair kSpecialPairs[] = {
    {0x0178, 0x00FF},  // Ÿ ÿ
    {0x0130, 0x0069},  // İ i (Turkish dotted capital I)
    {0x0386, 0x03AC}, {0x0388, 0x03AD}, {0x0389, 0x03AE}, {0x038A, 0x03AF},
    {0x038C, 0x03CC}, {0x038E, 0x03CD}, {0x038F, 0x03CE},
};

// Latin Extended-A alternates upper/lower in pairs; the parity of the upper-case member flips
// at U+0139 and back at U+014A, and U+0179..U+017E follow the U+0139 parity.
bool latin_ext_a_upper(std::uint32_t cp) {
  if (cp == 0x0138 || cp == 0x0149 || cp == 0x017F || cp == 0x0130 || cp == 0x0131 || cp == 0x0178) return false;
  if ((cp >= 0x0100 && cp <= 0x0137) || (cp >= 0x014A && cp <= 0x0177)) return cp % 2 == 0;
  if ((cp >= 0x0139 && cp <= 0x0148) || (cp >= 0x0179 && cp <= 0x017E)) return cp % 2 == 1;
  return false;
}

bool latin_ext_a_lower(std::uint32_t cp) {
  if (cp == 0x0138 || cp == 0x0149 || cp == 0x017F || cp == 0x0131) return true;
  if (cp == 0x0130 || cp == 0x0178) return false;
  if ((cp >= 0x0100 && cp <= 0x0137) || (cp >= 0x014A && cp <= 0x0177)) return cp % 2 == 1;
  if ((cp >= 0x0139 && cp <= 0x0148) || (cp >= 0x0179 && cp <= 0x017E)) return cp % 2 == 0;
  return false;
}

}  // namespace

std::optional<std::uint32_t> decode_utf8(std::string_view s, std::size_t& i) {
  if (i >= s.size()) return std::nullopt;
  auto b0 = static_cast<unsigned char>(s[i]);
  std::size_t len = b0 < 0x80 ? 1 : (b0 >> 5) == 0x6 ? 2 : (b0 >> 4) == 0xE ? 3 : (b0 >> 3) == 0x1E ? 4 : 0;
  if (len == 0 || i + len > s.size()) return std::nullopt;
  std::uint32_t cp = len == 1 ? b0 : len == 2 ? (b0 & 0x1F) : len == 3 ? (b0 & 0x0F) : (b0 & 0x07);
  for (std::size_t k = 1; k < len; ++k) {
    auto b = static_cast<unsigned char>(s[i + k]);
    if ((b >> 6) != 0x2) return std::nullopt;
    cp = (cp << 6) | (b & 0x3F);
  }
  // Reject overlong forms and surrogates.
  if ((len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && (cp < 0x10000 || cp > 0x10FFFF)) ||
      (cp >= 0xD800 && cp <= 0xDFFF))
    return std::nullopt;
  i += len;
  return cp;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out.push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out.push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out.push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out.push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

bool is_upper(std::uint32_t cp) {
  if (cp >= 'A' && cp <= 'Z') return true;
  if (cp >= 0x00C0 && cp <= 0x00DE) return cp != 0x00D7;  // × is not a letter
  for (const auto& p : kSpecialPairs)
    if (p.upper == cp) return true;
  if (cp >= 0x0100 && cp <= 0x017F) return latin_ext_a_upper(cp);
  if (cp >= 0x0218 && cp <= 0x021B) return cp % 2 == 0;   // Ș Ț
  if (cp >= 0x0391 && cp <= 0x03A9) return cp != 0x03A2;  // Greek capitals
  if (cp >= 0x0400 && cp <= 0x042F) return true;          // Cyrillic capitals
  return false;
}

bool is_lower(std::uint32_t cp) {
  if (cp >= 'a' && cp <= 'z') return true;
  if (cp >= 0x00DF && cp <= 0x00FF) return cp != 0x00F7;  // ÷ is not a letter; ß has no capital here
  for (const auto& p : kSpecialPairs)
    if (p.lower == cp && cp >= 0x80) return true;
  if (cp >= 0x0100 && cp <= 0x017F) return latin_ext_a_lower(cp);
  if (cp >= 0x0218 && cp <= 0x021B) return cp % 2 == 1;
  if (cp >= 0x03B1 && cp <= 0x03C9) return true;  // with final sigma U+03C2
  if (cp >= 0x0430 && cp <= 0x045F) return true;
  return false;
}

std::uint32_t to_lower(std::uint32_t cp) {
  if (!is_upper(cp)) return cp;
  for (const auto& p : kSpecialPairs)
    if (p.upper == cp) return p.lower;
  if (cp < 0x80 || (cp >= 0x00C0 && cp <= 0x00DE) || (cp >= 0x0391 && cp <= 0x03A9) || (cp >= 0x0410 && cp <= 0x042F))
    return cp + 0x20;
  if (cp >= 0x0400 && cp <= 0x040F) return cp + 0x50;
  return cp + 1;  // Latin Extended-A and Ș Ț: the lower-case letter follows its capital
}

std::uint32_t to_upper(std::uint32_t cp) {
  if (!is_lower(cp)) return cp;
  for (const auto& p : kSpecialPairs)
    if (p.lower == cp && cp >= 0x80) return p.upper;
  if (cp == 0x00DF || cp == 0x0138 || cp == 0x0149 || cp == 0x017F || cp == 0x0131) return cp;  // no simple capital
  if (cp == 0x03C2) return 0x03A3;  // ς -> Σ
  if (cp < 0x80 || (cp >= 0x00E0 && cp <= 0x00FE) || (cp >= 0x03B1 && cp <= 0x03C9) || (cp >= 0x0430 && cp <= 0x044F))
    return cp - 0x20;
  if (cp >= 0x0450 && cp <= 0x045F) return cp - 0x50;
  return cp - 1;
}

std::string lower_utf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    auto cp = decode_utf8(s, i);
    if (!cp) return std::string(s);
    append_utf8(out, to_lower(*cp));
  }
  return out;
}

}  // namespace tourmap::load
