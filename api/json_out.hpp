#pragma once
// Direct JSON text output for the large arrays of coordinates in road networks and deformation
// results: building an nlohmann::json tree of 100K numbers first cost more than the solve it
// reports (about 25 ms for Liechtenstein), so these writers append straight to the body. The
// cluster answers use them too: there the tree of small objects cost more than the query.

#include "geo/lonlat.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::api {

// A number with at most 7 decimals (1e-7 degrees is about 1 cm), trailing zeros trimmed;
// non-finite numbers become null.
void append_number(std::string& out, double value);
void append_integer(std::string& out, std::int64_t value);
// The shortest text that reads back as the same double, as nlohmann::json writes it (a whole
// number keeps ".0"); non-finite numbers become null.
void append_double(std::string& out, double value);
// A JSON string literal; invalid UTF-8 is replaced (U+FFFD), never emitted.
void append_string(std::string& out, std::string_view text);
// [lon,lat]
void append_position(std::string& out, geo::LonLat p);
// [lon,lat,lon,lat,...]
void append_flat_positions(std::string& out, const std::vector<geo::LonLat>& points);

}  // namespace tourmap::api
