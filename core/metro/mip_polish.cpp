#include "metro/mip_polish.hpp"

#include "metro/octilinear_mip.hpp"
#include "metro/station_spacing.hpp"
#include "util/elapsed.hpp"

#include <algorithm>
#include <cstdio>

namespace tourmap::metro {
namespace {

// Why a MIP layout with a lower objective is still refused; empty when it is kept. It is kept
// only when a user sees a better map: fewer bends, and no worse by the report otherwise. The
// MIP constrains only nearby segment pairs (crossings) and its bend cost is per line, not the
// report's bends; its place term is soft. Measured with 10 s on the shared networks before
// these guards: Sydney 16 -> 11 bends, but 2.6 -> 4.6 % displacement and the smallest gap
// 0.53 -> 0.41 of the mean edge; in the server's 0.5 s, Chicago's gap 0.53 -> 0.12 and
// Berlin's U55 8 km west.
std::string refusal(const LayoutQuality& q, const LayoutQuality& fast) {
  auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return std::string(buf);
  };
  std::string why;
  auto add = [&](const std::string& what) { why.append(why.empty() ? "it would have " : "; ").append(what); };
  if (q.bends >= fast.bends)
    add(std::to_string(q.bends) + " bends, the fast layout " + std::to_string(fast.bends));
  if (q.crossings > fast.crossings || q.added_crossings > fast.added_crossings)
    add(std::to_string(q.crossings) + " crossings (" + std::to_string(q.added_crossings) + " added), the fast layout " +
        std::to_string(fast.crossings) + " (" + std::to_string(fast.added_crossings) + ")");
  if (q.order_violations > fast.order_violations)
    add(std::to_string(q.order_violations) + " order violations, the fast layout " + std::to_string(fast.order_violations));
  if (q.octilinear_share < fast.octilinear_share) add("edges that are not octilinear");
  const double gap_floor = std::min(fast.min_station_gap_ratio, kMipKeepGap) - 1e-3;
  if (q.min_station_gap_ratio < gap_floor)
    add("a smallest gap of " + num(q.min_station_gap_ratio) + " mean edges, at least " + num(gap_floor) + " asked");
  const auto edge_ratio = [](const LayoutQuality& l) { return l.mean_edge > 0 ? l.min_edge / l.mean_edge : 0.0; };
  const double edge_floor = std::min(edge_ratio(fast), kMipKeepShortestEdge) - 1e-3;
  if (edge_ratio(q) < edge_floor)
    add("a shortest edge of " + num(edge_ratio(q)) + " mean edges, at least " + num(edge_floor) + " asked");
  const double place_cap = fast.mean_displacement * kMipKeepDisplacement + 1e-3;
  if (q.mean_displacement > place_cap)
    add("stations " + num(q.mean_displacement) + " mean edges from the geography, at most " + num(place_cap) + " asked");
  return why;
}

}  // namespace

MipReport polish_with_mip(const LayoutGraph& g, Layout& layout, LayoutQuality& quality, double l_const,
                          double budget_s, const MipSolveFn& solve) {
  MipReport report;
  auto started = util::Clock::now();
  // Weights 1 / 50 / 1 for bend / topo / length (paper 5.4.2), and a place term of our own.
  MipLayoutParams params{1.0, 50.0, 1.0, kMipPlaceWeight, l_const};
  auto model = build_octilinear_mip(g, layout, params);
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
  if (r.x.empty()) {
    report.time_ms = util::ms_since(started);
    return report;
  }

  auto polished = decode_octilinear_mip(model, r.x, g.pos.size());
  report.solved = true;
  report.objective = r.objective;
  report.gap = r.gap;
  if (r.objective >= model.start_objective - 1e-6) {
    report.reason = "no improvement on the start";
    report.time_ms = util::ms_since(started);
    return report;
  }
  // The MIP knows the spacing rule only for nearby segment pairs: the spacing program gives the
  // stations their room back, directions (so bends) kept, as on the fast path.
  SpacingParams spacing;
  spacing.time_limit_ms = 300.0;
  space_stations(g, polished, spacing);
  auto q = measure_layout(g, polished);
  report.time_ms = util::ms_since(started);
  auto why = refusal(q, quality);
  if (why.empty()) {
    polished.status = r.status;
    layout = std::move(polished);
    quality = q;
    report.accepted = true;
  } else {
    report.reason = std::move(why);
  }
  return report;
}

}  // namespace tourmap::metro
