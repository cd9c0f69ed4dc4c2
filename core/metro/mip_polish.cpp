#include "metro/mip_polish.hpp"

#include "metro/octilinear_mip.hpp"
#include "util/elapsed.hpp"

namespace tourmap::metro {
namespace {

// Why a MIP layout with a lower objective is still refused.
std::string refusal(const LayoutQuality& q, const LayoutQuality& fast) {
  std::string why = "it would have ";
  why.append(std::to_string(q.crossings)).append(" crossings (").append(std::to_string(q.added_crossings));
  why.append(" added) and ").append(std::to_string(q.order_violations)).append(" order violations, the fast layout ");
  why.append(std::to_string(fast.crossings)).append(" (").append(std::to_string(fast.added_crossings)).append(") and ");
  why.append(std::to_string(fast.order_violations));
  if (q.bends > fast.bends)
    why.append("; ").append(std::to_string(q.bends)).append(" bends, the fast layout ").append(std::to_string(fast.bends));
  return why;
}

}  // namespace

MipReport polish_with_mip(const LayoutGraph& g, Layout& layout, LayoutQuality& quality, double l_const,
                          double budget_s, const MipSolveFn& solve) {
  MipReport report;
  auto started = util::Clock::now();
  // Weights 1 / 50 / 1 for bend / topo / length (paper 5.4.2).
  auto model = build_octilinear_mip(g, layout, {1.0, 50.0, 1.0, l_const});
  report.build_ms = util::ms_since(started);
  if (model.model.columns() > kMaxMipColumns) {
    report.status = "skipped";
    report.reason = "network too large for the MIP";
    return report;
  }
  auto r = solve(model.model, budget_s, 0.01);
  report.built = true;
  report.status = r.status;
  report.columns = model.model.columns();
  report.rows = model.model.rows.size();
  report.start_objective = model.start_objective;
  report.time_ms = util::ms_since(started);
  if (r.x.empty()) return report;

  auto polished = decode_octilinear_mip(model, r.x, g.pos.size());
  auto q = measure_layout(g, polished);
  report.solved = true;
  report.objective = r.objective;
  report.gap = r.gap;
  // Kept only when it lowers the objective and is no worse than the fast layout by the report:
  // the MIP constrains only nearby segment pairs (crossings), and its bend cost is per line,
  // not the report's bends.
  bool better = r.objective < model.start_objective - 1e-6;
  bool no_worse = q.octilinear_share >= quality.octilinear_share && q.crossings <= quality.crossings &&
                  q.added_crossings <= quality.added_crossings && q.order_violations <= quality.order_violations &&
                  q.bends <= quality.bends;
  if (better && no_worse) {
    polished.status = r.status;
    layout = std::move(polished);
    quality = q;
    report.accepted = true;
  } else {
    report.reason = better ? refusal(q, quality) : "no improvement on the start";
  }
  return report;
}

}  // namespace tourmap::metro
