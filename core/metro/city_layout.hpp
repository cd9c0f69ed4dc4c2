#pragma once
// A city's transit-centric tourist map (paper 5.4), as one computation on plain structs:
// visual worth (5.4.1) -> edge lengths (eq. 5.3, 5.4) -> stress pre-layout -> octilinear grid
// routing (5.4.2) -> bend reduction -> spacing -> optional MIP polish -> the lines' order along
// shared track -> frame, and POIs, mesh and outline warped into the
// layout (5.4.3), with the quality report. No JSON, no I/O: api/metro_layout.cpp writes the
// answer, bench/metro_bench.cpp measures it.

#include "metro/bend_reduction.hpp"
#include "metro/station_spacing.hpp"
#include "metro/city_frame.hpp"
#include "metro/city_input.hpp"
#include "metro/layout_metrics.hpp"
#include "metro/layout_quality.hpp"
#include "metro/line_order.hpp"
#include "metro/station_labels.hpp"
#include "metro/mip_polish.hpp"
#include "metro/octilinear_grid.hpp"

#include <optional>
#include <string>
#include <vector>

namespace tourmap::metro {

// Solvers: "fast" is the grid routing alone; "mip" polishes it with the octilinear MIP for the
// rest of the time limit; "automatic" routes, then polishes networks of up to
// kAutoMipStations stations for a tenth of the time limit, at most 0.5 s.
enum class LayoutSolver { automatic, fast, mip };  // the order is in stored layouts' cache keys
inline constexpr std::size_t kAutoMipStations = 250;

// CPU time for making room for names when asked (CityLayoutParams::label_room_ms; London:
// 4-6 s in up to 12 rounds of 6 tries and 6 tries per name left, 200-300 ms each; the budget
// is a backstop).
inline constexpr double kLabelRoomCpuMs = 10000;

struct CityLayoutParams {
  bool worth_lengths = true;  // visual-worth lengths (eq. 5.4), else uniform l_const (the paper's DF4)
  double l_const = 10.0;
  RankSource rank = RankSource::automatic;
  WorthParams worth;
  // Per POI its interest weight in eq. 5.1 (poi/interests.hpp; beyond the paper); empty: 1.
  std::vector<double> poi_weight;
  LayoutSolver solver = LayoutSolver::automatic;
  double time_limit_s = 10.0;
  MipSolveFn mip;  // needed when the MIP may run; empty: no MIP (as "fast")
  // CPU time for making room in the layout for names left out (0: none; the server's
  // background improvement sets it, as it costs 100-400 ms that a first answer cannot spend).
  double label_room_ms = 0;
};

// Room made in the layout for the names left out where symbols are 12 px across (issue 14).
struct LabelRoomReport {
  std::string status = "not_run";  // "not_run", "not_needed", "kept", "no_gain", "no_time"
  std::size_t rooms = 0;              // stations asked room for (in the first round)
  std::size_t unnamed_before = 0, unnamed_after = 0;  // at the first such zoom
  int rounds = 0, kept = 0;    // rounds for all names left out at once, and tries kept (of both kinds)
  int single_tries = 0;        // tries for one name in one of its places, after the rounds
};

struct SolverReport {
  std::string kind = "fast";    // whose layout it is: "fast" or "mip"
  std::string status;           // that solver's status
  std::optional<double> gap;    // the MIP's relative gap (kind "mip")
  std::optional<MipReport> mip;  // when the MIP was considered
  LabelRoomReport label_room;    // room made for names (CityLayoutParams::label_room_ms)
};

struct CityLayoutTimings {  // ms
  double visual_worth = 0, prelayout = 0, fast = 0, layout = 0, warp = 0, total = 0;
  // The fast path's stages (within `fast`): grid routing, bend reduction, spacing, measuring.
  double route = 0, bends = 0, spacing = 0, measure = 0;
  double line_order = 0;  // the lines' order along shared track (after the MIP, on the final layout)
  double labels = 0;      // the station names' placements
  double label_room = 0;  // making room for the names left out, and placing them again
};

struct CityLayoutResult {
  Layout layout;                     // layout units; layout.status is the result's status
  std::vector<double> min_length;    // per edge, layout units (eq. 5.4)
  CityFrame frame;                   // layout -> metres; POIs, mesh and outline warped
  std::vector<double> node_worth;    // vw per node (raw eq. 5.1)
  std::vector<double> poi_worth;     // vw per POI (raw eq. 5.1)
  LayoutQuality quality;
  CompareMetrics compare;            // the figures of ../shared/tools/metro_compare.py (bends as a
                                     // reader counts them: along lines between interchanges)
  GridRouteReport route;
  BendReductionReport bends;
  SpacingReport spacing;
  SolverReport solver;
  LineOrder line_order;              // per edge, its lines left to right (metro/line_order.hpp)
  std::vector<LabelScale> labels;    // station names placed per zoom (metro/station_labels.hpp)
  CityLayoutTimings timing;
};

// The zooms station names are placed for: the mean edge on screen, px. Symbols reach 12 px
// across (LabelStyle: 0.08 of the mean edge in radius) from a mean edge of 75 px on.
inline const std::vector<double> kLabelMeanEdgesPx = {15, 22, 33, 50, 75, 112, 168};

// Throws std::invalid_argument when params.rank is `data` and no POI has a rank. `pois` are
// the POIs `in` was made from (their prominence gives the ranks).
CityLayoutResult layout_city(const CityMetroInput& in, const std::vector<model::Poi>& pois,
                             const CityLayoutParams& params);

}  // namespace tourmap::metro
