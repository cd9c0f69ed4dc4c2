#pragma once
// A city's transit-centric tourist map (paper 5.4) as the API serves it: the request's
// parameters, and the answer as JSON. The computation (visual worth -> edge lengths ->
// octilinear layout -> POIs, outline and a mesh warped into it, with the quality report) is
// core's, metro/city_layout.hpp. Everything is in one planar frame, metres in the city's
// projection: the layout is aligned to the geography by a uniform scale and a translation (no
// rotation, which would break octilinearity), so clients can animate between the two.

#include "http.hpp"
#include "metro_data.hpp"
#include "mip_runner.hpp"

#include "metro/city_layout.hpp"
#include "metro/layout_quality.hpp"
#include "poi/cluster_tree.hpp"
#include "poi/interests.hpp"

#include <chrono>
#include <memory>
#include <string>

namespace tourmap::api {

struct LayoutRequest {
  bool worth_lengths = true;  // lengths=visual-worth (eq. 5.4) | uniform (the paper's DF4)
  using Solver = metro::LayoutSolver;  // auto | fast | mip (see below)
  Solver solver = Solver::automatic;
  double time_limit_s = 10.0;
  RankSource rank = RankSource::automatic;
  metro::WorthParams worth;
  double l_const = 10.0;
  // Not a parameter: the background improvement's (MetroService::improve) request also makes
  // room in the layout for names left out (metro::CityLayoutParams::label_room_ms).
  bool label_room = false;
  // Interests (beyond the paper; poi/interests.hpp): `interests_given` as the request names
  // them (checked for form), `interests` their canonical form for the city once
  // resolve_interests ran (empty: the paper's worth). canonical() writes the canonical form
  // when resolved, else the given one sorted (a key part that may split equivalent requests,
  // never join different ones); nothing when there are none, so default keys stay as they were.
  poi::CategoryWeights interests_given;
  poi::CategoryWeights interests;
  bool interests_resolved = false;
  std::string canonical() const;  // cache key part
};

// From the query string (GET) or a JSON object (POST); ApiError 400 naming the field.
LayoutRequest parse_layout_query(const Request& req);
LayoutRequest parse_layout_body(const nlohmann::json& body);

// The request's interests in canonical form for the city's categories; ApiError 400 naming
// `interests` for a category the city does not have (the message lists them) or when every
// category would weigh 0. Idempotent.
void resolve_interests(LayoutRequest& req, const CityMetroData& data);
// The interests' part of a cache key: "" without interests, else " interests={...}".
std::string interests_key(const LayoutRequest& req);
// Per POI its interest weight (resolves a copy of `req`); empty when every weight is 1.
std::vector<double> interest_weights(const LayoutRequest& req, const CityMetroData& data);

struct CityLayout {
  std::string body;                   // the JSON answer
  std::vector<geo::XY> poi_layout;    // POIs in the layout frame (metres)
  std::vector<double> poi_worth;      // vw per POI (raw eq. 5.1)
  std::vector<bool> poi_outside;      // far beyond the network: not warped with confidence
  metro::LayoutQuality quality;
  std::string status;
};

// Solvers (parameter `solver`): "fast" is the grid-graph routing alone; "mip" polishes it with
// the octilinear MIP for the rest of the time limit; "auto" routes, then polishes networks of up
// to `kAutoMipStations` stations for a tenth of the time limit, at most 0.5 s (the server
// answers "auto" with the fast layout and polishes in the background instead: MetroService).
// The MIP result is kept only with fewer bends and no worse otherwise (metro/mip_polish.hpp).
inline constexpr std::size_t kAutoMipStations = metro::kAutoMipStations;
inline constexpr std::size_t kMaxMipColumns = metro::kMaxMipColumns;
std::shared_ptr<const CityLayout> compute_city_layout(const CityMetroData& data, const LayoutRequest& req,
                                                      const MipSolver& mip);

// The core pipeline's parameters for a request (`mip` solves the MIP when it runs).
metro::CityLayoutParams layout_params(const CityMetroData& data, const LayoutRequest& req, const MipSolver& mip);

// The JSON answer for a computed layout; `started`: when the request's computation began
// (timing_ms.total).
std::string layout_body(const CityMetroData& data, const LayoutRequest& req, const metro::CityLayoutResult& layout,
                        std::chrono::steady_clock::time_point started);

// POI visual worth at their geographic positions with default parameters (for clusters);
// `poi_weight`: the interest weights (interest_weights), empty for the paper's worth.
std::vector<double> poi_worth_geo(const CityMetroData& data, RankSource rank, const metro::WorthParams& params,
                                  const std::vector<double>& poi_weight = {});

}  // namespace tourmap::api
