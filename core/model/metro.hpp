#pragma once
// A metro network as a line graph: nodes (stations, or track junctions without a station),
// edges between nodes carrying one or more lines, each edge with its track polyline.

#include "geo/lonlat.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::model {

// How a line's stroke is drawn beyond its colour, so lines of nearly the same colour on one map
// can be told apart (metro/line_styles.hpp assigns it at import). Default: a plain stroke.
struct LineStyle {
  bool casing = false;       // outlined: a thin contrasting border on both sides of the stroke
  std::vector<double> dash;  // on/off lengths in stroke widths, e.g. {2, 1}; empty: solid
  bool plain() const { return !casing && dash.empty(); }
  bool operator==(const LineStyle&) const = default;
};

struct MetroLine {
  std::string id;     // unique within the network
  std::string label;  // what riders read, e.g. "U2"
  std::string color;  // "rrggbb" without '#', empty when unknown
  LineStyle style{};
};

struct MetroNode {
  std::string id;          // unique within the network
  std::string station_id;  // empty for a junction that is not a station
  std::string name;
  geo::LonLat pos;
  bool is_station() const { return !station_id.empty(); }
};

struct MetroEdge {
  std::uint32_t from = 0;               // index into MetroNetwork::nodes
  std::uint32_t to = 0;                 // index into MetroNetwork::nodes
  std::vector<std::uint32_t> lines;     // indices into MetroNetwork::lines
  std::vector<geo::LonLat> geometry;    // track polyline from `from` to `to` (>= 2 points)
};

struct MetroNetwork {
  std::vector<MetroNode> nodes;
  std::vector<MetroEdge> edges;
  std::vector<MetroLine> lines;

  std::size_t station_count() const {
    std::size_t n = 0;
    for (const auto& node : nodes) n += node.is_station() ? 1 : 0;
    return n;
  }
};

geo::BBox bbox_of(const MetroNetwork& net);

}  // namespace tourmap::model
