#include "export/page_layout.hpp"

#include "export/line_sort.hpp"
#include "metro/label_font.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tourmap::map_export {
namespace {

using geo::XY;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kHaloPx = 1.5;      // a name's halo reaches this far beyond its box
constexpr double kOutlinePx = 1.1;   // half an interchange's outline
constexpr double kCasingMarginPx = 3.5;  // the client's casing: a bundle's width plus this

double text_px(const std::string& text, double font_px) { return metro::label_text_em(text) * font_px; }

// The room needed along one axis at scale s: the items' extent from the lowest reach to the
// highest. Convex in s (a maximum of lines minus a minimum of lines).
struct Extent {
  double lo = kInf, hi = -kInf;
};

Extent extent_x(const std::vector<FitItem>& items, double s) {
  Extent e;
  for (const auto& it : items) {
    e.lo = std::min(e.lo, s * it.p.x + it.x0);
    e.hi = std::max(e.hi, s * it.p.x + it.x1);
  }
  return e;
}

Extent extent_y(const std::vector<FitItem>& items, double s) {
  Extent e;
  for (const auto& it : items) {
    e.lo = std::min(e.lo, -s * it.p.y + it.y0);
    e.hi = std::max(e.hi, -s * it.p.y + it.y1);
  }
  return e;
}

bool fits(const std::vector<FitItem>& items, const Box& box, double s) {
  const auto x = extent_x(items, s), y = extent_y(items, s);
  return x.hi - x.lo <= box.width() && y.hi - y.lo <= box.height();
}

// What the schematic alone needs: every path point with its bundle's casing, every station
// with its largest symbol across its widest bundle.
std::vector<FitItem> network_items(const MapScene& scene) {
  std::vector<FitItem> items;
  const auto& st = scene.label_style;
  std::vector<double> node_pad(scene.nodes.size(), 0);
  for (const auto& e : scene.edges) {
    const double lines = static_cast<double>(std::max<std::size_t>(1, e.order.size()));
    const double casing = (lines * st.line_spacing_px + kCasingMarginPx) / 2;
    for (const auto& p : e.path) items.push_back({p, -casing, -casing, casing, casing});
    const double symbol = st.symbol_max_px + (lines - 1) * st.line_spacing_px / 2 + kOutlinePx;
    for (auto v : {e.from, e.to})
      if (v < node_pad.size()) node_pad[v] = std::max(node_pad[v], symbol);
  }
  for (std::size_t v = 0; v < scene.nodes.size(); ++v) {
    if (!scene.nodes[v].station) continue;
    const double pad = std::max(node_pad[v], st.symbol_max_px + kOutlinePx);
    items.push_back({scene.nodes[v].pos, -pad, -pad, pad, pad});
  }
  return items;
}

void add_label_items(const MapScene& scene, const SceneLabelScale& scale, std::vector<FitItem>& items) {
  for (const auto& l : scale.labels) {
    if (l.node >= scene.nodes.size()) continue;
    items.push_back({scene.nodes[l.node].pos, l.x0 - kHaloPx, l.y0 - kHaloPx, l.x1 + kHaloPx, l.y1 + kHaloPx});
  }
}

// The largest label scale at or below `scale`, from index `below` down; -1: none.
int label_scale_at(const MapScene& scene, double scale, int below) {
  for (int i = std::min(below, static_cast<int>(scene.label_scales.size()) - 1); i >= 0; --i)
    if (scene.label_scales[static_cast<std::size_t>(i)].px_per_unit <= scale * (1 + 1e-9)) return i;
  return -1;
}

struct LegendPlan {
  double width = 0, height = 0;  // its box
  std::size_t rows = 0;          // per column
};

// The legend in columns of at most `rows` entries.
LegendPlan legend_plan(std::size_t n, std::size_t rows, double entry_px, const PageStyle& style) {
  LegendPlan p;
  p.rows = std::max<std::size_t>(1, std::min(rows, n));
  const std::size_t columns = (n + p.rows - 1) / p.rows;
  p.width = static_cast<double>(columns) * entry_px + static_cast<double>(columns > 0 ? columns - 1 : 0) * style.legend_column_gap_px;
  p.height = static_cast<double>(p.rows) * style.legend_row_px;
  return p;
}

}  // namespace

