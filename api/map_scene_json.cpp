#include "map_scene_json.hpp"

#include <unordered_map>

namespace tourmap::api {
namespace {

using map_export::MapScene;

geo::XY point(const nlohmann::json& xy) { return {xy.at(0).get<double>(), xy.at(1).get<double>()}; }

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void read_labels(const nlohmann::json& labels, std::size_t stations, MapScene& scene) {
  auto& style = scene.label_style;
  const auto& font = labels.at("font");
  style.font_px = font.value("size_px", style.font_px);
  style.line_px = font.value("line_px", style.line_px);
  const auto& symbol = labels.at("symbol");
  style.symbol_share = symbol.value("share", style.symbol_share);
  style.symbol_min_px = symbol.value("min_px", style.symbol_min_px);
  style.symbol_max_px = symbol.value("max_px", style.symbol_max_px);
  style.line_spacing_px = labels.value("line_spacing_px", style.line_spacing_px);
  scene.mean_edge = labels.value("mean_edge_m", 0.0);
  for (const auto& s : labels.at("scales")) {
    map_export::SceneLabelScale scale;
    scale.px_per_unit = s.at("px_per_m").get<double>();
    for (const auto& l : s.at("labels")) {
      // [station index, x0, y0, x1, y1, text x, text y, anchor, split, size(, leader x0, y0, x1, y1)]:
      // stations are the scene's first nodes, in the answer's order.
      map_export::SceneLabel label;
      label.node = l.at(0).get<std::uint32_t>();
      label.x0 = l.at(1).get<double>();
      label.y0 = l.at(2).get<double>();
      label.x1 = l.at(3).get<double>();
      label.y1 = l.at(4).get<double>();
      label.text_x = l.at(5).get<double>();
      label.text_y = l.at(6).get<double>();
      const auto anchor = l.at(7).get<std::string>();
      label.anchor = anchor.empty() ? 's' : anchor[0];
      label.split = l.at(8).get<std::size_t>();
      label.font_px = l.at(9).get<double>();
      if (l.size() >= 14) {
        label.leader = true;
        label.lx0 = l.at(10).get<double>(), label.ly0 = l.at(11).get<double>();
        label.lx1 = l.at(12).get<double>(), label.ly1 = l.at(13).get<double>();
      }
      if (label.node < stations) scale.labels.push_back(label);
    }
    scene.label_scales.push_back(std::move(scale));
  }
}

}  // namespace

map_export::Rgb parse_line_color(const std::string& hex) {
  if (hex.size() != 6) return {};
  int v[6];
  for (int i = 0; i < 6; ++i)
    if ((v[i] = hex_digit(hex[static_cast<std::size_t>(i)])) < 0) return {};
  return {static_cast<std::uint8_t>(v[0] * 16 + v[1]), static_cast<std::uint8_t>(v[2] * 16 + v[3]),
          static_cast<std::uint8_t>(v[4] * 16 + v[5])};
}

MapScene scene_from_layout(const nlohmann::json& layout, const std::string& title) {
  MapScene scene;
  scene.title = title;
  std::unordered_map<std::string, std::uint32_t> line_index, node_index;
  for (const auto& l : layout.at("lines")) {
    const auto id = l.at("id").get<std::string>();
    line_index.emplace(id, static_cast<std::uint32_t>(scene.lines.size()));
    scene.lines.push_back({id, l.at("label").get<std::string>(), parse_line_color(l.value("color", ""))});
  }
  auto lines_of = [&](const nlohmann::json& ids) {
    std::vector<std::uint32_t> out;
    for (const auto& id : ids)
      if (auto it = line_index.find(id.get<std::string>()); it != line_index.end()) out.push_back(it->second);
    return out;
  };
  for (const auto& f : layout.at("stations").at("features")) {
    const auto& props = f.at("properties");
    map_export::SceneNode node;
    node.pos = point(f.at("geometry").at("coordinates"));
    node.station = true;
    node.name = props.value("name", "");
    node.lines = lines_of(props.at("lines"));
    node_index.emplace(props.at("id").get<std::string>(), static_cast<std::uint32_t>(scene.nodes.size()));
    scene.nodes.push_back(std::move(node));
  }
  const std::size_t stations = scene.nodes.size();
  // Edge ends that are not stations (junctions) become nodes of their own.
  auto node_at = [&](const std::string& id, geo::XY pos) {
    auto [it, added] = node_index.emplace(id, static_cast<std::uint32_t>(scene.nodes.size()));
    if (added) scene.nodes.push_back({pos, false, "", {}});
    return it->second;
  };
  for (const auto& f : layout.at("edges").at("features")) {
    const auto& props = f.at("properties");
    map_export::SceneEdge edge;
    for (const auto& p : f.at("geometry").at("coordinates")) edge.path.push_back(point(p));
    if (edge.path.empty()) continue;
    edge.from = node_at(props.at("from").get<std::string>(), edge.path.front());
    edge.to = node_at(props.at("to").get<std::string>(), edge.path.back());
    edge.order = lines_of(props.contains("line_order") ? props.at("line_order") : props.at("lines"));
    scene.edges.push_back(std::move(edge));
  }
  if (layout.contains("labels")) read_labels(layout.at("labels"), stations, scene);
  for (const auto& a : layout.value("attribution", nlohmann::json::array())) scene.attribution.push_back(a.get<std::string>());
  return scene;
}

}  // namespace tourmap::api
