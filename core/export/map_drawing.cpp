#include "export/map_drawing.hpp"

#include "export/bundle_paths.hpp"
#include "metro/label_font.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace tourmap::map_export {
namespace {

using geo::XY;

std::vector<XY> page_path(const Fit& fit, const std::vector<XY>& path) {
  std::vector<XY> out;
  out.reserve(path.size());
  for (const auto& p : path) out.push_back(to_page(fit, p));
  return out;
}

// Per node: the widest bundle (2 lines or more) through it, and the direction its lines run
// on the page (degrees, y down), as the client's bundlesAtStations.
struct StationBundle {
  std::size_t lines = 0;
  double angle_deg = 0;
};

std::vector<StationBundle> bundles_at_nodes(const MapScene& scene, const std::vector<std::vector<XY>>& paths) {
  std::vector<StationBundle> out(scene.nodes.size());
  for (std::size_t e = 0; e < scene.edges.size(); ++e) {
    const auto& edge = scene.edges[e];
    const auto& points = paths[e];
    const auto lines = edge.order.size();
    if (points.size() < 2 || lines < 2) continue;
    const std::pair<std::uint32_t, std::pair<XY, XY>> ends[] = {{edge.from, {points[0], points[1]}},
                                                               {edge.to, {points.back(), points[points.size() - 2]}}};
    for (const auto& [node, seg] : ends) {
      if (node >= out.size() || out[node].lines >= lines) continue;
      out[node] = {lines, std::atan2(seg.second.y - seg.first.y, seg.second.x - seg.first.x) * 180 / std::numbers::pi};
    }
  }
  return out;
}

void draw_network(const MapScene& scene, const PageLayout& page, const MapStyle& style, Drawing& d) {
  const double spacing = scene.label_style.line_spacing_px;
  std::vector<std::vector<XY>> paths;
  paths.reserve(scene.edges.size());
  for (const auto& e : scene.edges) paths.push_back(page_path(page.fit, e.path));

  // Casings: one white stroke per bundle size, wider ones first so that a narrower bundle's
  // casing never hides a wider one's lines.
  std::map<std::size_t, std::vector<std::vector<XY>>, std::greater<>> casings;
  for (std::size_t e = 0; e < scene.edges.size(); ++e)
    if (paths[e].size() > 1) casings[std::max<std::size_t>(1, scene.edges[e].order.size())].push_back(paths[e]);
  for (auto& [size, list] : casings)
    d.items.push_back(Strokes{Role::casing, std::move(list), style.paper,
                              static_cast<double>(size) * spacing + style.casing_margin_px});

  std::vector<BundleEdge> bundles;
  for (std::size_t e = 0; e < scene.edges.size(); ++e)
    if (paths[e].size() > 1) bundles.push_back({scene.edges[e].from, scene.edges[e].to, paths[e], scene.edges[e].order});
  auto pieces = bundle_pieces(bundles, scene.lines.size(), spacing);
  for (std::size_t l = 0; l < scene.lines.size(); ++l) {
    auto& strokes = pieces.strokes[l];
    for (auto& join : pieces.joins[l]) strokes.push_back(std::move(join));
    if (strokes.empty()) continue;
    d.items.push_back(Strokes{Role::line, std::move(strokes), color_of(scene.lines[l].color), style.line_width_px});
  }

  // Station symbols: a circle, or across a bundle a capsule 2r + (n - 1) spacings long.
  const auto at_nodes = bundles_at_nodes(scene, paths);
  const double r = page.symbol_px;
  for (std::size_t v = 0; v < scene.nodes.size(); ++v) {
    const auto& node = scene.nodes[v];
    if (!node.station) continue;
    const bool interchange = node.lines.size() > 1;
    const auto lanes = at_nodes[v].lines > 1 ? at_nodes[v].lines - 1 : 0;
    RoundedRect symbol;
    symbol.role = Role::station;
    symbol.center = to_page(page.fit, node.pos);
    symbol.width = 2 * r + static_cast<double>(lanes) * spacing;
    symbol.height = 2 * r;
    symbol.radius = r;
    symbol.angle_deg = lanes > 0 ? at_nodes[v].angle_deg + 90 : 0;
    symbol.fill = style.paper;
    if (interchange) {
      symbol.stroke = style.ink;
      symbol.stroke_width = style.interchange_outline_px;
    } else {
      symbol.stroke = node.lines.empty() || node.lines[0] >= scene.lines.size() ? color_of(Rgb{})
                                                                                : color_of(scene.lines[node.lines[0]].color);
      symbol.stroke_width = style.station_outline_px;
    }
    d.items.push_back(symbol);
  }
}

// The name on one line or two (split at byte `split`, the first part's trailing space dropped).
std::vector<std::string> label_lines(const std::string& name, std::size_t split) {
  if (split == 0 || split >= name.size()) return {name};
  auto first = name.substr(0, split);
  while (!first.empty() && first.back() == ' ') first.pop_back();
  return {first, name.substr(split)};
}

void draw_labels(const MapScene& scene, const PageLayout& page, const MapStyle& style, Drawing& d) {
  if (page.label_scale < 0) return;
  const auto& st = scene.label_style;
  const auto& placed = scene.label_scales[static_cast<std::size_t>(page.label_scale)].labels;
  // Leaders first, under the names' halos.
  Strokes leaders{Role::label, {}, style.ink, style.leader_width_px};
  for (const auto& l : placed) {
    if (!l.leader || l.node >= scene.nodes.size() || scene.nodes[l.node].name.empty()) continue;
    const XY at = to_page(page.fit, scene.nodes[l.node].pos);
    leaders.paths.push_back({{at.x + l.lx0, at.y + l.ly0}, {at.x + l.lx1, at.y + l.ly1}});
  }
  if (!leaders.paths.empty()) d.items.push_back(std::move(leaders));
  for (const auto& l : placed) {
    if (l.node >= scene.nodes.size() || scene.nodes[l.node].name.empty()) continue;
    const XY at = to_page(page.fit, scene.nodes[l.node].pos);
    Text t;
    t.role = Role::label;
    t.at = {at.x + l.text_x, at.y + l.text_y};
    t.lines = label_lines(scene.nodes[l.node].name, l.split);
    for (const auto& line : t.lines) t.fit_em.push_back(metro::label_text_em(line));
    // A name in the smaller type has its line spacing scaled alike (metro::LabelStyle).
    t.size_px = l.font_px > 0 ? l.font_px : st.font_px;
    t.line_px = st.line_px * t.size_px / st.font_px;
    t.bold = true;
    t.anchor = l.anchor;
    t.fill = style.ink;
    t.halo = style.paper;
    t.halo.a = style.label_halo_alpha;
    t.halo_px = style.label_halo_px;
    d.items.push_back(std::move(t));
  }
}

Text plain_text(Role role, const TextLine& line, double size_px, bool bold, Color fill) {
  Text t;
  t.role = role;
  t.at = line.at;
  t.lines = {line.text};
  t.size_px = size_px;
  t.line_px = size_px * 1.2;
  t.bold = bold;
  t.fill = fill;
  return t;
}

void draw_frame(const MapScene& scene, const PageLayout& page, const MapStyle& style, const PageStyle& ps, Drawing& d) {
  if (!page.title.text.empty()) d.items.push_back(plain_text(Role::title, page.title, page.title_px, true, style.ink));
  for (const auto& e : page.legend) {
    RoundedRect swatch;
    swatch.role = Role::legend;
    swatch.center = {(e.swatch.x0 + e.swatch.x1) / 2, (e.swatch.y0 + e.swatch.y1) / 2};
    swatch.width = e.swatch.width();
    swatch.height = e.swatch.height();
    swatch.radius = std::min(style.swatch_radius_px, swatch.height / 2);
    swatch.fill = color_of(scene.lines[e.line].color);
    d.items.push_back(swatch);
    d.items.push_back(plain_text(Role::legend, {scene.lines[e.line].label, e.text_at}, ps.legend_font_px, true, style.ink));
  }
  for (const auto& line : page.attribution)
    d.items.push_back(plain_text(Role::attribution, line, ps.attribution_px, false, style.ink_soft));
}

}  // namespace

Color color_of(const Rgb& rgb) { return {rgb.r / 255.0, rgb.g / 255.0, rgb.b / 255.0, 1}; }

Drawing draw_map(const MapScene& scene, const PageLayout& page, const MapStyle& style, const PageStyle& page_style) {
  Drawing d;
  d.width = page.width;
  d.height = page.height;
  d.title = scene.title;
  d.font_family = metro::kLabelFontFamily;
  RoundedRect background;
  background.role = Role::background;
  background.center = {page.width / 2, page.height / 2};
  background.width = page.width;
  background.height = page.height;
  background.fill = style.paper;
  d.items.push_back(background);
  draw_network(scene, page, style, d);
  draw_labels(scene, page, style, d);
  draw_frame(scene, page, style, page_style, d);
  return d;
}

Drawing draw_map(const MapScene& scene, double width_px, double height_px) {
  return draw_map(scene, layout_page(scene, width_px, height_px));
}

}  // namespace tourmap::map_export
