#pragma once
// A drawing as SVG text, written here rather than by cairo's SVG surface: cairo (1.16, and
// later versions alike) emits every glyph as an outline (<symbol> paths placed by <use>), so the
// station names would not be text: not searchable, selectable, read out or restyled. Here every
// name is a <text> element in the labels' font (with fallbacks stretched to the width the
// layout measured, as the client does), each primitive carries its role as its class, and the
// result is the same picture the cairo backends paint from the same drawing.

#include "export/drawing.hpp"

#include <string>

namespace tourmap::map_export {

struct SvgSize {
  std::string width, height;  // the root's width and height attributes ("1600", "420mm")
};

// `size` empty: the drawing's px.
std::string write_svg(const Drawing& drawing, const SvgSize& size = {});

// Text for XML content and attribute values: & < > " escaped, characters XML 1.0 forbids
// (control characters other than tab, newline and carriage return) dropped.
std::string xml_escape(const std::string& text);

}  // namespace tourmap::map_export
