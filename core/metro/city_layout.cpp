#include "metro/city_layout.hpp"

#include "metro/bend_reduction.hpp"
#include "metro/prelayout.hpp"
#include "metro/station_spacing.hpp"
#include "util/elapsed.hpp"
#include "util/thread_cpu_clock.hpp"

#include <algorithm>
#include <future>
#include <tuple>
#include <utility>
#include <optional>

namespace tourmap::metro {
namespace {

using util::Clock;
using util::ms_since;

// Names left out where symbols are 12 px across (from the first zoom with names round the
// ring), at that zoom and the larger ones.
std::size_t unnamed_from(const std::vector<LabelScale>& scales, std::size_t first) {
  std::size_t n = 0;
  for (std::size_t k = first; k < scales.size(); ++k) n += scales[k].unlabelled;
  return n;
}

// Room for the names left out where symbols are 12 px across (issue 14): rounds of the spacing
// program that also keep the place each such name wants clear of lines and symbols
// (metro/station_spacing.hpp, make_room_for_labels), in the usual type and then in the smaller
// one. Each round tries the points within 5, 10 and 20 mean edges of a wanted name moving of
// their own (the rest moves only with the whole map): which one wins depends on the network and
// the round (London: 10 -> 1 unnamed at 75 px in 3-4 rounds, uniform lengths 10 -> 0). Then
// each name still left out, alone, in each of its six places that need the least room (it
// named the last one of an earlier version of London uniform; London's last one now loses
// others each time). A try is kept if it names the most stations at those zooms, more than
// before, and keeps
// the layout's guarantees against the layout before any room was made: octilinear, no added
// crossing or order violation more, the smallest gap at least min(it, 0.5) mean edges, at most
// 1.2 times its displacement (the MIP's guards, metro/mip_polish.hpp, but a name is worth
// more displacement than a bend: with 1.1, London's rounds stopped at 10 of 302 unnamed). The
// names placed in one round keep their places in the next where still free (their boxes are
// kept clear of the lines and symbols that move), so a round that names a few more does not
// lose as many elsewhere. Within `budget_ms` of this thread's CPU time (a try in progress
// finishes).
constexpr double kRoomKeepDisplacement = 1.2;
void make_room_for_names(const LayoutGraph& g, Layout& layout, const StationLabelInput& names, double budget_ms,
                         CityLayoutResult& out) {
  const LabelStyle style;
  std::size_t first = 0;
  while (first < kLabelMeanEdgesPx.size() && kLabelMeanEdgesPx[first] < style.ring_min_mean_edge_px) ++first;
  auto& report = out.solver.label_room;
  if (first >= out.labels.size()) return;
  report.unnamed_before = report.unnamed_after = out.labels[first].unlabelled;
  report.status = "not_needed";
  if (out.labels[first].wanted.empty()) return;
  const auto cpu_started = util::ThreadCpuClock::now();
  const auto used_ms = [&] {
    return std::chrono::duration<double, std::milli>(util::ThreadCpuClock::now() - cpu_started).count();
  };
  const LayoutQuality base = out.quality;
  const auto sound = [&](const LayoutQuality& q) {
    return q.octilinear_share >= 1 - 1e-9 && q.added_crossings <= base.added_crossings &&
           q.order_violations <= base.order_violations &&
           q.min_station_gap_ratio >= std::min(base.min_station_gap_ratio, kMipKeepGap) - 1e-3 &&
           q.mean_displacement <= base.mean_displacement * kRoomKeepDisplacement + 1e-3;
  };
  constexpr int kMaxRounds = 12;
  constexpr double kMoveRadii[] = {5.0, 10.0, 20.0};
  struct Try {
    Layout layout;
    LayoutQuality quality;
    std::vector<LabelScale> labels;
    std::size_t unnamed;
  };
  // The layout with room made for `rooms` (the placed names kept clear), points within
  // `radius` mean edges of them moving, and its names placed keeping `before`'s places; none
  // when the program finds none or the layout breaks a guarantee.
  const auto try_rooms = [&](const std::vector<PlacedLabel>& wanted, const std::vector<LabelScale>& before,
                             double radius, bool keep_placed) -> std::optional<Try> {
    const auto& scale = out.labels[first];
    std::vector<LabelRoom> rooms, placed;
    for (const auto& l : wanted) rooms.push_back({l.node, l.x0, l.y0, l.x1, l.y1});
    for (const auto& l : scale.labels) placed.push_back({l.node, l.x0, l.y0, l.x1, l.y1});
    LabelRoomParams room;
    room.scale_px = scale.mean_edge_px;
    room.symbol_px = scale.symbol_px;
    room.line_spacing_px = style.line_spacing_px;
    room.clearance_px = style.clearance_px;
    room.label_gap_px = style.label_gap_px;
    room.move_radius = radius;
    room.keep_placed = keep_placed;
    SpacingParams spacing;
    spacing.time_limit_ms = budget_ms - used_ms();
    auto candidate = make_room_for_labels(g, layout, rooms, placed, room, spacing);
    if (!candidate) return std::nullopt;
    auto quality = measure_layout(g, *candidate);
    if (!sound(quality)) return std::nullopt;
    auto labels = place_station_labels(g, *candidate, names, kLabelMeanEdgesPx, LabelStyle{}, &before);
    const auto unnamed = unnamed_from(labels, first);
    return Try{std::move(*candidate), quality, std::move(labels), unnamed};
  };
  const auto keep = [&](Try& t) {
    layout = std::move(t.layout);
    out.labels = std::move(t.labels);
    out.quality = t.quality;
    ++report.kept;
    report.unnamed_after = out.labels[first].unlabelled;
  };
  for (const auto& l : out.labels[first].wanted) report.rooms += l.font_px >= style.font_px;
  report.status = "no_gain";
  // Rounds: room for every name left out at once.
  while (report.rounds < kMaxRounds && !out.labels[first].wanted.empty() && report.status != "no_time") {
    ++report.rounds;
    std::optional<Try> best;
    // Room for the names in the usual type, then in the smaller one (less room, and the only
    // way for some); each with every move radius.
    for (const bool small : {false, true}) {
      auto before = out.labels;  // the placement to keep, wanting only the places of this type
      auto& wanted = before[first].wanted;
      std::erase_if(wanted, [&](const PlacedLabel& l) { return (l.font_px < style.font_px) != small; });
      if (wanted.empty()) continue;
      for (const double radius : kMoveRadii) {
        if (used_ms() >= budget_ms) {
          report.status = "no_time";
          break;
        }
        auto t = try_rooms(wanted, before, radius, true);
        if (t && t->unnamed < (best ? best->unnamed : unnamed_from(out.labels, first))) best = std::move(t);
      }
    }
    if (!best) break;
    keep(*best);
  }
  // Then one name at a time, each in the places that need the least room (the one the rounds
  // asked for may be blocked where another is not): points within 10 mean edges move, then
  // within 20, first with the names around it free to move, then with them kept clear (London:
  // Leicester Square's second place needed the wider reach with the names around it kept, 301
  // -> 302 of 302 named at 75 px, with and without POIs, with visual-worth and uniform lengths).
  std::vector<std::uint32_t> left;
  for (const auto& l : out.labels[first].wanted)
    if (std::find(left.begin(), left.end(), l.node) == left.end()) left.push_back(l.node);
  for (const auto v : left) {
    std::vector<PlacedLabel> places;
    for (const auto& l : out.labels[first].alternatives)
      if (l.node == v) places.push_back(l);
    constexpr std::pair<double, bool> kSingleTries[] = {{10.0, false}, {20.0, false}, {10.0, true}, {20.0, true}};
    for (const auto& place : places) {
      bool named = false;
      for (const auto& [radius, keep_placed] : kSingleTries) {
        if (used_ms() >= budget_ms) {
          report.status = "no_time";
          break;
        }
        ++report.single_tries;
        auto before = out.labels;
        before[first].wanted = {place};
        auto t = try_rooms({place}, before, radius, keep_placed);
        if (t && t->unnamed < unnamed_from(out.labels, first)) {
          keep(*t);
          named = true;
          break;
        }
      }
      if (named || report.status == "no_time") break;
    }
    if (report.status == "no_time") break;
  }
  if (report.kept > 0) report.status = "kept";  // a later try may have found no more
}

// The MIP's time budget in seconds (see the header for the policy); none: no MIP.
std::optional<double> mip_budget(const CityLayoutParams& p, std::size_t stations, double fast_ms) {
  bool want = p.mip && (p.solver == LayoutSolver::mip ||
                        (p.solver == LayoutSolver::automatic && stations <= kAutoMipStations));
  if (!want) return std::nullopt;
  double left_s = p.time_limit_s - fast_ms / 1000.0;
  double budget = p.solver == LayoutSolver::mip ? left_s : std::min(0.5, 0.1 * p.time_limit_s);
  return std::min(budget, left_s);
}

}  // namespace

CityLayoutResult layout_city(const CityMetroInput& in, const std::vector<model::Poi>& pois,
                             const CityLayoutParams& params) {
  auto started = Clock::now();
  CityLayoutResult out;

  // 1. Visual worth (5.4.1, eq. 5.1) at every node and POI: one batched evaluation.
  auto t = Clock::now();
  auto vw = make_visual_worth(in, pois, params.rank, params.worth, params.poi_weight);
  std::vector<XY> worth_points(in.graph.pos);
  worth_points.insert(worth_points.end(), in.poi_xy.begin(), in.poi_xy.end());
  auto worth = vw.at_points(worth_points);
  const auto nodes_end = worth.begin() + static_cast<std::ptrdiff_t>(in.graph.pos.size());
  out.node_worth.assign(worth.begin(), nodes_end);
  out.poi_worth.assign(nodes_end, worth.end());
  out.timing.visual_worth = ms_since(t);

  // 2. Octilinear layout (5.4.2) with edge lengths from visual worth (eq. 5.3, 5.4) or uniform.
  t = Clock::now();
  auto g = in.graph;
  g.min_length = params.worth_lengths ? visual_worth_lengths(g, out.node_worth, params.l_const)
                                      : std::vector<double>(g.edges.size(), params.l_const);
  auto stretched = g;  // the stress layout's targets (prelayout.hpp); the layout keeps g's minimums
  stretched.min_length = stress_lengths(g);
  auto start = stress_layout(stretched, scale_to_lengths(stretched));
  out.timing.prelayout = ms_since(t);
  GridRouteParams route;
  route.time_limit_ms = params.time_limit_s * 1000.0;
  auto stage = Clock::now();
  auto layout = route_octilinear(g, start, route, &out.route);
  out.timing.route = ms_since(stage);

  // Fewer bends along the lines (same stations and edges, same topology), before the fast
  // layout is measured and handed to the MIP as its start. Rounds, not time, end the search,
  // so that a request gets the same layout under any load and on any machine (with a CPU-time
  // budget Chicago came out at 17-20 bends and 3.42-3.63 % displacement from run to run):
  // 4 + 2 rounds under 200 stations (Chicago 70-80 ms: 20 bends, 3.54 %; 6 + 3 gave 18 bends
  // and 3.45 % but 125 ms, and Chicago's cold answer over 0.3 s), 10 + 5 above (London
  // 470-630 ms: 80 and 82 bends). The time limit is a backstop for a slow machine.
  BendReductionParams bends;
  const bool small = in.station_count < 200;  // the classes count stations, not nodes
  bends.max_rounds = small ? 4 : 10;
  bends.polish_max_rounds = small ? 2 : 5;
  bends.time_limit_ms = std::min(small ? 300.0 : 1500.0, 0.25 * params.time_limit_s * 1000.0);
  stage = Clock::now();
  reduce_bends(g, layout, bends, &out.bends);
  out.timing.bends = ms_since(stage);
  // Room around the stations (issue 13), the directions kept: London takes 1-2 rounds of
  // 150-300 ms, smaller networks 0-1 round of 3-30 ms. A round starts only within the budget.
  SpacingParams spacing;
  spacing.time_limit_ms = std::min(small ? 100.0 : 900.0, 0.15 * params.time_limit_s * 1000.0);
  stage = Clock::now();
  out.spacing = space_stations(g, layout, spacing);
  out.timing.spacing = ms_since(stage);

  stage = Clock::now();
  out.quality = measure_layout(g, layout);
  out.timing.measure = ms_since(stage);
  out.timing.fast = ms_since(t);
  out.solver.status = layout.status;

  // Optional MIP polish (see the header for the policy).
  auto budget = mip_budget(params, in.station_count, out.timing.fast);
  if (budget && *budget < 0.2) {
    MipReport skipped;
    skipped.status = "skipped";
    skipped.reason = "no time left";
    out.solver.mip = std::move(skipped);
  } else if (budget) {
    out.solver.mip = polish_with_mip(g, layout, out.quality, params.l_const, *budget, params.mip);
    if (out.solver.mip->accepted) {
      out.solver.kind = "mip";
      out.solver.status = layout.status;
      out.solver.gap = out.solver.mip->gap;
    }
  }
  // The lines' order along shared track, on the final drawing, beside the station names (they
  // need only how many lines each edge carries): the two take a core each. The order's model is
  // small (a column per pair of lines sharing an edge: 1-465 on the shared networks, capped at
  // 20,000) and solved in this process within CBC's own time limit: a child process (as the
  // layout MIP gets in the server) cost 15-30 ms more than the whole solve.
  auto ordering = std::async(std::launch::async, [&g, &layout] {
    const auto started = Clock::now();
    const MipSolveFn in_process = [](const MipModel& m, double limit, double gap) { return solve_with_cbc(m, limit, gap); };
    auto order = order_lines(g, layout, in_process);
    return std::pair{std::move(order), ms_since(started)};
  });
  // Station names per zoom: interchanges and termini first, then by visual worth.
  auto stage2 = Clock::now();
  StationLabelInput names;
  names.names = in.names;
  names.priority = out.node_worth;
  for (const auto& lines : g.edge_lines) {
    auto distinct = lines;
    std::sort(distinct.begin(), distinct.end());
    names.lines.push_back(static_cast<std::size_t>(std::unique(distinct.begin(), distinct.end()) - distinct.begin()));
  }
  out.labels = place_station_labels(g, layout, names, kLabelMeanEdgesPx);
  out.timing.labels = ms_since(stage2);
  // The order reads the layout: it is done before the layout makes room for names. The room
  // keeps every segment's direction, so the order (of lines along each edge, by the edges'
  // circular order at the stations) stays valid.
  std::tie(out.line_order, out.timing.line_order) = ordering.get();
  stage2 = Clock::now();
  if (params.label_room_ms > 0) make_room_for_names(g, layout, names, params.label_room_ms, out);
  out.timing.label_room = ms_since(stage2);
  out.compare = metro_compare_metrics(g, in.is_station, layout);
  out.timing.layout = ms_since(t);

  // 3. Into the geographic frame, and warping (5.4.3) of POIs, outline and mesh.
  t = Clock::now();
  out.frame = frame_city(g.pos, layout, in.poi_xy);
  out.timing.warp = ms_since(t);

  out.layout = std::move(layout);
  out.min_length = std::move(g.min_length);
  out.timing.total = ms_since(started);
  return out;
}

}  // namespace tourmap::metro
