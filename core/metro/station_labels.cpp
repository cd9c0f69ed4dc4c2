#include "metro/station_labels.hpp"

#include "metro/label_choice.hpp"
#include "metro/label_font.hpp"
#include "metro/segment_geometry.hpp"
#include "util/stop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <unordered_map>

namespace tourmap::metro {

double LabelStyle::symbol_px(double mean_edge_px) const {
  return std::clamp(symbol_share * mean_edge_px, symbol_min_px, symbol_max_px);
}

double label_width_px(const std::string& name, const LabelStyle& style) { return label_text_em(name) * style.font_px; }

namespace {

struct Rect {
  double x0, y0, x1, y1;  // layout units, y up
};


double rect_point_distance(const Rect& r, XY p) {
  const double dx = std::max({r.x0 - p.x, 0.0, p.x - r.x1}), dy = std::max({r.y0 - p.y, 0.0, p.y - r.y1});
  return std::hypot(dx, dy);
}

// Does the segment pass through the rectangle? (Liang-Barsky clipping.)
bool crosses(const Rect& r, XY a, XY b) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {a.x - r.x0, r.x1 - a.x, a.y - r.y0, r.y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

// Distance between a rectangle and a segment (0 when they meet).
double rect_segment_distance(const Rect& r, XY a, XY b) {
  if (crosses(r, a, b)) return 0;
  const std::array<XY, 4> c = {XY{r.x0, r.y0}, XY{r.x1, r.y0}, XY{r.x1, r.y1}, XY{r.x0, r.y1}};
  double best = std::min(rect_point_distance(r, a), rect_point_distance(r, b));
  for (const auto& corner : c) best = std::min(best, point_segment_distance(corner, a, b));
  return best;
}

Rect expanded(const Rect& r, double d) { return {r.x0 - d, r.y0 - d, r.x1 + d, r.y1 + d}; }

// A label's leader in layout units (none: `on` false).
struct Leader {
  XY a{0, 0}, b{0, 0};
  bool on = false;
};

Rect bounds_with(const Rect& r, const Leader& l) {
  if (!l.on) return r;
  return {std::min({r.x0, l.a.x, l.b.x}), std::min({r.y0, l.a.y, l.b.y}), std::max({r.x1, l.a.x, l.b.x}),
          std::max({r.y1, l.a.y, l.b.y})};
}

bool segments_meet(XY a, XY b, XY c, XY d) { return segment_contact(a, b, c, d, 0).kind != SegmentContact::none; }

double segment_distance(XY a, XY b, XY c, XY d) {
  if (segments_meet(a, b, c, d)) return 0;
  return std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d), point_segment_distance(c, a, b),
                   point_segment_distance(d, a, b)});
}

// A uniform grid over the layout's bounds, cells in one array (a hash of cells was a tenth of
// the placement's time): items by the cells their boxes cover; boxes beyond the bounds count
// in the border cells.
class Grid {
 public:
  Grid() = default;
  Grid(const Rect& bounds, double cell) : bounds_(bounds), cell_(cell > 0 ? cell : 1) {
    cols_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((bounds.x1 - bounds.x0) / cell_)) + 1);
    rows_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((bounds.y1 - bounds.y0) / cell_)) + 1);
    cells_.assign(static_cast<std::size_t>(cols_ * rows_), {});
  }
  void clear() {
    for (auto& c : cells_) c.clear();
  }
  void add(const Rect& box, int item) {
    for_cells(box, [&](std::size_t cell) {
      cells_[cell].push_back(item);
      return false;
    });
  }
  template <typename F>
  void near(const Rect& box, F&& f) const {
    for_cells(box, [&](std::size_t cell) {
      for (int item : cells_[cell]) f(item);
      return false;
    });
  }
  // Whether `f` holds for an item near `box` (asked no further once it does).
  template <typename F>
  bool any(const Rect& box, F&& f) const {
    return for_cells(box, [&](std::size_t cell) {
      for (int item : cells_[cell])
        if (f(item)) return true;
      return false;
    });
  }

 private:
  std::int64_t col(double x) const { return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x - bounds_.x0) / cell_)), 0, cols_ - 1); }
  std::int64_t row(double y) const { return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((y - bounds_.y0) / cell_)), 0, rows_ - 1); }
  // Calls f on the cells under box until it returns true; whether one did.
  template <typename F>
  bool for_cells(const Rect& box, F&& f) const {
    if (cells_.empty()) return false;
    const auto c0 = col(box.x0), c1 = col(box.x1), r0 = row(box.y0), r1 = row(box.y1);
    for (auto r = r0; r <= r1; ++r)
      for (auto c = c0; c <= c1; ++c)
        if (f(static_cast<std::size_t>(r * cols_ + c))) return true;
    return false;
  }
  Rect bounds_{0, 0, 0, 0};
  double cell_ = 1;
  std::int64_t cols_ = 0, rows_ = 0;
  std::vector<std::vector<int>> cells_;
};

struct Segment {
  XY a, b;
  std::size_t lines;
  std::uint32_t edge;
};

// The eight sides, counter-clockwise from east, and how much each reads worse than east; a
// label slid off a line along its side, or on two lines, reads a little worse again.
constexpr std::array<double, 8> kPlaceCost = {0.0, 0.3, 0.6, 0.4, 0.1, 0.45, 0.65, 0.35};
constexpr double kSlideCost = 0.15, kTwoLineCost = 0.25, kFarCost = 0.2;
constexpr double kSameSideBonus = 0.5;  // the side a neighbour on the line took
// Off the sixteen places (any angle: reads a little worse), and each leader step further out.
constexpr double kRingCost = 2.0, kLeaderStepCost = 1.5;

// A name's text: its width, and where it breaks onto two lines (0: it does not).
struct Text {
  double width;
  std::size_t split;
};

