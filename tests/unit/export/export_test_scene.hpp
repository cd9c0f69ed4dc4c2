#pragma once
// A small network for the export tests: two lines sharing a trunk, an interchange, a junction
// end, names on one and two lines, and two label scales.

#include "export/map_scene.hpp"

namespace tourmap::map_export::testing {

// U1 (red) west-east along y = 0 from Alpha to Delta; U2 (blue) with it from Beta to Gamma,
// then north to Epsilon. Layout units; a mean edge of 100.
inline MapScene small_scene() {
  MapScene s;
  s.title = "Testville";
  s.lines = {{"u2", "U2", {0x00, 0x55, 0xaa}}, {"u1", "U1", {0xe2, 0x00, 0x1a}}};
  auto station = [&](double x, double y, const char* name, std::vector<std::uint32_t> lines) {
    s.nodes.push_back({{x, y}, true, name, std::move(lines)});
  };
  station(0, 0, "Alpha", {1});
  station(100, 0, "Beta & Sons", {0, 1});
  station(200, 0, "Gamma Platz", {0, 1});
  station(300, 0, "Delta", {1});
  station(200, 100, "Epsilon", {0});
  s.edges = {{0, 1, {{0, 0}, {100, 0}}, {1}},
             {1, 2, {{100, 0}, {200, 0}}, {0, 1}},
             {2, 3, {{200, 0}, {300, 0}}, {1}},
             {2, 4, {{200, 0}, {200, 100}}, {0}}};
  s.mean_edge = 100;
  SceneLabelScale small{0.2, {}};
  SceneLabelScale large{0.5, {}};
  for (std::uint32_t v = 0; v < 5; ++v) {
    const bool two = v == 2;
    const double h = two ? 27 : 14;
    large.labels.push_back({v, 6, -h / 2, 60, h / 2, 6, -h / 2 + 7 + 4.2, 's', two ? std::size_t{6} : 0});
  }
  small.labels.push_back({0, 6, -7, 40, 7, 6, 4.2, 's', 0});
  s.label_scales = {small, large};
  s.attribution = {"Network: Testville Transit (CC BY 4.0)", "Places: Wikidata (CC0)"};
  return s;
}

}  // namespace tourmap::map_export::testing
