#pragma once
// The geography stretched to the layout's edge lengths: node positions in layout units that
// keep every edge's geographic direction while giving it its target length (eq. 5.4), in the
// least-squares sense, with a weak pull to the scaled geography so the map keeps its shape:
//
//   min  sum_edges |P_v - P_u - l_uv * dir_uv|^2  +  lambda * sum_nodes |P_v - s * g_v|^2
//
// s maps the mean geographic edge length to the mean target length. The octilinear layouts
// start from these positions.

#include "metro/layout_graph.hpp"

namespace tourmap::metro {

std::vector<XY> stretch_to_lengths(const LayoutGraph& g, double lambda = 0.05);

// The geography scaled so that the mean edge gets the mean target length: the same topology
// (crossings, circular orders) as the geography.
std::vector<XY> scale_to_lengths(const LayoutGraph& g);

// The lengths the stress layout aims at: an edge's minimum length, or `geo_share` of its
// geographic length (at the scale that gives the mean edge the mean minimum length) where that
// is longer. Long edges keep most of their geographic length, so the periphery is not pulled in
// towards the centre and stations stay near their geography, while short central edges still
// get their minimum, so a dense centre spreads. (With the minimum lengths alone, station
// displacement was 3.7 % on Chicago and 2.7 % on London with uniform lengths; with these
// 3.1 % and 2.3 %, and fewer bends. geo_share 0.6-0.8 all do about as well: 0.7 is in the
// middle, not a value that suits one network.)
std::vector<double> stress_lengths(const LayoutGraph& g, double geo_share = 0.7);

struct StressOptions {
  int iterations = 60;
  double anchor = 0.05;        // pull towards `init`, relative to the stress weights
  bool keep_topology = true;   // moves that change crossings or circular orders are shortened
                               // (halved twice) or dropped (metro/topology_guard.hpp)
};

// Stress majorization (SMACOF, Gansner/Koren/North 2004) from `init`: distances between all
// connected node pairs approach their graph distances over the target lengths, so a dense
// centre spreads out as much as its edge lengths ask, with a pull of `anchor` towards `init`
// to keep the geography's orientation. Pairs in different components are left out. With
// keep_topology, `init`'s topology is kept: start from scale_to_lengths to keep the geography's.
std::vector<XY> stress_layout(const LayoutGraph& g, const std::vector<XY>& init, const StressOptions& options = {});

}  // namespace tourmap::metro
