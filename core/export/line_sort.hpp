#pragma once
// The legend's order of lines, as the client's sortLines (web/src/metro/lines.ts) sorts them:
// by label, numbers compared as numbers ("U2" before "U11"), case ignored.

#include "export/map_scene.hpp"

#include <cstddef>
#include <string_view>
#include <vector>

namespace tourmap::map_export {

// <0, 0, >0 as a sorts before, with or after b. Runs of ASCII digits compare by value, letters
// without case; other bytes (accented letters in UTF-8) by value. (The client's localeCompare
// with sensitivity "base" also folds accents: labels of metro lines rarely have any.)
int compare_labels(std::string_view a, std::string_view b);

// Indices of `lines` in legend order (stable for equal labels).
std::vector<std::size_t> legend_order(const std::vector<SceneLine>& lines);

}  // namespace tourmap::map_export
