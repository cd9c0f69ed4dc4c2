#include "load/coastline_sea.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <utility>

namespace tourmap::load {
namespace {

using geo::BBox;
using geo::LonLat;
using Ring = std::vector<LonLat>;

bool same(LonLat a, LonLat b) { return a.lon == b.lon && a.lat == b.lat; }

void push_point(Ring& ring, LonLat p) {
  if (ring.empty() || !same(ring.back(), p)) ring.push_back(p);
}

struct Chain {
  std::vector<std::int64_t> ids;
  Ring points;
  bool closed() const { return ids.size() >= 4 && ids.front() == ids.back(); }
};

// Joins the ways end to end by node id: a way continues a chain when its first node is the
// chain's last one (and is prepended when its last node is the chain's first one).
std::vector<Chain> join_ways(const std::vector<CoastlineWay>& ways) {
  std::unordered_map<std::int64_t, std::vector<std::size_t>> by_first, by_last;
  for (std::size_t i = 0; i < ways.size(); ++i) {
    const auto& way = ways[i];
    if (way.node_ids.size() < 2 || way.node_ids.size() != way.points.size()) continue;
    by_first[way.node_ids.front()].push_back(i);
    by_last[way.node_ids.back()].push_back(i);
  }
  std::vector<bool> used(ways.size(), false);
  auto take = [&](std::unordered_map<std::int64_t, std::vector<std::size_t>>& index,
                  std::int64_t id) -> std::optional<std::size_t> {
    auto it = index.find(id);
    if (it == index.end()) return std::nullopt;
    for (std::size_t i : it->second)
      if (!used[i]) {
        used[i] = true;
        return i;
      }
    return std::nullopt;
  };
  std::vector<Chain> chains;
  for (std::size_t i = 0; i < ways.size(); ++i) {
    const auto& first = ways[i];
    if (used[i] || first.node_ids.size() < 2 || first.node_ids.size() != first.points.size()) continue;
    used[i] = true;
    Chain chain{first.node_ids, first.points};
    while (!chain.closed()) {
      const auto next = take(by_first, chain.ids.back());
      if (!next) break;
      const auto& way = ways[*next];
      chain.ids.insert(chain.ids.end(), way.node_ids.begin() + 1, way.node_ids.end());
      chain.points.insert(chain.points.end(), way.points.begin() + 1, way.points.end());
    }
    while (!chain.closed()) {
      const auto previous = take(by_last, chain.ids.front());
      if (!previous) break;
      const auto& way = ways[*previous];
      chain.ids.insert(chain.ids.begin(), way.node_ids.begin(), way.node_ids.end() - 1);
      chain.points.insert(chain.points.begin(), way.points.begin(), way.points.end() - 1);
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

// The part [t0, t1] of the segment p-q inside the box (Liang-Barsky), or nothing when the
// segment misses the box or only touches it.
std::optional<std::pair<double, double>> clip_segment(LonLat p, LonLat q, const BBox& box) {
  double t0 = 0.0, t1 = 1.0;
  // The constraint num * t <= den.
  auto edge = [&](double num, double den) {
    if (num == 0.0) return den >= 0.0;
    const double t = den / num;
    if (num < 0.0) {
      if (t > t1) return false;
      t0 = std::max(t0, t);
    } else {
      if (t < t0) return false;
      t1 = std::min(t1, t);
    }
    return true;
  };
  const double dx = q.lon - p.lon, dy = q.lat - p.lat;
  if (edge(-dx, p.lon - box.min_lon) && edge(dx, box.max_lon - p.lon) && edge(-dy, p.lat - box.min_lat) &&
      edge(dy, box.max_lat - p.lat) && t0 < t1)
    return std::pair{t0, t1};
  return std::nullopt;
}

LonLat along(LonLat p, LonLat q, double t) {
  if (t <= 0.0) return p;
  if (t >= 1.0) return q;
  return {p.lon + t * (q.lon - p.lon), p.lat + t * (q.lat - p.lat)};
}

// A part of a chain inside the box. An end is "cut" where the chain crosses the box's boundary;
// otherwise it is the chain's own end (which may lie short of the boundary).
struct Piece {
  Ring points;
  bool start_cut = false;
  bool end_cut = false;
};

std::vector<Piece> clip_polyline(const Ring& points, const BBox& box) {
  std::vector<Piece> pieces;
  std::optional<Piece> open;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const LonLat p = points[i], q = points[i + 1];
    const auto part = clip_segment(p, q, box);
    if (!part) {
      if (open) {  // p lies on the boundary and the chain leaves there
        pieces.push_back(std::move(*open));
        open.reset();
      }
      continue;
    }
    if (!open) {
      open.emplace();
      open->start_cut = part->first > 0.0;
      open->points.push_back(along(p, q, part->first));
    }
    push_point(open->points, along(p, q, part->second));
    if (part->second < 1.0) {
      open->end_cut = true;
      pieces.push_back(std::move(*open));
      open.reset();
    }
  }
  if (open) pieces.push_back(std::move(*open));
  std::erase_if(pieces, [](const Piece& piece) { return piece.points.size() < 2; });
  return pieces;
}

// Distances of a point (in the box) to the box's sides: top, right, bottom, left.
std::array<double, 4> side_distances(LonLat p, const BBox& box) {
  return {std::max(0.0, box.max_lat - p.lat), std::max(0.0, box.max_lon - p.lon), std::max(0.0, p.lat - box.min_lat),
          std::max(0.0, p.lon - box.min_lon)};
}

int nearest_side(LonLat p, const BBox& box) {
  const auto d = side_distances(p, box);
  return static_cast<int>(std::min_element(d.begin(), d.end()) - d.begin());
}

double distance_to_boundary(LonLat p, const BBox& box) {
  const auto d = side_distances(p, box);
  return *std::min_element(d.begin(), d.end());
}

// The point of the nearest side closest to p.
LonLat onto_boundary(LonLat p, const BBox& box) {
  const LonLat q{std::clamp(p.lon, box.min_lon, box.max_lon), std::clamp(p.lat, box.min_lat, box.max_lat)};
  switch (nearest_side(q, box)) {
    case 0:
      return {q.lon, box.max_lat};
    case 1:
      return {box.max_lon, q.lat};
    case 2:
      return {q.lon, box.min_lat};
    default:
      return {box.min_lon, q.lat};
  }
}

// Position of a boundary point clockwise from the top-left corner: top side [0, 1], right
// side [1, 2], bottom side [2, 3], left side [3, 4) (each side scaled to length 1).
double boundary_param(LonLat p, const BBox& box) {
  const double w = box.max_lon - box.min_lon, h = box.max_lat - box.min_lat;
  double t = 0.0;
  switch (nearest_side(p, box)) {
    case 0:
      t = (p.lon - box.min_lon) / w;
      break;
    case 1:
      t = 1.0 + (box.max_lat - p.lat) / h;
      break;
    case 2:
      t = 2.0 + (box.max_lon - p.lon) / w;
      break;
    default:
      t = 3.0 + (p.lat - box.min_lat) / h;
      break;
  }
  return t >= 4.0 ? t - 4.0 : t;
}

LonLat corner(int k, const BBox& box) {  // k = 0 top-left, then clockwise
  switch (k & 3) {
    case 0:
      return {box.min_lon, box.max_lat};
    case 1:
      return {box.max_lon, box.max_lat};
    case 2:
      return {box.max_lon, box.min_lat};
    default:
      return {box.min_lon, box.min_lat};
  }
}

// Appends the box corners passed walking clockwise from boundary position a to b.
void add_corners(Ring& ring, double a, double b, const BBox& box) {
  double distance = b - a;
  if (distance < 0.0) distance += 4.0;
  for (double c = std::floor(a) + 1.0; c < a + distance; c += 1.0) push_point(ring, corner(static_cast<int>(c), box));
}

// An open piece with both ends on the boundary.
struct Crossing {
  Ring points;
  double start = 0.0;  // boundary positions of its first and last points
  double end = 0.0;
};

// Sea rings from the pieces (each with the water on its right), joined clockwise along the
// box; nothing when the pieces' ends and starts do not alternate along it.
std::optional<std::vector<Ring>> close_along_box(const std::vector<Crossing>& pieces, const BBox& box) {
  struct Event {
    double at;
    int type;  // 0 end, 1 start: at a tie a piece ends before the next one starts
    std::size_t piece;
  };
  std::vector<Event> events;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    events.push_back({pieces[i].end, 0, i});
    events.push_back({pieces[i].start, 1, i});
  }
  std::sort(events.begin(), events.end(),
            [](const Event& a, const Event& b) { return a.at != b.at ? a.at < b.at : a.type < b.type; });
  std::vector<std::size_t> next(pieces.size());
  for (std::size_t k = 0; k < events.size(); ++k) {
    const auto& here = events[k];
    const auto& after = events[(k + 1) % events.size()];
    if (here.type == after.type) return std::nullopt;
    if (here.type == 0) next[here.piece] = after.piece;
  }
  std::vector<Ring> rings;
  std::vector<bool> done(pieces.size(), false);
  for (std::size_t first = 0; first < pieces.size(); ++first) {
    if (done[first]) continue;
    Ring ring;
    std::size_t i = first;
    do {
      done[i] = true;
      for (LonLat p : pieces[i].points) push_point(ring, p);
      add_corners(ring, pieces[i].end, pieces[next[i]].start, box);
      i = next[i];
    } while (!done[i]);
    if (ring.size() >= 2 && same(ring.front(), ring.back())) ring.pop_back();
    if (ring.size() >= 3) rings.push_back(std::move(ring));
  }
  return rings;
}

Ring counter_clockwise(Ring ring) {
  if (signed_area2(ring) < 0.0) std::reverse(ring.begin(), ring.end());
  return ring;
}

Ring clockwise(Ring ring) {
  if (signed_area2(ring) > 0.0) std::reverse(ring.begin(), ring.end());
  return ring;
}

}  // namespace

double signed_area2(const std::vector<geo::LonLat>& ring) {
  double sum = 0.0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const auto& a = ring[i];
    const auto& b = ring[(i + 1) % n];
    sum += (a.lon - b.lon) * (a.lat + b.lat);
  }
  return sum;
}

bool ring_contains(const std::vector<geo::LonLat>& ring, geo::LonLat p) {
  bool inside = false;
  for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a.lat > p.lat) != (b.lat > p.lat) && p.lon < a.lon + (p.lat - a.lat) * (b.lon - a.lon) / (b.lat - a.lat))
      inside = !inside;
  }
  return inside;
}

