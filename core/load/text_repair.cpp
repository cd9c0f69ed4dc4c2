#include "load/text_repair.hpp"

#include "load/utf8.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace tourmap::load {
namespace {

// Windows-1252 bytes 0x80..0x9F as Unicode code points (0 = undefined in cp1252).
constexpr std::array<std::uint32_t, 32> kCp1252High = {
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0,      0x017D, 0,      0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178};

// The cp1252 byte that decodes to `cp`, if any.
std::optional<unsigned char> cp1252_byte(std::uint32_t cp) {
  if (cp < 0x80 || (cp >= 0xA0 && cp <= 0xFF)) return static_cast<unsigned char>(cp);
  for (std::size_t k = 0; k < kCp1252High.size(); ++k)
    if (kCp1252High[k] == cp && cp != 0) return static_cast<unsigned char>(0x80 + k);
  // Bytes undefined in cp1252 (0x81, 0x8D, ...) are often passed through as C1 controls.
  if (cp >= 0x80 && cp <= 0x9F) return static_cast<unsigned char>(cp);
  return std::nullopt;
}

}  // namespace

bool is_valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();)
    if (!decode_utf8(s, i)) return false;
  return true;
}

std::string repair_mojibake(std::string_view s) {
  // Only text with the tell-tale lead characters (Ã, Â, â) is a candidate.
  if (s.find("\xC3") == std::string_view::npos && s.find("\xC2") == std::string_view::npos) return std::string(s);
  std::string bytes;
  bool any_high = false;
  for (std::size_t i = 0; i < s.size();) {
    auto cp = decode_utf8(s, i);
    if (!cp) return std::string(s);
    auto b = cp1252_byte(*cp);
    if (!b) return std::string(s);  // a character cp1252 cannot hold: not mojibake
    any_high |= *b >= 0x80;
    bytes.push_back(static_cast<char>(*b));
  }
  if (!any_high || !is_valid_utf8(bytes)) return std::string(s);
  return bytes;
}

}  // namespace tourmap::load
