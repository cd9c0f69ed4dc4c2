#pragma once
// A drawing painted with cairo into memory: PNG (an RGB image) and PDF (vector, the names as
// real text in an embedded subset of the labels' font). The drawing's px are stretched to the
// requested size, so a page laid out in CSS px (1/96 in) prints at any resolution. Text is
// drawn with cairo's own font selection (fontconfig): the labels' family, bold; each line is
// stretched to the width the layout measured it with, so a substituted font takes the same room.

#include "export/drawing.hpp"

#include <string>

namespace tourmap::map_export {

// Throws std::runtime_error when cairo fails (e.g. out of memory for the image).
std::string render_png(const Drawing& drawing, int width_px, int height_px);
std::string render_pdf(const Drawing& drawing, double width_pt, double height_pt);

}  // namespace tourmap::map_export
