#pragma once
// Networks the layout has never seen, made from the shared ones (metro_bench --variants): the
// layout must hold on networks it was not tuned to, including flawed input (issue 13). Each
// variant is deterministic (a fixed seed per network), so a run can be repeated.
//   - jitter: every node moved by up to a quarter of the median edge, in a random direction;
//   - minus-line: the line with the most edges taken out (nodes left without an edge go too);
//   - flawed: a second station at the very point of an existing one (joined to a new terminus
//     1 km away) and an edge straight across the city between the two termini farthest apart,
//     on a line of its own.

#include "model/metro.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace tourmap::bench {

inline geo::LonLat moved(geo::LonLat p, double azimuth_deg, double metres) {
  double lat = 0, lon = 0;
  GeographicLib::Geodesic::WGS84().Direct(p.lat, p.lon, azimuth_deg, metres, lat, lon);
  return {lon, lat};
}

inline double metres(geo::LonLat a, geo::LonLat b) {
  double s = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat, a.lon, b.lat, b.lon, s);
  return s;
}

// Edges drawn straight between their (new) end points.
inline void straighten(model::MetroNetwork& net) {
  for (auto& e : net.edges) e.geometry = {net.nodes[e.from].pos, net.nodes[e.to].pos};
}

inline model::MetroNetwork jittered(model::MetroNetwork net, std::uint32_t seed) {
  std::vector<double> lengths;
  for (const auto& e : net.edges) lengths.push_back(metres(net.nodes[e.from].pos, net.nodes[e.to].pos));
  if (lengths.empty()) return net;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  const double reach = 0.25 * lengths[lengths.size() / 2];
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(0, 360), share(0, 1);
  for (auto& n : net.nodes) n.pos = moved(n.pos, angle(rng), reach * share(rng));
  straighten(net);
  return net;
}

// Without the line that has the most edges; nodes left without an edge are dropped.
inline model::MetroNetwork minus_line(const model::MetroNetwork& net) {
  std::vector<std::size_t> count(net.lines.size(), 0);
  for (const auto& e : net.edges)
    for (auto l : e.lines) ++count[l];
  const auto gone = static_cast<std::uint32_t>(std::max_element(count.begin(), count.end()) - count.begin());
  model::MetroNetwork out;
  out.lines = net.lines;
  std::vector<std::int64_t> index(net.nodes.size(), -1);
  const auto keep = [&](std::uint32_t v) {
    if (index[v] < 0) {
      index[v] = static_cast<std::int64_t>(out.nodes.size());
      out.nodes.push_back(net.nodes[v]);
    }
    return static_cast<std::uint32_t>(index[v]);
  };
  for (const auto& e : net.edges) {
    model::MetroEdge f = e;
    f.lines.erase(std::remove(f.lines.begin(), f.lines.end(), gone), f.lines.end());
    if (f.lines.empty()) continue;
    f.from = keep(e.from);
    f.to = keep(e.to);
    out.edges.push_back(std::move(f));
  }
  return out;
}

inline model::MetroNetwork flawed(model::MetroNetwork net) {
  std::vector<std::size_t> degree(net.nodes.size(), 0);
  for (const auto& e : net.edges) ++degree[e.from], ++degree[e.to];
  std::vector<std::uint32_t> termini;
  for (std::uint32_t v = 0; v < net.nodes.size(); ++v)
    if (degree[v] == 1 && net.nodes[v].is_station()) termini.push_back(v);
  const auto line = static_cast<std::uint32_t>(net.lines.size());
  net.lines.push_back({"variant-flaw", "X", "777777"});
  // Two stations at one point: a copy of a busy station's position, joined to a new terminus.
  const auto busiest = static_cast<std::uint32_t>(std::max_element(degree.begin(), degree.end()) - degree.begin());
  const auto twin = static_cast<std::uint32_t>(net.nodes.size());
  net.nodes.push_back({"variant-twin", "variant-twin", net.nodes[busiest].name + " (twin)", net.nodes[busiest].pos});
  const auto end = static_cast<std::uint32_t>(net.nodes.size());
  net.nodes.push_back({"variant-end", "variant-end", "Twin terminus", moved(net.nodes[busiest].pos, 45, 1000)});
  net.edges.push_back({twin, end, {line}, {net.nodes[twin].pos, net.nodes[end].pos}});
  // An edge straight across the city between the two termini farthest apart.
  if (termini.size() >= 2) {
    std::uint32_t a = termini[0], b = termini[1];
    double far = -1;
    for (std::size_t i = 0; i < termini.size(); ++i)
      for (std::size_t j = i + 1; j < termini.size(); ++j)
        if (double d = metres(net.nodes[termini[i]].pos, net.nodes[termini[j]].pos); d > far) {
          far = d;
          a = termini[i];
          b = termini[j];
        }
    net.edges.push_back({a, b, {line}, {net.nodes[a].pos, net.nodes[b].pos}});
  }
  return net;
}

struct Variant {
  std::string name;
  model::MetroNetwork net;
};

inline std::vector<Variant> variants_of(const model::MetroNetwork& net, std::uint32_t seed) {
  return {{"jitter", jittered(net, seed)}, {"minus-line", minus_line(net)}, {"flawed", flawed(net)}};
}

}  // namespace tourmap::bench
