#pragma once
// Context layers of a map: what is drawn under and around the roads of a deformed map so that
// the reader recognises the place (sea and water, parks and woods, land use, buildings, rivers
// and railways, place names). Loaded from OSM by load/osm_context.hpp; plain data here.
//
// Rings are in lon/lat without the repeated closing point (as geo::Polygon), the outer ring
// counter-clockwise and holes clockwise (the orientation RFC 7946 asks of GeoJSON).

#include "geo/projection.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tourmap::model {

enum class ContextAreaKind : std::uint8_t {
  sea,          // from natural=coastline, closed along the extract's bounds
  water,        // lakes, reservoirs, river areas, docks
  park,         // parks and gardens
  forest,       // forests and woods
  farmland,     // farmland, meadows, orchards, vineyards
  grass,        // grass, village greens, recreation grounds, pitches
  residential,  // residential land use
  industrial,   // industrial, commercial and retail land use
  building,
};
inline constexpr std::size_t kContextAreaKinds = 9;

enum class ContextLineKind : std::uint8_t { river, stream, canal, railway };
inline constexpr std::size_t kContextLineKinds = 4;

enum class ContextPlaceKind : std::uint8_t { city, town, village, suburb, hamlet, neighbourhood, locality, island };
inline constexpr std::size_t kContextPlaceKinds = 8;

// Stable lowercase names (JSON, storage), in enum order.
inline constexpr std::array<std::string_view, kContextAreaKinds> kContextAreaKindNames = {
    "sea", "water", "park", "forest", "farmland", "grass", "residential", "industrial", "building"};
inline constexpr std::array<std::string_view, kContextLineKinds> kContextLineKindNames = {"river", "stream", "canal",
                                                                                          "railway"};
inline constexpr std::array<std::string_view, kContextPlaceKinds> kContextPlaceKindNames = {
    "city", "town", "village", "suburb", "hamlet", "neighbourhood", "locality", "island"};

inline std::string_view name_of(ContextAreaKind kind) { return kContextAreaKindNames[static_cast<std::size_t>(kind)]; }
inline std::string_view name_of(ContextLineKind kind) { return kContextLineKindNames[static_cast<std::size_t>(kind)]; }
inline std::string_view name_of(ContextPlaceKind kind) {
  return kContextPlaceKindNames[static_cast<std::size_t>(kind)];
}

// The kind called `name` (as name_of gives it), or nothing.
template <class Kind, std::size_t N>
std::optional<Kind> kind_named(const std::array<std::string_view, N>& names, std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Kind>(i);
  return std::nullopt;
}
inline std::optional<ContextAreaKind> area_kind_named(std::string_view name) {
  return kind_named<ContextAreaKind>(kContextAreaKindNames, name);
}
inline std::optional<ContextLineKind> line_kind_named(std::string_view name) {
  return kind_named<ContextLineKind>(kContextLineKindNames, name);
}
inline std::optional<ContextPlaceKind> place_kind_named(std::string_view name) {
  return kind_named<ContextPlaceKind>(kContextPlaceKindNames, name);
}

// One polygon: rings[0] is the outer ring, the rest are holes. A multipolygon with several
// outer rings is several ContextAreas.
struct ContextArea {
  ContextAreaKind kind = ContextAreaKind::water;
  std::vector<std::vector<geo::LonLat>> rings;  // each >= 3 points
};

struct ContextLine {
  ContextLineKind kind = ContextLineKind::river;
  std::string name;                 // OSM name=*, UTF-8 as in the data; may be empty
  bool tunnel = false;              // in a tunnel or culvert: a client may dash it or leave it out
  std::vector<geo::LonLat> points;  // >= 2
};

struct ContextPlace {
  ContextPlaceKind kind = ContextPlaceKind::village;
  std::string name;  // OSM name=*, UTF-8 as in the data; never empty
  geo::LonLat pos;
  // Lower is more important (label priority): 10 * the kind's rank (city 0, town 1, suburb 2,
  // village 3, island 4, neighbourhood 5, hamlet 6, locality 7) + a population step (0 for
  // >= 10^7 people, one more per factor 10 down to 7 for < 10; 8 without population=*).
  int rank = 0;
};

struct ContextLayers {
  std::vector<ContextArea> areas;  // sea first, then in the order of the file
  std::vector<ContextLine> lines;
  std::vector<ContextPlace> places;
};

}  // namespace tourmap::model
