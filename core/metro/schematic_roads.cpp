#include "metro/schematic_roads.hpp"

#include "deform/applications.hpp"
#include "deform/deformer.hpp"
#include "deform/foldover.hpp"
#include "deform/planar.hpp"
#include "grid/grid.hpp"
#include "metro/warp.hpp"
#include "util/elapsed.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace tourmap::metro {
namespace {

using util::Clock;
using util::ms_since;

double dist(XY a, XY b) { return std::hypot(a.x - b.x, a.y - b.y); }

// The inverse of a Helmert transformation (5.4.3): [a -b; b a] p + t = q  =>  p = [a b; -b a] (q - t) / s^2.
XY helmert_inverse(const Helmert& h, XY q) {
  const double s2 = h.a * h.a + h.b * h.b;
  const double x = q.x - h.tx, y = q.y - h.ty;
  return {(h.a * x + h.b * y) / s2, (-h.b * x + h.a * y) / s2};
}

// The roads inside the crop box, as a network of their own, with what each of its ways was.
struct Cropped {
  model::RoadNetwork net;
  std::vector<std::uint32_t> way_of;  // per cropped way: the input way
  std::vector<RoadRank> rank_of;      // per cropped way
};

// Axis-aligned box in a local projection's metres.
struct MetreBox {
  geo::LocalProjection projection;
  XY lo, hi;
  bool contains(XY p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

MetreBox crop_box(const std::vector<SchematicStation>& stations, const SchematicRoadsParams& params) {
  geo::BBox box;
  for (const auto& s : stations) box.extend(s.geo);
  MetreBox m;
  m.projection = geo::projection_for(box);
  m.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  m.hi = {-m.lo.x, -m.lo.y};
  for (const auto& s : stations) {
    const auto p = geo::project(m.projection, s.geo);
    m.lo = {std::min(m.lo.x, p.x), std::min(m.lo.y, p.y)};
    m.hi = {std::max(m.hi.x, p.x), std::max(m.hi.y, p.y)};
  }
  const double margin = std::max(params.margin_share * std::max(m.hi.x - m.lo.x, m.hi.y - m.lo.y), params.margin_min_m);
  m.lo = {m.lo.x - margin, m.lo.y - margin};
  m.hi = {m.hi.x + margin, m.hi.y + margin};
  return m;
}

// Per input node: inside the box (1), outside (0), not yet projected (-1).
class NodeInside {
 public:
  NodeInside(const model::RoadNetwork& net, const MetreBox& box) : net_(net), box_(box), state_(net.nodes.size(), -1) {}
  bool operator()(std::uint32_t n) {
    if (state_[n] < 0) state_[n] = box_.contains(geo::project(box_.projection, net_.nodes[n].pos)) ? 1 : 0;
    return state_[n] == 1;
  }

 private:
  const model::RoadNetwork& net_;
  const MetreBox& box_;
  std::vector<signed char> state_;
};

// The ranks kept: the most important first, as long as their edges inside the box fit the
// bound (at least the major roads).
int ranks_within(const std::array<std::size_t, kRoadRanks>& inside, std::size_t max_edges) {
  std::size_t total = 0;
  for (int r = 0; r < kRoadRanks; ++r) {
    total += inside[r];
    if (total > max_edges) return std::max(r, 1);
  }
  return kRoadRanks;
}

Cropped crop_roads(const model::RoadNetwork& roads, const MetreBox& box, const SchematicRoadsParams& params,
                   SchematicRoadsStats& stats) {
  NodeInside inside(roads, box);
  std::vector<std::optional<RoadRank>> rank(roads.ways.size());
  std::array<std::size_t, kRoadRanks> edges_inside{};
  for (std::size_t w = 0; w < roads.ways.size(); ++w) {
    if ((w & 1023) == 0) util::check_stop();
    rank[w] = road_rank(roads.ways[w].highway);
    if (!rank[w]) continue;
    const auto& nodes = roads.ways[w].nodes;
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      const bool in = inside(nodes[i - 1]) && inside(nodes[i]);
      if (in) ++edges_inside[static_cast<int>(*rank[w])];
      else ++stats.cropped_out_edges;
    }
  }
  stats.ranks_kept = ranks_within(edges_inside, params.max_edges);
  for (int r = stats.ranks_kept; r < kRoadRanks; ++r) stats.dropped_edges += edges_inside[r];

  Cropped out;
  std::unordered_map<std::uint32_t, std::uint32_t> node_of;  // input node -> cropped node
  auto cropped_node = [&](std::uint32_t n) {
    auto [it, added] = node_of.emplace(n, static_cast<std::uint32_t>(out.net.nodes.size()));
    if (added) out.net.nodes.push_back(roads.nodes[n]);
    return it->second;
  };
  std::size_t edges = 0;
  for (std::size_t w = 0; w < roads.ways.size(); ++w) {
    if (!rank[w] || static_cast<int>(*rank[w]) >= stats.ranks_kept) continue;
    if ((w & 1023) == 0) util::check_stop();
    // The way's runs of consecutive nodes inside the box, each a way of the cropped network.
    model::RoadWay piece;
    auto flush = [&] {
      // The major roads alone may exceed the bound: the ways beyond it are dropped.
      if (piece.nodes.size() >= 2 && edges + piece.nodes.size() - 1 <= params.max_edges) {
        edges += piece.nodes.size() - 1;
        for (auto& n : piece.nodes) n = cropped_node(n);
        out.net.ways.push_back(piece);
        out.way_of.push_back(static_cast<std::uint32_t>(w));
        out.rank_of.push_back(*rank[w]);
      } else if (piece.nodes.size() >= 2) {
        stats.dropped_edges += piece.nodes.size() - 1;
      }
      piece.nodes.clear();
    };
    piece.osm_id = roads.ways[w].osm_id;
    piece.highway = roads.ways[w].highway;
    for (auto n : roads.ways[w].nodes) {
      if (inside(n)) piece.nodes.push_back(n);
      else flush();
    }
    flush();
  }
  out.net.edges = model::edges_of(out.net.ways);
  return out;
}

// The smallest distance between two of `points` (infinity for fewer than two): a sweep over x.
double min_spacing(std::vector<XY> points) {
  std::sort(points.begin(), points.end(), [](XY a, XY b) { return a.x < b.x; });
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size() && points[j].x - points[i].x < best; ++j)
      best = std::min(best, dist(points[i], points[j]));
  return best;
}

// Each station's nearest road node, pulled to the station's aligned layout position; one
// guide per node (the nearest station's), none beyond max_snap_m.
std::vector<deform::Guide> snap_stations(const deform::PlanarNetwork& planar, const deform::NodeIndex& index,
                      const std::vector<XY>& station_map, const std::vector<XY>& targets,
                      const SchematicRoadsParams& params, SchematicRoadsStats& stats) {
  struct Best {
    std::size_t station;
    double d;
  };
  std::unordered_map<std::uint32_t, Best> best;
  for (std::size_t s = 0; s < station_map.size(); ++s) {
    const auto node = index.nearest(station_map[s]);
    const double d = dist(planar.nodes[node], station_map[s]) * planar.transform.metres_per_unit;
    if (d > params.max_snap_m) {
      ++stats.far_stations;
      continue;
    }
    auto [it, added] = best.emplace(node, Best{s, d});
    if (added) continue;
    ++stats.shared_nodes;
    if (d < it->second.d) it->second = {s, d};
  }
  std::vector<std::pair<std::uint32_t, std::size_t>> chosen;
  for (const auto& [node, b] : best) chosen.emplace_back(node, b.station);
  std::sort(chosen.begin(), chosen.end());
  std::vector<deform::Guide> guides;  // sorted by node, as the prepared system expects
  for (const auto& [node, s] : chosen) guides.push_back({node, targets[s]});  // eq. 4.6: node i wants to be at its target
  return guides;
}

// The adaptive grid (4.4.1) over the roads and the guides' targets: fine enough that no two
// guides share a quad, coarsened until its unknowns fit the bound.
grid::Grid guide_grid(const deform::PlanarNetwork& planar, const std::vector<deform::Guide>& guides,
                      const std::vector<XY>& stations, const SchematicRoadsParams& params, SchematicRoadsStats& stats) {
  std::vector<XY> extent = planar.nodes;
  extent.insert(extent.end(), stations.begin(), stations.end());
  std::vector<XY> special;
  for (const auto& g : guides) {
    extent.push_back(g.target);  // the grid must reach where the guides go
    special.push_back(planar.nodes[g.node]);
  }
  const auto frame = grid::frame_around(extent, params.grid_base, params.grid_margin);
  const double spacing = min_spacing(special);
  int depth = params.min_depth;
  while (depth < params.max_depth && std::isfinite(spacing) &&
         frame.cell / std::ldexp(1.0, depth) > params.guide_cell_share * spacing)
    ++depth;
  int split = params.split_vertices;
  constexpr std::uint64_t kMaxLatticeCells = 1u << 22;  // as the deform service (memory)
  while (depth > 0 && grid::lattice_cells(frame, depth) > kMaxLatticeCells) --depth;
  for (;;) {
    util::check_stop();
    auto g = grid::build_adaptive(frame, planar.nodes, special, {params.grid_base, depth, split});
    if (2 * g.vertices.size() <= params.max_unknowns || (depth <= 1 && split >= 1024)) {
      stats.grid_depth = depth;
      stats.split_vertices = split;
      return g;
    }
    // Fewer vertices: first let quads hold more road nodes, then go less deep.
    if (split < 256) split *= 2;
    else --depth;
  }
}

// Points inside the road edges, no farther apart than `spacing` (map units): carried through
// the grids with the nodes, they draw each road as its image under the deformation rather than
// as the chord between its deformed nodes. The grid's map is one-to-one where no quad folded
// (deform/foldover.hpp), so images of roads that did not cross do not cross; chords may.
struct EdgePoints {
  std::vector<std::uint32_t> start;  // per edge: its first point; start[edges] = total
  std::vector<XY> points;
};

EdgePoints sample_edges(const deform::PlanarNetwork& net, double spacing) {
  EdgePoints out;
  out.start.reserve(net.edges.size() + 1);
  for (const auto& [a, b] : net.edges) {
    out.start.push_back(static_cast<std::uint32_t>(out.points.size()));
    const XY pa = net.nodes[a], pb = net.nodes[b];
    const int n = spacing > 0 ? static_cast<int>(dist(pa, pb) / spacing) : 0;
    for (int i = 1; i <= n; ++i) {
      const double t = static_cast<double>(i) / (n + 1);
      out.points.push_back({pa.x + t * (pb.x - pa.x), pa.y + t * (pb.y - pa.y)});
    }
  }
  out.start.push_back(static_cast<std::uint32_t>(out.points.size()));
  return out;
}

// The roads as chains through nodes and edge points: the points of `nodes` then of `inner`,
// each edge a chain from its first node through its points to its second.
deform::PlanarNetwork dense_network(const deform::PlanarNetwork& net, const EdgePoints& samples, const std::vector<XY>& nodes,
                                    const std::vector<XY>& inner) {
  deform::PlanarNetwork out;
  out.transform = net.transform;
  out.nodes = nodes;
  out.nodes.insert(out.nodes.end(), inner.begin(), inner.end());
  const auto base = static_cast<std::uint32_t>(nodes.size());
  for (std::size_t e = 0; e < net.edges.size(); ++e) {
    std::uint32_t previous = net.edges[e].first;
    for (auto i = samples.start[e]; i < samples.start[e + 1]; ++i) {
      out.edges.emplace_back(previous, base + i);
      previous = base + i;
    }
    out.edges.emplace_back(previous, net.edges[e].second);
  }
  return out;
}

struct StepResult {
  std::vector<XY> nodes;    // road nodes after the step
  std::vector<XY> carried;  // the other points carried through the step's grid
};

// One deformation on an adaptive grid over the roads as they are now (eq. 4.5 with the guide
// term, fold-overs relaxed and added crossings smoothed after the solve: 4.4.2).
StepResult deform_step(const deform::PlanarNetwork& current, const std::vector<deform::Guide>& guides,
                       const std::vector<XY>& points, const SchematicRoadsParams& params, SchematicRoadsStats& stats) {
  auto t = Clock::now();
  auto grid = guide_grid(current, guides, points, params, stats);
  stats.grid_ms += ms_since(t);
  stats.quads = grid.quads.size();
  deform::Targets wanted;
  wanted.guides = guides;
  auto prepared = deform::prepare_grid(current, std::move(grid), deform::guide_nodes(guides), params.weights, params.boundary);
  stats.assembly_ms += prepared.assembly_ms;
  stats.unknowns = static_cast<std::size_t>(prepared.rest_unknowns.size());
  deform::RunOptions options;
  stats.cholesky = stats.unknowns <= params.max_direct_unknowns;
  options.solve.kind = stats.cholesky ? deform::SolverKind::cholesky : deform::SolverKind::cg;
  options.solve.max_iterations = params.cg_max_iterations;
  options.solve.time_limit_ms = params.cg_time_limit_ms;
  options.correction_budget_ms = params.correction_budget_ms;
  options.untangle = params.untangle_chords;
  options.relax_iterations = params.relax_iterations;
  auto run = deform::run(prepared, current, wanted, options);
  stats.factor_ms += run.solve.factor_ms;
  stats.solve_ms += run.solve.solve_ms;
  stats.place_ms += run.place_ms;
  stats.iterations += run.solve.iterations;
  stats.converged = run.solve.converged;
  stats.foldovers = run.inverted_quads;
  stats.untangle_left = run.untangle_left;
  stats.relax_iterations = run.relax_iterations;
  const deform::NodeIndex index(current.nodes);
  auto carried = deform::map_points(prepared, run.points, run.nodes, current.nodes, index, points);
  return {std::move(run.nodes), std::move(carried)};
}

}  // namespace

