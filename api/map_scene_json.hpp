#pragma once
// The scene a map export draws (core/export/map_scene.hpp), read from a layout answer
// (GET .../layout's JSON, api/metro_layout.cpp): the very data the client draws from, whether
// the layout was just computed or read back from the cache, so the export shows what the
// Metro view shows.

#include "export/map_scene.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace tourmap::api {

// `title`: the city's name. Throws nlohmann::json::exception on a body of another shape.
map_export::MapScene scene_from_layout(const nlohmann::json& layout, const std::string& title);

// "rrggbb" (any case) as a colour; anything else: the client's grey for lines without one.
map_export::Rgb parse_line_color(const std::string& hex);

}  // namespace tourmap::api