// The label of text `t` on side p (slid by `slide` lanes of `lane` px off the line along that
// side), around a symbol reaching rho px, in px from the point.
PlacedLabel place_box(std::uint32_t node, int p, int slide, const Text& t, double rho, double lane, const LabelStyle& s) {
  const double w = t.width, h = s.height_px + (t.split ? s.line_px : 0), d = rho * std::sqrt(0.5);
  PlacedLabel l{node, p, slide, 0, 0, 0, 0, 0, 0, 's', t.split};
  l.font_px = s.font_px;
  // Slid boxes clear the line along their side: beside it rather than centred on it.
  const double beside = lane + (slide < 0 ? h : 0);
  switch (p) {
    case 0: l.x0 = rho, l.y0 = slide == 0 ? -h / 2 : slide < 0 ? -beside : lane; break;
    case 1: l.x0 = d, l.y0 = -d - h; break;
    case 2: l.x0 = slide == 0 ? -w / 2 : slide < 0 ? -lane - w : lane, l.y0 = -rho - h; break;
    case 3: l.x0 = -d - w, l.y0 = -d - h; break;
    case 4: l.x0 = -rho - w, l.y0 = slide == 0 ? -h / 2 : slide < 0 ? -beside : lane; break;
    case 5: l.x0 = -d - w, l.y0 = d; break;
    case 6: l.x0 = slide == 0 ? -w / 2 : slide < 0 ? -lane - w : lane, l.y0 = rho; break;
    default: l.x0 = d, l.y0 = d; break;
  }
  l.anchor = (p == 2 || p == 6) ? (slide == 0 ? 'm' : slide < 0 ? 'e' : 's') : (p >= 3 && p <= 5) ? 'e' : 's';
  l.x1 = l.x0 + w;
  l.y1 = l.y0 + h;
  l.text_x = l.anchor == 's' ? l.x0 : l.anchor == 'e' ? l.x1 : (l.x0 + l.x1) / 2;
  // Each line centred in its share of the box: the baseline 0.35 em below the share's middle
  // (DejaVu's capitals are 0.73 em tall).
  l.text_y = l.y0 + s.height_px / 2 + 0.35 * s.font_px;
  return l;
}

// The label of text `t` touching, at `angle_deg` (counter-clockwise from east), the circle of
// radius `ring` px around the point, `extra` px further out: a box whose corner meets the
// circle on the diagonals and that slides along it between them (as the sixteen places do, but
// at any angle). Beyond the ring (`extra` > 0) a leader joins it to the symbol's rim at `reach`.
PlacedLabel ring_box(std::uint32_t node, double angle_deg, double extra, const Text& t, double ring, double reach,
                     const LabelStyle& s) {
  const double w = t.width, h = s.height_px + (t.split ? s.line_px : 0);
  const double a = angle_deg * std::numbers::pi / 180, fx = std::cos(a), fy = -std::sin(a), r = ring + extra;
  // Beyond |f| = 0.38 (about 22.5 degrees off an axis) the box sits wholly on that side.
  constexpr double kSide = 0.38;
  const double sx = std::clamp(fx / kSide, -1.0, 1.0), sy = std::clamp(fy / kSide, -1.0, 1.0);
  const int side = static_cast<int>(std::lround(angle_deg / 45.0)) % 8;
  PlacedLabel l{node, side, 0, 0, 0, 0, 0, 0, 0, 's', t.split};
  l.font_px = s.font_px;
  l.x0 = r * fx + (sx - 1) * w / 2;
  l.y0 = r * fy + (sy - 1) * h / 2;
  l.x1 = l.x0 + w;
  l.y1 = l.y0 + h;
  l.anchor = sx >= 1 ? 's' : sx <= -1 ? 'e' : 'm';
  l.text_x = l.anchor == 's' ? l.x0 : l.anchor == 'e' ? l.x1 : (l.x0 + l.x1) / 2;
  l.text_y = l.y0 + s.height_px / 2 + 0.35 * s.font_px;
  if (extra > 0) {
    // From the rim towards the box's nearest point.
    const double ex = std::clamp(0.0, l.x0, l.x1), ey = std::clamp(0.0, l.y0, l.y1), len = std::hypot(ex, ey);
    l.leader = true;
    l.lx0 = ex / len * reach, l.ly0 = ey / len * reach, l.lx1 = ex, l.ly1 = ey;
  }
  return l;
}

// Where a name of several words breaks most evenly onto two lines (0: one word).
Text text_of(const std::string& name, const LabelStyle& style, bool two_lines) {
  const double whole = label_width_px(name, style);
  if (!two_lines) return {whole, 0};
  Text best{whole, 0};
  for (std::size_t i = 1; i + 1 < name.size(); ++i) {
    // After a space (dropped) or a hyphen (kept on the first line: "Mendelssohn-/Bartholdy-Park").
    const bool hyphen = name[i] == '-' && name[i - 1] != ' ' && name[i + 1] != ' ';  // not " - "
    if (name[i] != ' ' && !hyphen) continue;
    const std::size_t first = name[i] == ' ' ? i : i + 1;
    const double w = std::max(label_width_px(name.substr(0, first), style), label_width_px(name.substr(i + 1), style));
    if (w < best.width) best = {w, i + 1};
  }
  return best;
}