CoastlineSea sea_from_coastlines(const std::vector<CoastlineWay>& ways, const geo::BBox& box, double snap_fraction) {
  CoastlineSea out;
  const auto chains = join_ways(ways);
  out.chains = chains.size();
  const double width = box.max_lon - box.min_lon, height = box.max_lat - box.min_lat;
  if (chains.empty() || box.empty() || !(width > 0.0) || !(height > 0.0)) return out;
  const double snap = snap_fraction * std::max(width, height);

  std::vector<Crossing> crossings;
  std::vector<Ring> islands, lagoons;  // closed chains inside the box: land inside, water inside
  std::size_t open_chains = 0;
  for (const auto& chain : chains) {
    if (chain.closed() &&
        std::all_of(chain.points.begin(), chain.points.end(), [&](LonLat p) { return box.contains(p); })) {
      Ring ring(chain.points.begin(), chain.points.end() - 1);
      if (ring.size() < 3) continue;
      if (signed_area2(ring) > 0.0) {
        islands.push_back(std::move(ring));
        ++out.islands;
      } else {
        lagoons.push_back(std::move(ring));
      }
      continue;
    }
    Ring line = chain.points;
    if (chain.closed()) {  // a ring across the box: start it outside, so every piece is cut at both ends
      line.pop_back();
      const auto outside = std::find_if(line.begin(), line.end(), [&](LonLat p) { return !box.contains(p); });
      std::rotate(line.begin(), outside, line.end());
      line.push_back(line.front());
    }
    auto pieces = clip_polyline(line, box);
    if (pieces.empty()) continue;  // wholly outside the box
    ++open_chains;
    bool reaches = true;
    for (const auto& piece : pieces) {
      if (!piece.start_cut && distance_to_boundary(piece.points.front(), box) > snap) reaches = false;
      if (!piece.end_cut && distance_to_boundary(piece.points.back(), box) > snap) reaches = false;
    }
    if (!reaches) {
      ++out.broken_chains;
      continue;
    }
    for (auto& piece : pieces) {
      // Cut ends move onto the side they lie on (up to rounding); own ends get a segment to it.
      Crossing crossing;
      crossing.points = std::move(piece.points);
      const LonLat first = onto_boundary(crossing.points.front(), box);
      const LonLat last = onto_boundary(crossing.points.back(), box);
      if (piece.start_cut)
        crossing.points.front() = first;
      else if (!same(first, crossing.points.front()))
        crossing.points.insert(crossing.points.begin(), first);
      if (piece.end_cut)
        crossing.points.back() = last;
      else
        push_point(crossing.points, last);
      crossing.start = boundary_param(crossing.points.front(), box);
      crossing.end = boundary_param(crossing.points.back(), box);
      crossings.push_back(std::move(crossing));
    }
  }

  std::vector<Ring> outers;
  if (out.broken_chains == 0 && !crossings.empty()) {
    auto rings = close_along_box(crossings, box);
    if (rings) {
      for (auto& ring : *rings) outers.push_back(counter_clockwise(std::move(ring)));
    } else {
      out.broken_chains = open_chains;  // drawn the wrong way round somewhere: none is usable
    }
  }
  for (auto& ring : lagoons) outers.push_back(counter_clockwise(std::move(ring)));
  if (open_chains == 0) {
    // No coastline crosses the box: the box is sea around the islands that are not in a lagoon.
    const bool open_sea = std::any_of(islands.begin(), islands.end(), [&](const Ring& island) {
      return std::none_of(lagoons.begin(), lagoons.end(),
                          [&](const Ring& lagoon) { return ring_contains(lagoon, island.front()); });
    });
    if (open_sea) outers.push_back({corner(3, box), corner(2, box), corner(1, box), corner(0, box)});
  }

  for (auto& outer : outers) out.seas.push_back({std::move(outer), {}});
  for (auto& island : islands) {
    geo::Polygon* around = nullptr;
    double around_area = 0.0;
    for (auto& sea : out.seas) {
      const double area = std::abs(signed_area2(sea.outer));
      if ((!around || area < around_area) && ring_contains(sea.outer, island.front())) {
        around = &sea;
        around_area = area;
      }
    }
    if (around) around->holes.push_back(clockwise(std::move(island)));
  }
  return out;
}

}  // namespace tourmap::load