Fit fit_items(const std::vector<FitItem>& items, const Box& box) {
  Fit fit;
  if (items.empty() || box.width() <= 0 || box.height() <= 0) return fit;
  double lo = 0, hi = 1;
  if (!fits(items, box, 0)) {
    // Their reach alone does not fit: fit the points alone.
    std::vector<FitItem> points;
    for (const auto& it : items) points.push_back({it.p, 0, 0, 0, 0});
    return fit_items(points, box);
  }
  // Grow the bracket until it no longer fits (a network of one point fits at any scale: cap).
  constexpr double kMaxScale = 1e9;
  while (fits(items, box, hi) && hi < kMaxScale) {
    lo = hi;
    hi *= 2;
  }
  if (hi >= kMaxScale && fits(items, box, hi)) lo = hi;
  for (int i = 0; i < 60 && hi - lo > lo * 1e-9; ++i) {
    const double mid = (lo + hi) / 2;
    (fits(items, box, mid) ? lo : hi) = mid;
  }
  fit.scale = lo;
  const auto x = extent_x(items, lo), y = extent_y(items, lo);
  fit.origin = {box.x0 + (box.width() - (x.hi - x.lo)) / 2 - x.lo, box.y0 + (box.height() - (y.hi - y.lo)) / 2 - y.lo};
  return fit;
}

XY to_page(const Fit& fit, XY p) { return {fit.origin.x + fit.scale * p.x, fit.origin.y - fit.scale * p.y}; }

double symbol_radius_px(const MapScene& scene, double scale) {
  const auto& st = scene.label_style;
  return std::clamp(st.symbol_share * scene.mean_edge * scale, st.symbol_min_px, st.symbol_max_px);
}

