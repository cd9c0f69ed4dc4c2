#pragma once
// The order of the lines along each edge of a drawn metro network, so that lines sharing track
// cross each other as seldom as possible: the metro-line crossing minimisation problem (MLCM;
// Bekos et al. 2007, Argyriou et al. JGAA 2010; solved exactly by an ILP after reductions in
// Bast, Brosi, Storandt, SIGSPATIAL 2018, which is the model here).
//
// An edge's order runs left to right as seen travelling from edges[e].first to .second. Two
// lines a and b cross at a node v where
//   - both run through v on the same two edges and swap sides there, or
//   - they share the edge s into v and part there, and the one on the left of s (travelling
//     into v) leaves by the edge further right than the other's.
// (Two lines that only meet at v, on no common edge, cross there or not by the geometry alone:
// no order changes that, so they are not counted.)
//
// Exact model: a binary y(e, a, b) per edge and pair of its lines (a left of b), transitivity
// on every triple of an edge, a crossing indicator per pair running through a node on the same
// two edges, and the parting pairs as linear costs; minimise the crossings. Solved by the
// caller's MIP function (CBC) with a time limit, from a heuristic start: each pair's order on
// an edge voted by where the pair parts, followed along the track they share in both
// directions. Lines that run together on consecutive edges but are not neighbours on one of
// them are a separation (reported, not minimised).

#include "metro/layout_graph.hpp"
#include "metro/mip_model.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::metro {

struct LineOrderParams {
  double time_limit_s = 0.5;  // for the exact model (the heuristic start stays when it runs out)
  std::size_t max_pairs = 20000;  // pair variables beyond which the model is not built (heuristic only)
};

struct LineOrderReport {
  std::string method;            // "none" (no shared track), "exact", "best_found" (time limit), "heuristic"
  std::size_t crossings = 0;     // of the order returned
  std::size_t separations = 0;
  std::size_t heuristic_crossings = 0;  // of the heuristic start
  double lower_bound = 0;        // crossings no order can go below (the MIP's bound; 0 unknown)
  std::size_t pairs = 0;         // pair variables of the model
  double time_ms = 0;
};

struct LineOrder {
  std::vector<std::vector<std::uint32_t>> order;  // per edge: g.edge_lines[e] left to right
  LineOrderReport report;
};

// `layout`: the drawing (the direction each edge leaves a node gives the node's circular order).
// `mip`: how the exact model is solved (may be empty: heuristic only).
LineOrder order_lines(const LayoutGraph& g, const Layout& layout, const MipSolveFn& mip, const LineOrderParams& params = {});

// The crossings and separations of `order` (per edge, left to right) on `layout`.
struct LineCrossings {
  std::size_t crossings = 0, separations = 0;
};
LineCrossings count_line_crossings(const LayoutGraph& g, const Layout& layout,
                                   const std::vector<std::vector<std::uint32_t>>& order);

}  // namespace tourmap::metro
