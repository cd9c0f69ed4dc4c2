#pragma once
// The optional MIP polish of a fast-path layout (paper 5.4.2): the octilinear MIP started from
// the layout (with a place term that holds stations near it), solved under a time limit, given
// room by the spacing program, and kept only when it has fewer bends and is no worse by the
// quality report (octilinearity, crossings, circular order, gaps, shortest edge, displacement).

#include "metro/layout_graph.hpp"
#include "metro/layout_quality.hpp"
#include "metro/mip_model.hpp"

#include <string>

namespace tourmap::metro {

// The MIP's place term (octilinear_mip.hpp): per l_const a station moves from the fast layout,
// in bends. At 0.5-2 Freiburg's optimum still moved its stations 0.7 mean edges from the
// geography (the fast layout: 0.47), as the topology term's 50 per segment outweighs it; at 8
// the MIP keeps Chicago's displacement and removes 5 of its 20 bends.
inline constexpr double kMipPlaceWeight = 8.0;
// A MIP layout is kept only with fewer bends and, against the fast layout: a smallest gap of
// at least min(the fast one's, kMipKeepGap) mean edges, a shortest edge of at least min(the
// fast one's, kMipKeepShortestEdge), stations at most kMipKeepDisplacement times as far from
// the geography, and no new crossing or order violation.
inline constexpr double kMipKeepGap = 0.5, kMipKeepShortestEdge = 0.4, kMipKeepDisplacement = 1.1;

// Larger models are not solved: CBC's root LP alone outlasts any time limit.
inline constexpr std::size_t kMaxMipColumns = 40000;

struct MipReport {
  std::string status;  // the solver's ("optimal", "time_limit", "killed", ...) or "skipped"
  std::string reason;  // why skipped or not accepted; empty otherwise
  bool built = false;  // the model was built and handed to the solver (the fields below are set)
  std::size_t columns = 0, rows = 0;
  double start_objective = 0;  // the fast layout's value of the objective
  double build_ms = 0, time_ms = 0;  // time_ms: building and solving
  bool solved = false;  // the solver returned a solution (objective, gap and accepted are set)
  double objective = 0, gap = 0;
  bool accepted = false;
};

// Polishes `layout` (whose report is `quality`) for `budget_s` seconds; replaces both when the
// result is accepted (the layout's status becomes the solver's).
MipReport polish_with_mip(const LayoutGraph& g, Layout& layout, LayoutQuality& quality, double l_const,
                          double budget_s, const MipSolveFn& solve);

}  // namespace tourmap::metro
