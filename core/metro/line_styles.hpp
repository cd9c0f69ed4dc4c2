#pragma once
// Lines of one map whose colours are too close to tell apart get distinct stroke styles
// (a casing, a dash), assigned at import so every reader draws the same. "Too close" is a
// CIEDE2000 colour difference below a threshold.

#include "model/metro.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::metro {

// CIELAB under the D65 white point: L* 0..100, a* and b* about -128..128.
struct Lab {
  double L = 0, a = 0, b = 0;
};

// "rrggbb" (or "#rrggbb") sRGB -> CIELAB; nullopt when it is not such a colour.
std::optional<Lab> lab_from_hex(std::string_view hex);

// CIEDE2000 (Sharma, Wu, Dalal 2005) with kL = kC = kH = 1. About 1 is the smallest difference
// seen between large patches side by side; it weighs lightness, chroma and hue as the eye
// does, where the plain Lab distance (CIE76) overrates differences among saturated blues and
// greens.
double delta_e2000(const Lab& x, const Lab& y);

// Default threshold: lines whose colours differ by less than this are drawn with distinct
// styles. ~1 is just noticeable for large patches side by side; the thin strokes of a metro
// map, seen apart and compared with a legend, need about ten times that (the difference needed
// grows as marks get thinner: Szafir, "Modeling Color Difference for Visualization Design",
// 2018). On the sample data every pair below 10 is one a rider mistakes (identical colours in
// Berlin and Stuttgart, London's District and DLR 5.2, Sydney's T4 and T6 6.0, Stuttgart's U5
// and U12 9.0); the next pair up differs by 12.4.
inline constexpr double kMinColourDifference = 10.0;

// The styles given, in turn, to the second, third, ... line of a group of close colours
// (a group of more than six lines reuses them).
const std::vector<model::LineStyle>& distinct_styles();

// "plain", "casing", "dash 2-1", "casing+dash 1-1": for import summaries.
std::string describe_style(const model::LineStyle& style);

// One group of lines whose colours are close (linked by differences below the threshold),
// ordered as styled: the first keeps a plain stroke.
struct CloseGroup {
  std::vector<std::uint32_t> lines;  // indices into MetroNetwork::lines
};

// Lines without a valid colour (OSM routes and GTFS routes often have none) get one from a
// palette of distinct colours that read on a light map: each, in line order, the palette
// colour farthest (CIEDE2000) from every colour the map already has. Returns how many.
// Deterministic. Runs before assign_line_styles.
std::size_t assign_missing_colours(model::MetroNetwork& net);

// Lines lighter than this (CIELAB L*) vanish on the light map (Liechtenstein's white bus 40;
// yellows such as London's Circle line, L* 89, stay plain):
// they are drawn with a casing whatever their group.
inline constexpr double kMaxPlainLightness = 92.0;

// Resets every line's style, then styles the lines of each close group: the line on the most
// edges (then the first in the line list) stays plain, the others take distinct_styles() in
// the same order; lines lighter than kMaxPlainLightness get a casing too. Lines without a
// valid colour take no part. Deterministic: the same network
// gets the same styles. `min_difference` 0 leaves every line plain.
std::vector<CloseGroup> assign_line_styles(model::MetroNetwork& net, double min_difference = kMinColourDifference);

}  // namespace tourmap::metro
