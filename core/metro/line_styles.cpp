#include "metro/line_styles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace tourmap::metro {
namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

std::optional<Lab> lab_from_hex(std::string_view hex) {
  if (!hex.empty() && hex[0] == '#') hex.remove_prefix(1);
  if (hex.size() != 6) return std::nullopt;
  double rgb[3];
  for (int k = 0; k < 3; ++k) {
    int hi = hex_digit(hex[2 * k]), lo = hex_digit(hex[2 * k + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    // sRGB (IEC 61966-2-1) stores gamma-encoded values: expand to linear light first.
    double c = (hi * 16 + lo) / 255.0;
    rgb[k] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  // Linear sRGB -> CIE XYZ (D65), divided by the D65 white (0.95047, 1, 1.08883).
  double x = (0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2]) / 0.95047;
  double y = 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2];
  double z = (0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2]) / 1.08883;
  // XYZ -> Lab: a cube root, linear near black (below (6/29)^3) so the slope stays finite.
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
  };
  return Lab{116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double delta_e2000(const Lab& x, const Lab& y) {
  // Lab -> L'C'h' with a* stretched for neutral colours (G), then weighted differences in
  // lightness, chroma and hue plus the rotation term for blues (R_T). Notation of the paper.
  const double c1 = std::hypot(x.a, x.b), c2 = std::hypot(y.a, y.b);
  const double c_mean7 = std::pow((c1 + c2) / 2, 7);
  const double g = 0.5 * (1 - std::sqrt(c_mean7 / (c_mean7 + std::pow(25.0, 7))));
  const double a1 = (1 + g) * x.a, a2 = (1 + g) * y.a;
  const double cp1 = std::hypot(a1, x.b), cp2 = std::hypot(a2, y.b);
  auto hue = [](double b, double a) {
    if (a == 0 && b == 0) return 0.0;
    double h = deg(std::atan2(b, a));
    return h < 0 ? h + 360 : h;
  };
  const double h1 = hue(x.b, a1), h2 = hue(y.b, a2);

  const double dl = y.L - x.L, dc = cp2 - cp1;
  double dh = 0;
  if (cp1 * cp2 != 0) {
    dh = h2 - h1;
    if (dh > 180) dh -= 360;
    else if (dh < -180) dh += 360;
  }
  const double d_big_h = 2 * std::sqrt(cp1 * cp2) * std::sin(rad(dh / 2));

  const double l_mean = (x.L + y.L) / 2, cp_mean = (cp1 + cp2) / 2;
  double h_mean = h1 + h2;
  if (cp1 * cp2 != 0) {
    if (std::abs(h1 - h2) <= 180) h_mean = (h1 + h2) / 2;
    else h_mean = h1 + h2 < 360 ? (h1 + h2 + 360) / 2 : (h1 + h2 - 360) / 2;
  }
  const double t = 1 - 0.17 * std::cos(rad(h_mean - 30)) + 0.24 * std::cos(rad(2 * h_mean)) +
                   0.32 * std::cos(rad(3 * h_mean + 6)) - 0.20 * std::cos(rad(4 * h_mean - 63));
  const double d_theta = 30 * std::exp(-std::pow((h_mean - 275) / 25, 2));
  const double cp_mean7 = std::pow(cp_mean, 7);
  const double r_c = 2 * std::sqrt(cp_mean7 / (cp_mean7 + std::pow(25.0, 7)));
  const double s_l = 1 + 0.015 * std::pow(l_mean - 50, 2) / std::sqrt(20 + std::pow(l_mean - 50, 2));
  const double s_c = 1 + 0.045 * cp_mean;
  const double s_h = 1 + 0.015 * cp_mean * t;
  const double r_t = -std::sin(rad(2 * d_theta)) * r_c;
  const double tl = dl / s_l, tc = dc / s_c, th = d_big_h / s_h;
  return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + r_t * tc * th));
}