std::optional<RoadRank> road_rank(std::string_view h) {
  for (std::string_view v : {"motorway", "motorway_link", "trunk", "trunk_link", "primary", "primary_link"})
    if (h == v) return RoadRank::major;
  for (std::string_view v : {"secondary", "secondary_link", "tertiary", "tertiary_link"})
    if (h == v) return RoadRank::medium;
  for (std::string_view v : {"residential", "unclassified", "living_street", "road"})
    if (h == v) return RoadRank::minor;
  return std::nullopt;
}

const char* road_rank_name(RoadRank rank) {
  switch (rank) {
    case RoadRank::major: return "major";
    case RoadRank::medium: return "medium";
    case RoadRank::minor: return "minor";
  }
  return "minor";
}

SchematicRoadsResult schematic_roads(const model::RoadNetwork& roads, const std::vector<SchematicStation>& stations,
                                     const SchematicRoadsParams& params) {
  const auto started = Clock::now();
  SchematicRoadsResult result;
  auto& stats = result.stats;
  stats.stations = stations.size();
  geo::BBox geo_box, layout_box;
  for (const auto& s : stations) {
    geo_box.extend(s.geo);
    layout_box.extend({s.layout.x, s.layout.y});
  }
  const auto point_like = [](const geo::BBox& b) { return b.min_lon == b.max_lon && b.min_lat == b.max_lat; };
  if (stations.size() < 2 || point_like(geo_box) || point_like(layout_box))
    throw std::invalid_argument("a schematic's roads need two stations at distinct places");

  auto t = Clock::now();
  const auto cropped = crop_roads(roads, crop_box(stations, params), params, stats);
  stats.road_edges = cropped.net.edges.size();
  stats.crop_ms = ms_since(t);
  if (cropped.net.nodes.empty()) {
    stats.total_ms = ms_since(started);
    return result;
  }
  const auto planar = deform::make_planar(cropped.net);

  // 1. The layout in the road map's plane (5.4.3): least squares layout -> map units.
  std::vector<XY> layout, station_map;
  for (const auto& s : stations) {
    layout.push_back(s.layout);
    station_map.push_back(planar.transform.to_map(s.geo));
  }
  const auto helmert = fit_helmert(layout, station_map);
  const double layout_per_map = 1.0 / helmert.scale();
  std::vector<XY> targets;
  for (std::size_t s = 0; s < stations.size(); ++s) {
    targets.push_back(helmert.apply(layout[s]));
    const double r = dist(targets.back(), station_map[s]) * layout_per_map;
    stats.helmert_rms += r * r / stations.size();
    stats.helmert_max = std::max(stats.helmert_max, r);
  }
  stats.helmert_rms = std::sqrt(stats.helmert_rms);
  stats.helmert_scale = helmert.scale() * planar.transform.metres_per_unit;
  stats.helmert_rotation_deg = helmert.rotation() * 180.0 / M_PI;

  // 2. Guides: stations snapped to road nodes, pulled to their targets (eq. 4.6/4.7).
  const auto guides = snap_stations(planar, deform::NodeIndex(planar.nodes), station_map, targets, params, stats);
  stats.guides = guides.size();

  // 3. The deformation on the adaptive grid, in steps: each asks for an equal share of what is
  // left between the guides and their targets, on a grid built over the roads as the previous
  // step left them. A schematic moves stations by up to kilometres relative to their
  // neighbours; one linear solve (which keeps every road edge's direction) folds the grid
  // there, and relaxing the folds gives most of the move back. Small steps fold little, so
  // the relaxation keeps what they did.
  deform::PlanarNetwork current = planar;
  const auto samples = sample_edges(planar, params.sample_spacing_m / planar.transform.metres_per_unit);
  // Carried through every step: the stations' geographic points, then the edge points.
  std::vector<XY> carried = station_map;
  carried.insert(carried.end(), samples.points.begin(), samples.points.end());
  const int steps = guides.empty() ? 0 : std::max(1, params.steps);
  for (int k = 0; k < steps; ++k) {
    std::vector<deform::Guide> step;
    for (const auto& g : guides) {
      const XY at = current.nodes[g.node];
      const double share = 1.0 / (steps - k);
      step.push_back({g.node, {at.x + (g.target.x - at.x) * share, at.y + (g.target.y - at.y) * share}});
    }
    auto moved = deform_step(current, step, carried, params, stats);
    current.nodes = std::move(moved.nodes);
    carried = std::move(moved.carried);
  }
  stats.steps = steps;
  stats.edge_points = samples.points.size();
  const std::vector<XY> inner(carried.begin() + static_cast<std::ptrdiff_t>(stations.size()), carried.end());
  t = Clock::now();
  stats.crossings_added = deform::count_added_crossings(dense_network(planar, samples, planar.nodes, samples.points),
                                                        dense_network(planar, samples, current.nodes, inner).nodes);
  stats.crossings_ms = ms_since(t);

  // What was achieved, in layout units: the guided nodes, and every station carried through
  // the deformed grids.
  for (const auto& g : guides) {
    const double e = dist(current.nodes[g.node], g.target) * layout_per_map;
    stats.max_guide_error = std::max(stats.max_guide_error, e);
    stats.mean_guide_error += e / guides.size();
  }
  for (std::size_t s = 0; s < stations.size(); ++s) {
    const double e = dist(carried[s], targets[s]) * layout_per_map;
    stats.max_station_error = std::max(stats.max_station_error, e);
    stats.mean_station_error += e / stations.size();
  }

  // Every road polyline through the deformed grids (its nodes and edge points), then back into
  // the layout's frame. The planar network's edges are the ways' consecutive node pairs, in
  // way order (model::edges_of).
  result.roads.reserve(cropped.net.ways.size());
  std::size_t edge = 0;
  for (std::size_t w = 0; w < cropped.net.ways.size(); ++w) {
    SchematicRoad road{cropped.way_of[w], cropped.rank_of[w], {}};
    const auto& nodes = cropped.net.ways[w].nodes;
    road.points.push_back(helmert_inverse(helmert, current.nodes[nodes[0]]));
    for (std::size_t i = 1; i < nodes.size(); ++i, ++edge) {
      for (auto k = samples.start[edge]; k < samples.start[edge + 1]; ++k) road.points.push_back(helmert_inverse(helmert, inner[k]));
      road.points.push_back(helmert_inverse(helmert, current.nodes[nodes[i]]));
    }
    result.roads.push_back(std::move(road));
  }
  stats.total_ms = ms_since(started);
  return result;
}

}  // namespace tourmap::metro