class Placer {
 public:
  Placer(const LayoutGraph& g, const Layout& L, const StationLabelInput& in, const LabelStyle& style)
      : g_(g), L_(L), style_(style), small_style_(style), neighbours_(g.pos.size()), degree_(g.pos.size(), 0) {
    // The smaller type: the same box proportions at small_font_px.
    const double ratio = style.small_font_px > 0 ? std::min(1.0, style.small_font_px / style.font_px) : 1.0;
    small_style_.font_px *= ratio;
    small_style_.height_px *= ratio;
    small_style_.line_px *= ratio;
    double total = 0;
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      const auto& path = L.paths[e];
      const std::size_t n = e < in.lines.size() ? std::max<std::size_t>(1, in.lines[e]) : 1;
      for (std::size_t i = 1; i < path.size(); ++i) {
        segments_.push_back({path[i - 1], path[i], n, e});
        total += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
      }
      auto [u, v] = g.edges[e];
      neighbours_[u].push_back(v);
      neighbours_[v].push_back(u);
      ++degree_[u], ++degree_[v];
      for (auto x : {u, v}) bundle_[x] = std::max(bundle_[x], n);
    }
    mean_ = g.edges.empty() ? 1.0 : total / g.edges.size();
    if (!(mean_ > 0)) mean_ = 1;
    grid_cell_ = mean_;
    Rect bounds{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const auto& p : L.pos) bounds = {std::min(bounds.x0, p.x), std::min(bounds.y0, p.y), std::max(bounds.x1, p.x), std::max(bounds.y1, p.y)};
    for (const auto& s : segments_)
      for (XY p : {s.a, s.b}) bounds = {std::min(bounds.x0, p.x), std::min(bounds.y0, p.y), std::max(bounds.x1, p.x), std::max(bounds.y1, p.y)};
    if (!(bounds.x0 <= bounds.x1)) bounds = {0, 0, 0, 0};
    bounds_ = bounds;
    Grid segment_grid(bounds_, grid_cell_);
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const auto& s = segments_[i];
      segment_grid.add({std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y), std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)},
                       static_cast<int>(i));
    }
    segment_grid_ = std::move(segment_grid);
    Grid symbol_grid(bounds_, grid_cell_);
    for (std::uint32_t v = 0; v < g.pos.size(); ++v) symbol_grid.add({L.pos[v].x, L.pos[v].y, L.pos[v].x, L.pos[v].y}, static_cast<int>(v));
    symbol_grid_ = std::move(symbol_grid);
    for (const auto& [v, n] : bundle_) max_lines_ = std::max(max_lines_, n);
    one_line_.resize(g.pos.size(), Text{0, 0});
    two_lines_.resize(g.pos.size(), Text{0, 0});
    small_one_line_.resize(g.pos.size(), Text{0, 0});
    small_two_lines_.resize(g.pos.size(), Text{0, 0});
    // Interchanges and termini first, then by the caller's priority.
    for (std::uint32_t v = 0; v < g.pos.size(); ++v)
      if (v < in.names.size() && !in.names[v].empty()) {
        order_.push_back(v);
        one_line_[v] = text_of(in.names[v], style, false);
        two_lines_[v] = text_of(in.names[v], style, true);
        small_one_line_[v] = text_of(in.names[v], small_style_, false);
        small_two_lines_[v] = text_of(in.names[v], small_style_, true);
      }
    std::stable_sort(order_.begin(), order_.end(), [&](auto a, auto b) {
      const auto key = [&](std::uint32_t v) {
        const bool first = bundle_.count(v) && (bundle_.at(v) > 1 || degree_[v] != 2);
        return std::pair{first ? 1 : 0, v < in.priority.size() ? in.priority[v] : 0.0};
      };
      return key(a) > key(b);
    });
  }

  double mean_edge() const { return mean_; }

  LabelScale place(double mean_edge_px, double symbol_px, double next_mean_edge_px, const LabelScale* before) {
    LabelScale out;
    out.mean_edge_px = mean_edge_px;
    out.px_per_unit = mean_edge_px / mean_;
    out.symbol_px = symbol_px;
    scale_ = out.px_per_unit;
    ring_ = mean_edge_px >= style_.ring_min_mean_edge_px;
    symbol_px_ = symbol_px;
    t_hi_ = 1 / scale_;
    t_lo_ = std::isfinite(next_mean_edge_px) ? mean_ / next_mean_edge_px : 0.0;
    labels_.clear();
    candidate_.clear();
    label_rects_.clear();
    leaders_.clear();
    placed_.assign(g_.pos.size(), -1);
    small_.assign(g_.pos.size(), 0);
    clear_memo_.assign(g_.pos.size() * 2 * kCandidates, -1);
    if (label_grid_cells_ != grid_cell_) {
      label_grid_ = Grid(bounds_, grid_cell_);
      label_grid_cells_ = grid_cell_;
    } else {
      label_grid_.clear();
    }
    // Each station's place in the earlier placement, or the place it wanted there.
    std::vector<int> hint(g_.pos.size(), -1);
    std::vector<char> hint_small(g_.pos.size(), 0);
    if (before) {
      for (const auto* list : {&before->wanted, &before->labels})
        for (const auto& l : *list)
          if (l.node < hint.size() && l.candidate >= 0 && l.candidate < kCandidates) {
            hint[l.node] = l.candidate;
            hint_small[l.node] = l.font_px < style_.font_px;
          }
    }
    std::vector<std::uint32_t> left_out;
    // The request's deadline or client stops the placement (util/stop.hpp): on a dense network
    // the ring and the repair try hundreds of places per station left out.
    for (auto v : order_) {
      util::check_stop();
      small_[v] = hint_small[v] && ring_;
      if (hint[v] >= 0 && valid(v, hint[v]) && free(v, hint[v])) {
        put(v, hint[v]);
        continue;
      }
      small_[v] = 0;
      if (!place_best(v)) left_out.push_back(v);
    }
    // Repair: a station left out may take a place held by labels in its way that can move.
    for (auto v : left_out) {
      util::check_stop();
      repair(v);
    }
    // Last, from the ring's zoom on: the names still left out in smaller type (as map makers
    // set the names of a crowded centre), in a free place or by moving labels in the way.
    if (ring_ && small_style_.font_px < style_.font_px)
      for (auto v : left_out) {
        if (placed_[v] >= 0) continue;
        util::check_stop();
        small_[v] = 1;
        if (!place_best(v) && !repair(v)) small_[v] = 0;
      }
    // Then several names moved at once, exactly, around each one still left out: at most
    // kExactRepairs per zoom, the first by priority (each costs 5-100 ms; London's centre
    // leaves 10 out at 75 px, London drawn as it lies 33).
    if (ring_ && style_.exact_group > 0) {
      std::size_t tried = 0;
      for (auto v : left_out)
        if (placed_[v] < 0 && tried++ < kExactRepairs) exact_repair(v);
    }
    std::size_t unlabelled = 0;
    for (auto v : left_out)
      if (placed_[v] < 0) {
        ++unlabelled;
        if (!has_room(v)) ++out.no_room;
      }
    for (const auto& l : labels_)
      if (l.node != kRemoved) {
        out.labels.push_back(l);
        if (l.leader) ++out.leaders;
        if (l.font_px < style_.font_px) ++out.small;
      }
    // The place each one left out wants, in the usual type and in the smaller one.
    if (ring_)
      for (auto v : left_out)
        if (placed_[v] < 0) {
          if (const int c = roomiest_place(v); c >= 0) out.wanted.push_back(candidate(v, c));
          if (small_style_.font_px >= style_.font_px) continue;
          small_[v] = 1;
          if (const int c = roomiest_place(v); c >= 0) out.wanted.push_back(candidate(v, c));
          small_[v] = 0;
        }
    // And each one's places in either type by the room they need, for a layout making room
    // for one name at a time.
    if (ring_)
      for (auto v : left_out)
        if (placed_[v] < 0) {
          std::vector<std::pair<double, PlacedLabel>> places;
          for (const char small : {0, 1}) {
            if (small && small_style_.font_px >= style_.font_px) continue;
            small_[v] = small;
            for (int c = 0; c < kPlaces; ++c)
              if (valid(v, c) && !far(c))
                if (const double need = room_needed(v, c); std::isfinite(need)) places.push_back({need, candidate(v, c)});
          }
          small_[v] = 0;
          std::stable_sort(places.begin(), places.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
          for (std::size_t i = 0; i < places.size() && i < kAlternatives; ++i) out.alternatives.push_back(places[i].second);
        }
    out.unlabelled = unlabelled;
    return out;
  }

 private:
  static constexpr std::uint32_t kRemoved = std::numeric_limits<std::uint32_t>::max();

  // How far v's symbol reaches, px: its radius, and half the widest bundle through it.
  double reach_px(std::uint32_t v) const {
    const auto it = bundle_.find(v);
    const std::size_t n = it == bundle_.end() ? 1 : it->second;
    return symbol_px_ + (static_cast<double>(n) - 1) / 2 * style_.line_spacing_px;
  }

  // A label's box and leader in layout units at `t` layout units per px (1 / scale_ at this
  // placement's zoom).
  Rect rect_at(std::uint32_t v, const PlacedLabel& l, double t) const {
    const XY p = L_.pos[v];
    return {p.x + l.x0 * t, p.y - l.y1 * t, p.x + l.x1 * t, p.y - l.y0 * t};
  }
  Leader leader_at(std::uint32_t v, const PlacedLabel& l, double t) const {
    if (!l.leader) return {};
    const XY p = L_.pos[v];
    return {{p.x + l.lx0 * t, p.y - l.ly0 * t}, {p.x + l.lx1 * t, p.y - l.ly1 * t}, true};
  }
  Rect rect_of(std::uint32_t v, const PlacedLabel& l) const { return rect_at(v, l, 1 / scale_); }
  Leader leader_of(std::uint32_t v, const PlacedLabel& l) const { return leader_at(v, l, 1 / scale_); }
  // Everything a label covers from this zoom to the next: boxes keep their size in px while
  // the stations spread, so in layout units a label shrinks towards its station.
  Rect swept(std::uint32_t v, const PlacedLabel& l) const {
    const XY p = L_.pos[v];
    const Rect r = bounds_with(rect_of(v, l), leader_of(v, l));
    return {std::min(r.x0, p.x), std::min(r.y0, p.y), std::max(r.x1, p.x), std::max(r.y1, p.y)};
  }

  // Whether the boxes of label l (of v) and label o (of u) come within the names' gap of each
  // other at any zoom from this placement's to the next one's (t from t_hi_ down to t_lo_). Per
  // axis the boxes are [P + a0 t, P + a1 t]; they overlap where P_a - P_b < (b1 - a0) t and
  // P_b - P_a < (a1 - b0) t, each a half-line in t.
  bool boxes_meet(std::uint32_t v, const PlacedLabel& l, std::uint32_t u, const PlacedLabel& o) const {
    const XY pa = L_.pos[v], pb = L_.pos[u];
    const double g = style_.label_gap_px;
    double lo = t_lo_, hi = t_hi_;
    // c < m t: t > c / m (m > 0), t < c / m (m < 0), always or never (m = 0).
    const auto keep = [&](double c, double m) {
      if (m > 0) lo = std::max(lo, c / m);
      else if (m < 0) hi = std::min(hi, c / m);
      else if (c >= 0) hi = -1;
    };
    // x: a0 = x0 - g, a1 = x1 + g; y (up): a0 = -y1 - g, a1 = -y0 + g.
    keep(pa.x - pb.x, o.x1 - (l.x0 - g));
    keep(pb.x - pa.x, (l.x1 + g) - o.x0);
    keep(pa.y - pb.y, -o.y0 - (-l.y1 - g));
    keep(pb.y - pa.y, (-l.y0 + g) - (-o.y1));
    return lo < hi * (1 - 1e-9);
  }

  // Whether two labels (l of v, o of u) clash: their boxes come within the names' gap (two names
  // touching read as one) at any zoom until the next placement's, or a leader of one crosses
  // the other or its leader (leaders: checked at both ends of the zooms and between).
  bool labels_meet(std::uint32_t v, const PlacedLabel& l, std::uint32_t u, const PlacedLabel& o) const {
    if (boxes_meet(v, l, u, o)) return true;
    if (!l.leader && !o.leader) return false;
    const double mid = (t_lo_ > 0 ? t_lo_ : t_hi_ / 4);
    for (double t : {t_hi_, (t_hi_ + mid) / 2, mid}) {
      const double g = style_.label_gap_px * t;
      const Rect r = expanded(rect_at(v, l, t), g), other_r = expanded(rect_at(u, o, t), g);
      const Leader lead = leader_at(v, l, t), other = leader_at(u, o, t);
      if ((other.on && crosses(r, other.a, other.b)) || (lead.on && crosses(other_r, lead.a, lead.b)) ||
          (lead.on && other.on && segments_meet(lead.a, lead.b, other.a, other.b)))
        return true;
    }
    return false;
  }

  // Candidate c < kPlaces: c % 16 the place (the 8 sides, then E, W, N, S slid to one side and
  // to the other); (c / 16) % 2 two lines of text; c / 32 half a line further out (off the
  // lines of an interchange whose diagonals pass close to the nearer places). Beyond: the ring,
  // kRingAngles angles, on one line or two, at kRingLevels distances (0: touching the places'
  // ring; then leader steps further out). The ring is tried only after every place.
  // Leaders up to 7 steps (56 px): with 3, London's centre kept 15 of 302 names out at 75 px
  // (with 7: 10 before room is made, 4 after); tried last, so they cost only where needed.
  static constexpr int kPlaces = 64, kRingAngles = 48, kRingLevels = 8;
  static constexpr int kCandidates = kPlaces + kRingAngles * 2 * kRingLevels;
  static constexpr std::size_t kAlternatives = 6;  // places per station left out, for room one at a time
  static bool on_ring(int c) { return c >= kPlaces; }
  static int ring_level(int c) { return on_ring(c) ? (c - kPlaces) / (2 * kRingAngles) : 0; }
  static bool two_line(int c) { return on_ring(c) ? (c - kPlaces) / kRingAngles % 2 == 1 : (c / 16) % 2 == 1; }
  static bool far(int c) { return !on_ring(c) && c >= 32; }
  static double ring_angle_deg(int c) { return (c - kPlaces) % kRingAngles * (360.0 / kRingAngles); }
  PlacedLabel candidate(std::uint32_t v, int c) const {
    const bool small = small_[v] != 0;
    const LabelStyle& st = small ? small_style_ : style_;
    const Text& t = two_line(c) ? (small ? small_two_lines_[v] : two_lines_[v]) : (small ? small_one_line_[v] : one_line_[v]);
    const double ring = reach_px(v) + style_.gap_px;
    if (on_ring(c)) {
      auto l = ring_box(v, ring_angle_deg(c), ring_level(c) * style_.leader_step_px, t, ring, reach_px(v), st);
      l.candidate = c;
      return l;
    }
    const int place = c % 16;
    const int side = candidate_side(c);
    const int slide = place < 8 ? 0 : (place % 2 ? 1 : -1);
    // The lane a slid label keeps clear of: half the widest bundle through v, and clearance.
    const auto it = bundle_.find(v);
    const double n = it == bundle_.end() ? 1.0 : static_cast<double>(it->second);
    const double lane = n * style_.line_spacing_px / 2 + style_.clearance_px + 1;
    auto l = place_box(v, side, slide, t, ring + (far(c) ? st.height_px / 2 : 0), lane, st);
    l.candidate = c;
    return l;
  }
  bool has_two_lines(std::uint32_t v) const { return two_lines_[v].split != 0; }
  bool valid(std::uint32_t v, int c) const { return (!two_line(c) || has_two_lines(v)) && (ring_ || !on_ring(c)); }
  double candidate_cost(std::uint32_t v, int c) const {
    const auto l = candidate(v, c);
    const double ring = on_ring(c) ? kRingCost + ring_level(c) * kLeaderStepCost : 0;
    return cost(v, c) + ring + (l.slide != 0 ? kSlideCost : 0) + (two_line(c) ? kTwoLineCost : 0) + (far(c) ? kFarCost : 0);
  }

  // A leader keeps clear of lines and of every symbol but its own.
  bool leader_clear(std::uint32_t v, const Leader& l) const {
    if (!l.on) return true;
    const double widest = (static_cast<double>(max_lines()) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
    const Rect query = expanded(bounds_with({l.a.x, l.a.y, l.a.x, l.a.y}, l), widest);
    const bool on_a_line = segment_grid_.any(query, [&](int i) {
      const auto& s = segments_[static_cast<std::size_t>(i)];
      const double half = (static_cast<double>(s.lines) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
      return segment_distance(l.a, l.b, s.a, s.b) < half;
    });
    if (on_a_line) return false;
    const double reach = (symbol_px_ + static_cast<double>(max_lines()) * style_.line_spacing_px + style_.clearance_px) / scale_;
    return !symbol_grid_.any(expanded(query, reach), [&](int i) {
      const auto u = static_cast<std::uint32_t>(i);
      return u != v && point_segment_distance(L_.pos[u], l.a, l.b) < (reach_px(u) + style_.clearance_px) / scale_;
    });
  }

  // Clear of lines and symbols (labels are checked separately); stops at the first it meets.
  bool clear_of_map(const Rect& r) const {
    const double widest = (static_cast<double>(max_lines()) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
    const Rect query{r.x0 - widest, r.y0 - widest, r.x1 + widest, r.y1 + widest};
    const bool on_a_line = segment_grid_.any(query, [&](int i) {
      const auto& s = segments_[static_cast<std::size_t>(i)];
      const double half = (static_cast<double>(s.lines) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
      // Boxes apart by more than the half width first: most segments near a label are.
      if (std::max(s.a.x, s.b.x) + half <= r.x0 || std::min(s.a.x, s.b.x) - half >= r.x1 ||
          std::max(s.a.y, s.b.y) + half <= r.y0 || std::min(s.a.y, s.b.y) - half >= r.y1)
        return false;
      return rect_segment_distance(r, s.a, s.b) < half;
    });
    if (on_a_line) return false;
    const double reach = (symbol_px_ + static_cast<double>(max_lines()) * style_.line_spacing_px + style_.clearance_px) / scale_;
    return !symbol_grid_.any({r.x0 - reach, r.y0 - reach, r.x1 + reach, r.y1 + reach}, [&](int i) {
      const auto v = static_cast<std::uint32_t>(i);
      return rect_point_distance(r, L_.pos[v]) < (reach_px(v) + style_.clearance_px) / scale_;
    });
  }

  std::size_t max_lines() const { return max_lines_; }

  // Placed labels (ids into labels_) that clash with label l of v (labels_meet).
  std::vector<int> label_conflicts(std::uint32_t v, const PlacedLabel& l) const {
    const double gap = style_.label_gap_px / scale_;
    std::vector<int> out;
    label_grid_.near(expanded(swept(v, l), gap), [&](int i) {
      const auto& o = labels_[static_cast<std::size_t>(i)];
      if (o.node == kRemoved || std::find(out.begin(), out.end(), i) != out.end()) return;
      if (labels_meet(v, l, o.node, o)) out.push_back(i);
    });
    return out;
  }

  // The place's own cost, less a bonus when a neighbour on the line is labelled the same way
  // (the same candidate: the same side and slide), half of it for the same side alone.
  double cost(std::uint32_t v, int c) const {
    const int p = candidate_side(c);
    double cost = kPlaceCost[static_cast<std::size_t>(p)];
    double bonus = 0;
    for (auto w : neighbours_[v]) {
      if (placed_[w] < 0) continue;
      const int other = candidate_[static_cast<std::size_t>(placed_[w])];
      if (!on_ring(other) && !on_ring(c) && other % 16 == c % 16) bonus = std::max(bonus, kSameSideBonus);
      else if (candidate_side(other) == p) bonus = std::max(bonus, kSameSideBonus / 2);
    }
    return cost - bonus;
  }
  static int candidate_side(int c) {
    if (on_ring(c)) return static_cast<int>(std::lround(ring_angle_deg(c) / 45.0)) % 8;
    const int place = c % 16;
    return place < 8 ? place : 2 * ((place - 8) / 2);
  }

  // v's candidates in [from, to), cheapest first.
  std::vector<int> ranked_candidates(std::uint32_t v, int from, int to) const {
    std::vector<std::pair<double, int>> ranked;
    for (int c = from; c < to; ++c) {
      if (!valid(v, c)) continue;
      ranked.push_back({candidate_cost(v, c), c});
    }
    std::sort(ranked.begin(), ranked.end());
    std::vector<int> out;
    for (auto [cost, c] : ranked) out.push_back(c);
    return out;
  }

  bool free(std::uint32_t v, int c, int except_label = -1) const {
    if (!clear_of_map(v, c)) return false;
    const auto l = candidate(v, c);
    auto conflicts = label_conflicts(v, l);
    conflicts.erase(std::remove(conflicts.begin(), conflicts.end(), except_label), conflicts.end());
    return conflicts.empty();
  }

  // Whether candidate c of v is clear of lines and symbols (the names aside). Lines and symbols
  // stay put while one zoom's names are placed, so each answer is kept (clear_memo_): the
  // repairs ask again and again for the same places (London's exact repairs at 75 px scan up to
  // 24 names x 832 places each; under ASan that made the background room job miss its budget).
  bool clear_of_map(std::uint32_t v, int c) const {
    auto& memo = clear_memo_[(static_cast<std::size_t>(v) * 2 + (small_[v] ? 1 : 0)) * kCandidates + static_cast<std::size_t>(c)];
    if (memo < 0) {
      const auto l = candidate(v, c);
      memo = clear_of_map(rect_of(v, l)) && leader_clear(v, leader_of(v, l)) ? 1 : 0;
    }
    return memo == 1;
  }

  // The place of v (one of the sixteen, on one line or two) that the fewest lines and symbols
  // stand in, none of them v's own lines; the cheapest of those; -1 when v's lines cross all.
  int roomiest_place(std::uint32_t v) const {
    int best = -1;
    std::pair<std::size_t, double> best_key{std::numeric_limits<std::size_t>::max(), 0};
    for (int c = 0; c < kPlaces; ++c) {
      if (!valid(v, c) || far(c)) continue;
      const Rect r = rect_of(v, candidate(v, c));
      std::size_t in_the_way = 0;
      bool own = false;
      segment_grid_.near(expanded(r, widest_half()), [&](int i) {
        const auto& s = segments_[static_cast<std::size_t>(i)];
        const double half = (static_cast<double>(s.lines) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
        if (rect_segment_distance(r, s.a, s.b) >= half) return;
        const auto [a, b] = g_.edges[s.edge];
        if (a == v || b == v) own = true;
        else ++in_the_way;
      });
      if (own) continue;
      const double reach = (symbol_px_ + static_cast<double>(max_lines()) * style_.line_spacing_px + style_.clearance_px) / scale_;
      symbol_grid_.near(expanded(r, reach), [&](int i) {
        const auto u = static_cast<std::uint32_t>(i);
        if (u != v && rect_point_distance(r, L_.pos[u]) < (reach_px(u) + style_.clearance_px) / scale_) ++in_the_way;
      });
      const std::pair<std::size_t, double> key{in_the_way, candidate_cost(v, c)};
      if (key < best_key) best_key = key, best = c;
    }
    return best;
  }
  double widest_half() const {
    return (static_cast<double>(max_lines()) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
  }

  // How far, in px summed, the lines and symbols in candidate c of v would have to move out of
  // it (each along the best of the eight octilinear directions, as the layout moves them:
  // metro/station_spacing.cpp, best_separation); infinite when one of v's own lines crosses it.
  double room_needed(std::uint32_t v, int c) const {
    const Rect r = rect_of(v, candidate(v, c));
    double depth = 0;
    bool own = false;
    std::vector<int> seen;
    segment_grid_.near(expanded(r, widest_half()), [&](int i) {
      if (std::find(seen.begin(), seen.end(), i) != seen.end()) return;
      seen.push_back(i);
      const auto& s = segments_[static_cast<std::size_t>(i)];
      const double half = (static_cast<double>(s.lines) * style_.line_spacing_px / 2 + style_.clearance_px) / scale_;
      if (rect_segment_distance(r, s.a, s.b) >= half) return;
      const auto [a, b] = g_.edges[s.edge];
      if (a == v || b == v) own = true;
      else depth += depth_in(r, s.a, s.b, half);
    });
    if (own) return std::numeric_limits<double>::infinity();
    const double reach = (symbol_px_ + static_cast<double>(max_lines()) * style_.line_spacing_px + style_.clearance_px) / scale_;
    symbol_grid_.near(expanded(r, reach), [&](int i) {
      const auto u = static_cast<std::uint32_t>(i);
      const double need = (reach_px(u) + style_.clearance_px) / scale_;
      if (u != v && rect_point_distance(r, L_.pos[u]) < need) depth += depth_in(r, L_.pos[u], L_.pos[u], need);
    });
    return depth * scale_;
  }
  // How far an obstacle (points a, b: a segment, or one point) would have to move to clear
  // box r by `need`, along the best of the eight octilinear directions; 0 when it is clear.
  static double depth_in(const Rect& r, XY a, XY b, double need) {
    static constexpr double k = std::numbers::sqrt2 / 2;
    static constexpr std::array<XY, 8> dirs = {XY{1, 0}, XY{k, k}, XY{0, 1}, XY{-k, k}, XY{-1, 0}, XY{-k, -k}, XY{0, -1}, XY{k, -k}};
    const std::array<XY, 4> corners = {XY{r.x0, r.y0}, XY{r.x1, r.y0}, XY{r.x1, r.y1}, XY{r.x0, r.y1}};
    double best = -std::numeric_limits<double>::infinity();
    for (const XY w : dirs) {
      double apart = std::numeric_limits<double>::infinity();
      for (const XY c : corners)
        for (const XY p : {a, b}) apart = std::min(apart, w.x * (p.x - c.x) + w.y * (p.y - c.y));
      best = std::max(best, apart);
    }
    return std::max(0.0, need - best);
  }

  // Whether any place of v is clear of lines and symbols (the names aside).
  bool has_room(std::uint32_t v) const {
    for (int c = 0; c < kCandidates; ++c)
      if (valid(v, c) && clear_of_map(v, c)) return true;
    return false;
  }

  // The cheapest free candidate of v, or -1. Every place costs less than any ring candidate
  // (kRingCost), so the ring is ranked only when no place is free.
  int best_free(std::uint32_t v) const {
    for (int c : ranked_candidates(v, 0, kPlaces))
      if (free(v, c)) return c;
    if (!ring_) return -1;
    for (int c : ranked_candidates(v, kPlaces, kCandidates))
      if (free(v, c)) return c;
    return -1;
  }

  void put(std::uint32_t v, int c) {
    const auto l = candidate(v, c);
    const auto id = static_cast<int>(labels_.size());
    labels_.push_back(l);
    candidate_.push_back(c);
    label_rects_.push_back(rect_of(v, l));
    leaders_.push_back(leader_of(v, l));
    label_grid_.add(swept(v, l), id);
    placed_[v] = id;
  }

  void remove(int id) {
    placed_[labels_[static_cast<std::size_t>(id)].node] = -1;
    labels_[static_cast<std::size_t>(id)].node = kRemoved;
  }

  bool place_best(std::uint32_t v) {
    const int c = best_free(v);
    if (c < 0) return false;
    put(v, c);
    return true;
  }

  // v takes a place (clear of the map, cheapest first) whose only conflicts are at most
  // kMaxDisplaced labels (one in an overview, where most stations go unnamed anyway and the
  // search would cost the most) that each find another free place.
  static constexpr std::size_t kMaxDisplaced = 3;
  bool repair(std::uint32_t v) {
    const std::size_t max_displaced = ring_ ? kMaxDisplaced : 1;
    for (int p : ranked_candidates(v, 0, ring_ ? kCandidates : kPlaces)) {
      const auto l = candidate(v, p);
      const auto conflicts = label_conflicts(v, l);
      if (conflicts.empty() || conflicts.size() > max_displaced || !clear_of_map(v, p)) continue;
      std::vector<std::pair<std::uint32_t, int>> displaced;  // node, its place
      for (int other : conflicts) {
        displaced.push_back({labels_[static_cast<std::size_t>(other)].node, candidate_[static_cast<std::size_t>(other)]});
        remove(other);
      }
      put(v, p);
      std::size_t moved = 0;
      for (; moved < displaced.size(); ++moved) {
        const int c = best_free(displaced[moved].first);
        if (c < 0) break;
        put(displaced[moved].first, c);
      }
      if (moved == displaced.size()) return true;
      // Undo: v and the moved ones go again, every displaced label back where it was.
      remove(placed_[v]);
      for (std::size_t k = 0; k < moved; ++k) remove(placed_[displaced[k].first]);
      for (const auto& [w, place] : displaced) put(w, place);
    }
    return false;
  }

  // Exact repair, from the ring's zoom on: v, the names in the way of its places and the names
  // nearest it (the style's exact_group in all, within kExactRadiusPx) are placed again
  // together (metro/label_choice.hpp), each among its present place and its cheapest places
  // clear of lines, symbols and the names outside the group (kExactPlaces per type size):
  // every name placed there keeps a place, and v gains one if any arrangement allows it. The
  // one-step repair moves one name per name in the way; a crowded centre needs several moved
  // at once (Berlin's Kleistpark between Eisenacher Str. and Yorckstr.; London's fast layout
  // at 75 px: 292 of 302 named with the one-step repair, 300 with this).
  static constexpr std::size_t kExactPlaces = 40, kExactNodes = 20000, kExactRepairs = 64;
  static constexpr double kExactRadiusPx = 160;
  static constexpr double kSmallCost = 3.0;  // the smaller type, in place costs: after any usual place
  struct Option {
    std::uint32_t node;
    int c;
    char small;
    PlacedLabel label;
  };
  bool exact_repair(std::uint32_t v) {
    // The named stations near v, nearest first.
    const XY p = L_.pos[v];
    const double r = kExactRadiusPx / scale_;
    std::vector<std::pair<double, std::uint32_t>> near;
    symbol_grid_.near({p.x - r, p.y - r, p.x + r, p.y + r}, [&](int i) {
      const auto u = static_cast<std::uint32_t>(i);
      const double d = std::hypot(L_.pos[u].x - p.x, L_.pos[u].y - p.y);
      const bool seen = std::any_of(near.begin(), near.end(), [&](const auto& e) { return e.second == u; });
      if (!seen && d <= r && (u == v || placed_[u] >= 0)) near.push_back({d, u});
    });
    std::sort(near.begin(), near.end());
    // First v and the names in the way of its places clear of the map (however far their
    // stations), then the nearest.
    std::vector<std::uint32_t> group{v};
    const auto add = [&](std::uint32_t u) {
      if (group.size() < style_.exact_group && std::find(group.begin(), group.end(), u) == group.end()) group.push_back(u);
    };
    const char v_small = small_[v];
    for (const char small : {char{0}, char{1}}) {
      if (small && small_style_.font_px >= style_.font_px) continue;
      small_[v] = small;
      for (int c : ranked_candidates(v, 0, kCandidates))
        if (clear_of_map(v, c))
          for (int i : label_conflicts(v, candidate(v, c))) add(labels_[static_cast<std::size_t>(i)].node);
    }
    small_[v] = v_small;
    for (auto [d, u] : near) add(u);
    const auto in_group = [&](std::uint32_t u) { return std::find(group.begin(), group.end(), u) != group.end(); };
    // Each one's places: clear of the map and of every name outside the group.
    std::vector<Option> options;
    LabelChoiceInput choice;
    choice.names = group.size();
    for (std::size_t k = 0; k < group.size(); ++k) {
      const std::uint32_t u = group[k];
      const int current = placed_[u];
      const int current_c = current >= 0 ? candidate_[static_cast<std::size_t>(current)] : -1;
      const char current_small = small_[u];
      if (current >= 0) {  // first: the group may stay as it is but for v
        options.push_back({u, current_c, current_small, labels_[static_cast<std::size_t>(current)]});
        choice.owner.push_back(static_cast<std::uint32_t>(k));
        choice.cost.push_back(-1);
      }
      for (const char small : {char{0}, char{1}}) {
        if (small && small_style_.font_px >= style_.font_px) continue;
        util::check_stop();
        small_[u] = small;
        std::size_t found = 0;
        for (int c : ranked_candidates(u, 0, kCandidates)) {
          if (found == kExactPlaces) break;
          if ((c == current_c && small == current_small) || !clear_of_map(u, c)) continue;
          const auto l = candidate(u, c);
          const auto conflicts = label_conflicts(u, l);
          if (std::any_of(conflicts.begin(), conflicts.end(), [&](int i) { return !in_group(labels_[static_cast<std::size_t>(i)].node); }))
            continue;
          options.push_back({u, c, small, l});
          choice.owner.push_back(static_cast<std::uint32_t>(k));
          choice.cost.push_back(candidate_cost(u, c) + (small ? kSmallCost : 0.0));
          ++found;
        }
      }
      small_[u] = current_small;
    }
    const double gap = style_.label_gap_px / scale_;
    std::vector<Rect> reach(options.size());
    for (std::size_t a = 0; a < options.size(); ++a) reach[a] = expanded(swept(options[a].node, options[a].label), gap);
    // The pairs whose reaches overlap, by a sweep along x (up to ~2,000 options: all pairs
    // would be 2 million box tests per repair).
    std::vector<std::size_t> by_x(options.size());
    std::iota(by_x.begin(), by_x.end(), std::size_t{0});
    std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return reach[a].x0 < reach[b].x0; });
    for (std::size_t i = 0; i < by_x.size(); ++i)
      for (std::size_t j = i + 1; j < by_x.size() && reach[by_x[j]].x0 <= reach[by_x[i]].x1; ++j) {
        const std::size_t a = std::min(by_x[i], by_x[j]), b = std::max(by_x[i], by_x[j]);
        if (options[a].node == options[b].node) continue;
        const Rect& ra = reach[a];
        const Rect& rb = reach[b];
        if (ra.y1 < rb.y0 || rb.y1 < ra.y0) continue;
        if (labels_meet(options[a].node, options[a].label, options[b].node, options[b].label))
          choice.clashes.push_back({static_cast<int>(a), static_cast<int>(b)});
      }
    std::sort(choice.clashes.begin(), choice.clashes.end());  // as listed pair by pair: the same search
    const LabelChoice chosen = choose_label_places(choice, kExactNodes);
    if (chosen.place.empty()) return false;
    for (auto u : group)
      if (placed_[u] >= 0) remove(placed_[u]);
    for (std::size_t k = 0; k < group.size(); ++k) {
      const auto& o = options[static_cast<std::size_t>(chosen.place[k])];
      small_[group[k]] = o.small;
      put(group[k], o.c);
    }
    return true;
  }

  const LayoutGraph& g_;
  const Layout& L_;
  LabelStyle style_;
  LabelStyle small_style_;  // the smaller type for names that fit nowhere else
  std::vector<Segment> segments_;
  std::vector<std::vector<std::uint32_t>> neighbours_;
  std::vector<std::size_t> degree_;
  std::unordered_map<std::uint32_t, std::size_t> bundle_;  // node -> widest bundle through it
  std::vector<std::uint32_t> order_;
  std::vector<Text> one_line_, two_lines_;  // per node: its name on one line, and on two
  std::vector<Text> small_one_line_, small_two_lines_;  // the same in the smaller type
  std::size_t max_lines_ = 1;
  double mean_ = 1, grid_cell_ = 1;
  Rect bounds_{0, 0, 0, 0};
  Grid segment_grid_, symbol_grid_, label_grid_;
  double label_grid_cells_ = 0;
  // Per scale:
  double scale_ = 1, symbol_px_ = 0;
  double t_hi_ = 1, t_lo_ = 0;  // layout units per px at this placement's zoom and at the next one's
  bool ring_ = false;  // the ring and leaders in use
  std::vector<PlacedLabel> labels_;
  std::vector<int> candidate_;  // per label: the candidate it is
  std::vector<Rect> label_rects_;
  std::vector<Leader> leaders_;  // per label
  std::vector<int> placed_;
  std::vector<char> small_;  // per node: its name in the smaller type at this scale
  mutable std::vector<signed char> clear_memo_;  // per node, type size and candidate: clear_of_map, -1 unknown
};

}  // namespace

std::vector<LabelScale> place_station_labels(const LayoutGraph& g, const Layout& layout, const StationLabelInput& in,
                                             const std::vector<double>& mean_edges_px, const LabelStyle& style,
                                             const std::vector<LabelScale>* before) {
  std::vector<LabelScale> out;
  if (layout.pos.size() != g.pos.size() || layout.paths.size() != g.edges.size()) return out;
  Placer placer(g, layout, in, style);
  auto scales = mean_edges_px;
  std::sort(scales.begin(), scales.end());
  for (std::size_t k = 0; k < scales.size(); ++k) {
    // Kept clear of the symbols as big as they get before the next scale takes over.
    const double next = k + 1 < scales.size() ? scales[k + 1] : std::numeric_limits<double>::infinity();
    const LabelScale* earlier = nullptr;
    if (before)
      for (const auto& b : *before)
        if (b.mean_edge_px == scales[k]) earlier = &b;
    out.push_back(placer.place(scales[k], style.symbol_px(next), next, earlier));
  }
  return out;
}

}  // namespace tourmap::metro