std::vector<std::string> wrap_text(const std::string& text, double font_px, double max_px) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size()) {
    auto space = text.find(' ', start);
    if (space == std::string::npos) space = text.size();
    const std::string word = text.substr(start, space - start);
    start = space + 1;
    if (word.empty()) continue;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_px(joined, font_px) > max_px) {
      lines.push_back(line);
      line = word;
    } else {
      line = joined;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

PageLayout layout_page(const MapScene& scene, double width_px, double height_px, const PageStyle& style) {
  PageLayout page;
  page.width = width_px;
  page.height = height_px;
  const double m = style.margin_px;
  const Box inner{m, m, width_px - m, height_px - m};

  // A long name is set smaller to fit across (not below 12 px; a tiny page may still cut it).
  const double title_em = metro::label_text_em(scene.title);
  page.title_px = title_em > 0 ? std::clamp(inner.width() / title_em, 12.0, style.title_px) : style.title_px;
  page.title = {scene.title, {m, m + page.title_px * 0.8}};
  const double top = scene.title.empty() ? m : m + page.title_px + style.title_gap_px;

  // The attribution at the foot, all publishers on as few lines as fit.
  std::string credits;
  for (const auto& a : scene.attribution) credits += (credits.empty() ? "" : "  ·  ") + a;
  const auto credit_lines = wrap_text(credits, style.attribution_px, inner.width());
  double bottom = height_px - m;
  if (!credit_lines.empty()) {
    bottom -= static_cast<double>(credit_lines.size()) * style.attribution_line_px;
    double y = bottom + style.attribution_px;
    for (const auto& line : credit_lines) {
      page.attribution.push_back({line, {m, y}});
      y += style.attribution_line_px;
    }
    bottom -= style.attribution_gap_px;
  }
  const Box room{m, top, width_px - m, bottom};

  // The legend: beside the map (columns as tall as the room) or below it (as many columns as
  // fit across), whichever lets the schematic be larger.
  const auto order = legend_order(scene.lines);
  double label_px = 0;
  for (const auto& line : scene.lines) label_px = std::max(label_px, text_px(line.label, style.legend_font_px));
  const double entry_px = style.swatch_width_px + style.swatch_gap_px + label_px;
  const auto network = network_items(scene);
  const std::size_t n = order.size();
  const auto beside = legend_plan(n, static_cast<std::size_t>(std::max(1.0, std::floor(room.height() / style.legend_row_px))), entry_px, style);
  const double across = std::floor((room.width() + style.legend_column_gap_px) / (entry_px + style.legend_column_gap_px));
  const auto columns_below = static_cast<std::size_t>(std::max(1.0, across));
  const auto below = legend_plan(n, (n + columns_below - 1) / std::max<std::size_t>(1, columns_below), entry_px, style);
  const Box map_beside{room.x0, room.y0, room.x1 - beside.width - style.legend_gap_px, room.y1};
  const Box map_below{room.x0, room.y0, room.x1, room.y1 - below.height - style.legend_gap_px};
  auto usable = [&](const Box& b) {
    return b.width() >= style.min_map_share * width_px && b.height() >= style.min_map_share * height_px;
  };
  const bool can_beside = n > 0 && usable(map_beside) && beside.height <= room.height();
  const bool can_below = n > 0 && usable(map_below) && below.width <= room.width();
  page.map = room;
  if (can_beside || can_below) {
    const double s_beside = can_beside ? fit_items(network, map_beside).scale : -1;
    const double s_below = can_below ? fit_items(network, map_below).scale : -1;
    page.legend_beside = s_beside >= s_below;
    const auto& plan = page.legend_beside ? beside : below;
    page.map = page.legend_beside ? map_beside : map_below;
    const double x0 = page.legend_beside ? room.x1 - plan.width : room.x0;
    const double y0 = page.legend_beside ? room.y0 : room.y1 - plan.height;
    for (std::size_t k = 0; k < n; ++k) {
      const auto column = static_cast<double>(k / plan.rows), row = static_cast<double>(k % plan.rows);
      const double x = x0 + column * (entry_px + style.legend_column_gap_px);
      const double mid = y0 + (row + 0.5) * style.legend_row_px;
      LegendEntry e;
      e.line = order[k];
      e.swatch = {x, mid - style.swatch_height_px / 2, x + style.swatch_width_px, mid + style.swatch_height_px / 2};
      e.text_at = {x + style.swatch_width_px + style.swatch_gap_px, mid + 0.35 * style.legend_font_px};
      page.legend.push_back(e);
    }
  }

  // The schematic: fitted alone, then with the names of the largest label scale at or below
  // that scale; when those names need a scale below their own, the next smaller placement.
  Fit fit = fit_items(network, page.map);
  int chosen = label_scale_at(scene, fit.scale, static_cast<int>(scene.label_scales.size()) - 1);
  while (chosen >= 0) {
    auto items = network;
    add_label_items(scene, scene.label_scales[static_cast<std::size_t>(chosen)], items);
    const Fit with_names = fit_items(items, page.map);
    if (with_names.scale >= scene.label_scales[static_cast<std::size_t>(chosen)].px_per_unit * (1 - 1e-9)) {
      fit = with_names;
      break;
    }
    chosen = label_scale_at(scene, with_names.scale, chosen - 1);
    if (chosen < 0) fit = fit_items(network, page.map);
  }
  page.fit = fit;
  page.label_scale = chosen;
  page.symbol_px = symbol_radius_px(scene, fit.scale);
  // A placement keeps clear of the symbols of the next scale up, not of larger ones: when the
  // next scale's names did not fit the page, the symbols stay that size.
  const auto next = static_cast<std::size_t>(chosen + 1);
  if (chosen >= 0 && next < scene.label_scales.size())
    page.symbol_px = std::min(page.symbol_px, symbol_radius_px(scene, scene.label_scales[next].px_per_unit));
  return page;
}

}  // namespace tourmap::map_export
