#pragma once
// The width of a station name in the labels' font (DejaVu Sans Condensed Bold, which the client
// and the export both draw with): what the label placement measures boxes with.

#include <string_view>

namespace tourmap::metro {

inline constexpr const char* kLabelFontFamily = "DejaVu Sans Condensed";

// The advance width of UTF-8 text, in ems (times the font size in px gives px).
double label_text_em(std::string_view utf8);

}  // namespace tourmap::metro
