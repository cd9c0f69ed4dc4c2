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

// Stress majorization (SMACOF, Gansner/Koren/North 2004) from `init`: distances between all
// connected node pairs approach their graph distances over the target lengths, so a dense
// centre spreads out as much as its edge lengths ask, with a pull of `anchor` towards `init`
// to keep the geography's orientation. Pairs in different components are left out.
std::vector<XY> stress_layout(const LayoutGraph& g, const std::vector<XY>& init, int iterations = 60,
                              double anchor = 0.05);

}  // namespace tourmap::metro
