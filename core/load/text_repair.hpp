#pragma once
// Repair of "mojibake": UTF-8 text that was once decoded as Windows-1252 and re-encoded, e.g.
// "Shakespeareâ€™s" -> "Shakespeare’s" (the London museums file has such names).

#include <string>
#include <string_view>

namespace tourmap::load {

bool is_valid_utf8(std::string_view s);

// Returns the repaired text when `s` is double-encoded UTF-8, else `s` unchanged.
std::string repair_mojibake(std::string_view s);

}  // namespace tourmap::load
