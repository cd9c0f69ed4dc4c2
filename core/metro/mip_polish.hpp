#pragma once
// The optional MIP polish of a fast-path layout (paper 5.4.2): the octilinear MIP started from
// the layout, solved under a time limit, and kept only when it lowers the objective without
// making the layout worse by the quality report (octilinearity, crossings, added crossings,
// circular order, bends).

#include "metro/layout_graph.hpp"
#include "metro/layout_quality.hpp"
#include "metro/mip_model.hpp"

#include <string>

namespace tourmap::metro {

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
