#pragma once
// UTF-8 code points and the simple (one-to-one) case mapping of the scripts station names use:
// Latin (ASCII, Latin-1, Latin Extended-A, Romanian comma letters), Greek and Cyrillic. Other
// characters have no case here. Enough to title-case names like "SÃO SEBASTIÃO"; not a
// replacement for full Unicode case folding (no "ß" -> "SS", no Greek final sigma).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tourmap::load {

// Decodes the code point at s[i] and advances i past it; nullopt on malformed UTF-8 (overlong
// forms and surrogates included), with i unchanged.
std::optional<std::uint32_t> decode_utf8(std::string_view s, std::size_t& i);
void append_utf8(std::string& out, std::uint32_t cp);

bool is_upper(std::uint32_t cp);
bool is_lower(std::uint32_t cp);
std::uint32_t to_lower(std::uint32_t cp);
std::uint32_t to_upper(std::uint32_t cp);

// The whole string in lower case (malformed UTF-8 is returned unchanged).
std::string lower_utf8(std::string_view s);

}  // namespace tourmap::load