const std::vector<model::LineStyle>& distinct_styles() {
  // A casing first: it changes the look of a line least. Dashes on metro maps often mean
  // "under construction", but tourmap hides such lines (name_rules.hpp), so here they only
  // tell close colours apart.
  static const std::vector<model::LineStyle> styles = {
      {true, {}}, {false, {2, 1}}, {false, {1, 1}}, {true, {2, 1}}, {true, {1, 1}}};
  return styles;
}

std::string describe_style(const model::LineStyle& style) {
  if (style.plain()) return "plain";
  std::string out = style.casing ? "casing" : "";
  if (!style.dash.empty()) {
    out.append(out.empty() ? "dash " : "+dash ");
    for (std::size_t k = 0; k < style.dash.size(); ++k) {
      char num[32];
      std::snprintf(num, sizeof num, "%s%g", k ? "-" : "", style.dash[k]);
      out.append(num);
    }
  }
  return out;
}

// Sasha Trubetskoy's "20 distinct colours" without the ones too light for thin strokes on a light
// background (yellow, lime, pink, lavender, beige, mint, apricot, white) plus two darker ones.
constexpr const char* kPalette[] = {"e6194b", "3cb44b", "4363d8", "f58231", "911eb4", "42d4f4", "f032e6",
                                    "469990", "9a6324", "800000", "808000", "000075", "a9a9a9", "1b7837"};

std::size_t assign_missing_colours(model::MetroNetwork& net) {
  std::vector<Lab> used;
  for (const auto& line : net.lines)
    if (auto lab = lab_from_hex(line.color)) used.push_back(*lab);
  std::size_t assigned = 0;
  for (auto& line : net.lines) {
    if (lab_from_hex(line.color)) continue;
    const char* best = kPalette[assigned % std::size(kPalette)];
    double best_gap = -1;
    for (const char* hex : kPalette) {
      const auto lab = *lab_from_hex(hex);
      double gap = 1e9;
      for (const auto& u : used) gap = std::min(gap, delta_e2000(lab, u));
      if (gap > best_gap) {
        best_gap = gap;
        best = hex;
      }
    }
    line.color = best;
    used.push_back(*lab_from_hex(best));
    ++assigned;
  }
  return assigned;
}

std::vector<CloseGroup> assign_line_styles(model::MetroNetwork& net, double min_difference) {
  const auto n = static_cast<std::uint32_t>(net.lines.size());
  std::vector<std::optional<Lab>> lab(n);
  std::vector<std::size_t> edge_count(n, 0);
  for (std::uint32_t l = 0; l < n; ++l) {
    net.lines[l].style = {};
    lab[l] = lab_from_hex(net.lines[l].color);
  }
  for (const auto& e : net.edges)
    for (auto l : e.lines)
      if (l < n) ++edge_count[l];

  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      if (lab[i] && lab[j] && delta_e2000(*lab[i], *lab[j]) < min_difference) parent[find(parent, j)] = find(parent, i);

  std::vector<std::vector<std::uint32_t>> members(n);
  for (std::uint32_t l = 0; l < n; ++l) members[find(parent, l)].push_back(l);
  std::vector<CloseGroup> groups;
  for (auto& group : members) {  // in order of each group's first line
    if (group.size() < 2) continue;
    std::stable_sort(group.begin(), group.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return edge_count[a] > edge_count[b]; });
    const auto& styles = distinct_styles();
    for (std::size_t k = 1; k < group.size(); ++k) net.lines[group[k]].style = styles[(k - 1) % styles.size()];
    groups.push_back({std::move(group)});
  }
  std::sort(groups.begin(), groups.end(),
            [](const CloseGroup& a, const CloseGroup& b) { return a.lines.front() < b.lines.front(); });
  for (std::uint32_t l = 0; l < n; ++l)
    if (lab[l] && lab[l]->L > kMaxPlainLightness) net.lines[l].style.casing = true;
  return groups;
}

}  // namespace tourmap::metro
