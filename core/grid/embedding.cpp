#include "grid/embedding.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::grid {
namespace {

double cross(XY a, XY b) { return a.x * b.y - a.y * b.x; }
XY sub(XY a, XY b) { return {a.x - b.x, a.y - b.y}; }

}  // namespace

XY bilinear(const std::array<XY, 4>& c, double u, double v) {
  double w0 = (1 - u) * (1 - v), w1 = u * (1 - v), w2 = u * v, w3 = (1 - u) * v;
  return {w0 * c[0].x + w1 * c[1].x + w2 * c[2].x + w3 * c[3].x, w0 * c[0].y + w1 * c[1].y + w2 * c[2].y + w3 * c[3].y};
}

std::optional<std::array<double, 2>> inverse_bilinear(const std::array<XY, 4>& c, XY p, double tolerance) {
  // p = a + e u + f v + g u v with a = c0, e = c1 - c0, f = c3 - c0, g = c0 - c1 + c2 - c3.
  // Eliminating u gives k2 v^2 + k1 v + k0 = 0.
  XY e = sub(c[1], c[0]), f = sub(c[3], c[0]), h = sub(p, c[0]);
  XY g = {c[0].x - c[1].x + c[2].x - c[3].x, c[0].y - c[1].y + c[2].y - c[3].y};
  double k2 = cross(g, f), k1 = cross(e, f) + cross(h, g), k0 = cross(h, e);
  double scale = std::max({std::abs(cross(e, f)), 1e-300});
  std::array<double, 2> candidates{};
  int n = 0;
  if (std::abs(k2) <= 1e-12 * scale) {  // parallelogram-like: linear in v
    if (k1 == 0) return std::nullopt;
    candidates[n++] = -k0 / k1;
  } else {
    double disc = k1 * k1 - 4 * k0 * k2;
    if (disc < 0) return std::nullopt;
    double root = std::sqrt(disc);
    candidates[n++] = (-k1 - root) / (2 * k2);
    candidates[n++] = (-k1 + root) / (2 * k2);
  }
  for (int i = 0; i < n; ++i) {
    double v = candidates[i];
    if (v < -tolerance || v > 1 + tolerance) continue;
    // u from whichever coordinate is better conditioned.
    double dx = e.x + g.x * v, dy = e.y + g.y * v;
    double u = std::abs(dx) >= std::abs(dy) ? (h.x - f.x * v) / dx : (h.y - f.y * v) / dy;
    if (u < -tolerance || u > 1 + tolerance) continue;
    return std::array<double, 2>{std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0)};
  }
  return std::nullopt;
}

std::array<XY, 4> corners_of(const Grid& grid, const std::vector<XY>& positions, std::uint32_t quad) {
  const auto& c = grid.quads[quad].corners;
  return {positions[c[0]], positions[c[1]], positions[c[2]], positions[c[3]]};
}

Embedding embed(const Grid& grid, XY p) {
  Embedding e;
  e.quad = grid.quad_at(p);
  auto corners = corners_of(grid, grid.vertices, e.quad);
  // Points outside the frame are clamped onto it (the frame is padded, so this is rare).
  auto uv = inverse_bilinear(corners, p, 1e-6);
  double u = 0.5, v = 0.5;
  if (uv) {
    u = (*uv)[0];
    v = (*uv)[1];
  } else {
    const auto& q = grid.quads[e.quad];
    u = std::clamp((p.x - q.min.x) / q.size, 0.0, 1.0);
    v = std::clamp((p.y - q.min.y) / q.size, 0.0, 1.0);
  }
  e.weight = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
  return e;
}

XY place(const Grid& grid, const std::vector<XY>& positions, const Embedding& e) {
  const auto& c = grid.quads[e.quad].corners;
  XY out{0, 0};
  for (int k = 0; k < 4; ++k) {
    out.x += e.weight[k] * positions[c[k]].x;
    out.y += e.weight[k] * positions[c[k]].y;
  }
  return out;
}

}  // namespace tourmap::grid
