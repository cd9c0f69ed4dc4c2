#pragma once
// POST /api/v1/deform/{focus,mental,destination}: the request body, validated. Every error is an
// ApiError naming the field (e.g. "regions[1].scale"). Geometry stays in lon/lat here; the
// service converts it to map units once it has the network.

#include "http.hpp"

#include "deform/problem.hpp"
#include "deform/solver.hpp"
#include "geo/lonlat.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tourmap::api {

enum class DeformApp { focus, mental, destination };

// Limits (documented in openapi.yaml).
struct DeformLimits {
  int max_base = 64;
  int max_depth = 6;
  int max_uniform = 256;
  std::size_t max_unknowns = 250000;          // any method with CG, and the edge-level Cholesky
  std::size_t max_direct_grid_unknowns = 60000;  // grid methods with Cholesky: factor time grows
                                                 // fast (2D fill-in): about 2 s at 43K unknowns
  std::uint64_t max_lattice_cells = 1u << 22;  // finest-level cells of an adaptive grid (memory)
  std::size_t max_regions = 32;
  std::size_t max_guides = 2000;
  std::size_t max_route = 20000;
  std::size_t max_map_points = 10000;
  std::size_t max_polygon_vertices = 10000;
  std::size_t max_inline_vertices = 50000;
  double max_scale = 50.0;
  double max_time_limit_ms = 30000.0;
  // Memory the service's caches may hold (least recently used entries go first).
  std::size_t network_cache_bytes = 256u << 20;   // road networks prepared for deformation
  std::size_t prepared_cache_bytes = 512u << 20;  // grids, systems and factorizations
  std::size_t result_cache_bytes = 64u << 20;     // whole response bodies
};

struct GridChoice {
  enum class Kind { adaptive, uniform, edges } kind = Kind::adaptive;
  int base = 10;   // adaptive
  int depth = 3;   // adaptive
  int c = 4;       // adaptive: split quads holding more road vertices than this
  int n = 80;      // uniform
  std::string describe() const;  // canonical, for cache keys and stats
};

struct FocusRegionInput {
  std::optional<geo::LonLat> center;
  double radius_m = 0.0;
  std::vector<geo::LonLat> polygon;
  double scale = 1.0;
};

struct GuideInput {
  std::optional<std::int64_t> vertex;  // road node id (OSM id, or index for inline roads)
  std::optional<geo::LonLat> point;    // else: snap this point to the nearest road node
  geo::LonLat target;
};

struct DeformRequest {
  DeformApp app = DeformApp::focus;
  std::string roads_id;                     // a stored road network, or
  std::optional<nlohmann::json> roads_inline;  // an inline GeoJSON FeatureCollection of LineStrings
  GridChoice grid;
  deform::Weights weights;
  deform::Boundary boundary = deform::Boundary::fixed;
  deform::SolverKind solver = deform::SolverKind::cholesky;
  int max_iterations = 20000;
  double tolerance = 1e-8;
  double time_limit_ms = 10000.0;
  bool relax = true;   // relax fold-overs away after solving (paper 4.4.2); false shows the raw solve
  bool check_crossings = false;
  enum class RoadsOutput { geojson, positions, none } roads_output = RoadsOutput::geojson;
  bool grid_output = true;
  std::vector<geo::LonLat> map_points;  // original-map points to report where they land

  std::vector<FocusRegionInput> regions;  // focus
  std::vector<GuideInput> guides;         // mental
  std::vector<std::int64_t> route;        // destination: road node ids along the route
  std::vector<geo::LonLat> sketch;        // destination
  double simplify_m = 0.0;                // destination: Douglas-Peucker tolerance for the sketch

  std::string canonical;  // the body as parsed, re-serialised (cache key part)
};

DeformRequest parse_deform_request(DeformApp app, const nlohmann::json& body, const DeformLimits& limits = {});

const char* app_name(DeformApp app);

}  // namespace tourmap::api
