#include "deform/system.hpp"
#include "deform/untangle.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>

#include <Eigen/SparseCholesky>

#include <chrono>
#include <cmath>
#include <numeric>

namespace tourmap::deform {

Prepared::Prepared() : factor_mutex_(std::make_unique<std::mutex>()) {}
Prepared::~Prepared() = default;
Prepared::Prepared(Prepared&&) noexcept = default;
Prepared& Prepared::operator=(Prepared&&) noexcept = default;


namespace {

using Clock = std::chrono::steady_clock;

// Collects rows as (point, axis, coefficient) terms; terms on fixed coordinates go to the
// row's fixed part instead of the matrix.
class SystemBuilder {
 public:
  SystemBuilder(const std::vector<XY>& rest, const std::vector<std::array<int, 2>>& column)
      : rest_(rest), column_(column) {}

  void add(std::uint32_t point, int axis, double coef) { terms_.push_back({point, axis, coef}); }

  // Closes the current row: row = scale * (sum of terms), target = scale * target.
  void end_row(double scale, double target = 0.0) {
    double fixed = 0.0;
    bool any_free = false;
    for (const auto& t : terms_) {
      int col = column_[t.point][t.axis];
      double value = t.axis == 0 ? rest_[t.point].x : rest_[t.point].y;
      if (col < 0) {
        fixed += scale * t.coef * value;
      } else {
        triplets_.emplace_back(static_cast<int>(rows_), col, scale * t.coef);
        any_free = true;
      }
    }
    (void)any_free;
    fixed_.push_back(fixed);
    target_.push_back(scale * target);
    terms_.clear();
    ++rows_;
  }

  std::size_t rows() const { return rows_; }

  LinearSystem finish(int unknowns) {
    LinearSystem s;
    s.A.resize(static_cast<Eigen::Index>(rows_), unknowns);
    s.A.setFromTriplets(triplets_.begin(), triplets_.end());  // sums repeated (row, col) terms
    s.fixed_part = Eigen::Map<Eigen::VectorXd>(fixed_.data(), static_cast<Eigen::Index>(fixed_.size()));
    s.base_target = Eigen::Map<Eigen::VectorXd>(target_.data(), static_cast<Eigen::Index>(target_.size()));
    return s;
  }

 private:
  struct Term {
    std::uint32_t point;
    int axis;
    double coef;
  };
  const std::vector<XY>& rest_;
  const std::vector<std::array<int, 2>>& column_;
  std::vector<Term> terms_;
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<double> fixed_, target_;
  std::size_t rows_ = 0;
};

// Numbers the free coordinates; fixed ones get -1.
int number_unknowns(std::vector<std::array<int, 2>>& column) {
  int next = 0;
  for (auto& c : column)
    for (auto& axis : c)
      if (axis >= 0) axis = next++;
  return next;
}

Eigen::VectorXd rest_vector(const std::vector<XY>& rest, const std::vector<std::array<int, 2>>& column, int unknowns) {
  Eigen::VectorXd x(unknowns);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (column[i][0] >= 0) x[column[i][0]] = rest[i].x;
    if (column[i][1] >= 0) x[column[i][1]] = rest[i].y;
  }
  return x;
}

// The similarity K (a 2x2 [[a, -b], [b, a]]) with K * from = to (eq. 4.3).
std::array<double, 2> similarity(XY from, XY to) {
  double n = from.x * from.x + from.y * from.y;
  return {(from.x * to.x + from.y * to.y) / n, (from.x * to.y - from.y * to.x) / n};
}

// Adds the two rows  B~ - K A~ = 0  for vectors given as weighted point sums.
struct Vec {
  std::vector<std::pair<std::uint32_t, double>> terms;  // sum of coef * point
};
void add_shape_rows(SystemBuilder& b, const Vec& B, const Vec& A, std::array<double, 2> k, double scale) {
  // x:  B.x - (a A.x - b A.y);  y:  B.y - (b A.x + a A.y)
  for (int axis = 0; axis < 2; ++axis) {
    for (auto [p, c] : B.terms) b.add(p, axis, c);
    for (auto [p, c] : A.terms) {
      if (axis == 0) {
        b.add(p, 0, -k[0] * c);
        b.add(p, 1, k[1] * c);
      } else {
        b.add(p, 0, -k[1] * c);
        b.add(p, 1, -k[0] * c);
      }
    }
    b.end_row(scale);
  }
}

XY eval(const Vec& v, const std::vector<XY>& pts) {
  XY out{0, 0};
  for (auto [p, c] : v.terms) {
    out.x += c * pts[p].x;
    out.y += c * pts[p].y;
  }
  return out;
}

void add_road_rows(SystemBuilder& b, const PlanarNetwork& net, const std::vector<grid::Embedding>* emb,
                   const grid::Grid* g, double scale) {
  for (const auto& [u, v] : net.edges) {
    XY d{net.nodes[u].x - net.nodes[v].x, net.nodes[u].y - net.nodes[v].y};
    for (int axis = 0; axis < 2; ++axis) {
      if (emb) {
        const auto& eu = (*emb)[u];
        const auto& ev = (*emb)[v];
        for (int k = 0; k < 4; ++k) {
          b.add(g->quads[eu.quad].corners[k], axis, eu.weight[k]);
          b.add(g->quads[ev.quad].corners[k], axis, -ev.weight[k]);
        }
      } else {
        b.add(u, axis, 1.0);
        b.add(v, axis, -1.0);
      }
      b.end_row(scale, axis == 0 ? d.x : d.y);  // the request's scale s_i multiplies this target
    }
  }
}

void add_guide_rows(SystemBuilder& b, const std::vector<std::uint32_t>& guides,
                    const std::vector<grid::Embedding>* emb, const grid::Grid* g, double scale) {
  for (auto node : guides)
    for (int axis = 0; axis < 2; ++axis) {
      if (emb) {
        const auto& e = (*emb)[node];
        for (int k = 0; k < 4; ++k) b.add(g->quads[e.quad].corners[k], axis, e.weight[k]);
      } else {
        b.add(node, axis, 1.0);
      }
      b.end_row(scale);  // target set per request
    }
}

void finish_prepared(Prepared& p, int unknowns, SystemBuilder& builder, Clock::time_point start) {
  auto road_rows = p.system.road_rows;
  auto guide_begin = p.system.guide_row_begin;
  auto road_scale = p.system.road_scale, guide_scale = p.system.guide_scale;
  p.system = builder.finish(unknowns);
  p.system.road_rows = road_rows;
  p.system.guide_row_begin = guide_begin;
  p.system.road_scale = road_scale;
  p.system.guide_scale = guide_scale;
  p.normal = SparseMatrix(p.system.A.transpose() * p.system.A);
  p.rest_unknowns = rest_vector(p.rest, p.column, unknowns);
  p.assembly_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

Prepared prepare_grid(const PlanarNetwork& net, grid::Grid g, const std::vector<std::uint32_t>& guide_nodes,
                      const Weights& w, Boundary boundary) {
  auto start = Clock::now();
  Prepared p;
  p.method = Method::grid;
  p.guide_nodes = guide_nodes;
  p.rest = g.vertices;

  // Unknowns: every vertex coordinate, except the outline's (fixed) or its normal one (sliding).
  double x0 = g.origin.x, y0 = g.origin.y, x1 = g.origin.x + g.cols * g.cell, y1 = g.origin.y + g.rows * g.cell;
  double eps = g.cell * 1e-9;
  p.column.assign(g.vertices.size(), {0, 0});
  for (std::size_t i = 0; i < g.vertices.size(); ++i) {
    if (!g.on_boundary[i]) continue;
    if (boundary == Boundary::fixed) {
      p.column[i] = {-1, -1};
      continue;
    }
    const auto& v = g.vertices[i];
    bool on_vertical = std::abs(v.x - x0) < eps || std::abs(v.x - x1) < eps;
    bool on_horizontal = std::abs(v.y - y0) < eps || std::abs(v.y - y1) < eps;
    p.column[i] = {on_vertical ? -1 : 0, on_horizontal ? -1 : 0};
  }
  int unknowns = number_unknowns(p.column);

  p.embeddings.reserve(net.nodes.size());
  for (const auto& node : net.nodes) p.embeddings.push_back(grid::embed(g, node));
  p.edge_samples = sample_edges(g, net);

  SystemBuilder b(p.rest, p.column);
  p.system.road_scale = std::sqrt(w.road);
  p.system.guide_scale = std::sqrt(w.guide);
  add_road_rows(b, net, &p.embeddings, &g, p.system.road_scale);  // eq. 4.2 / 4.9
  p.system.road_rows = b.rows();

  // The grid terms measure strain times quad size, the road terms strain times edge length; to
  // make the weights mean the same on any network and grid, the grid terms are scaled by
  // kappa = sum |road edge|^2 / sum quad side^2 (equal total stiffness at equal strain when
  // w_QE = w_RE).
  double road_sq = 0.0, quad_sq = 0.0;
  for (const auto& [u, v] : net.edges)
    road_sq += (net.nodes[u].x - net.nodes[v].x) * (net.nodes[u].x - net.nodes[v].x) +
               (net.nodes[u].y - net.nodes[v].y) * (net.nodes[u].y - net.nodes[v].y);
  for (const auto& q : g.quads) quad_sq += q.size * q.size;
  double kappa = road_sq > 0 && quad_sq > 0 ? road_sq / quad_sq : 1.0;

  // Quad shape (eq. 4.3): every side A_i relates to the bottom side B by its original similarity.
  double quad_scale = std::sqrt(w.quad * kappa);
  for (const auto& q : g.quads) {
    const auto& c = q.corners;
    Vec B{{{c[1], 1.0}, {c[0], -1.0}}};
    XY b0 = eval(B, p.rest);
    for (int side = 1; side < 4; ++side) {
      Vec A{{{c[(side + 1) % 4], 1.0}, {c[side], -1.0}}};
      add_shape_rows(b, B, A, similarity(eval(A, p.rest), b0), quad_scale);
    }
  }
  // Support edges (4.4.1): from a coarse quad's centroid to each T-junction on its sides, with
  // the same shape objective, so T-junctions stay on the coarse quad's outline (no cracks).
  for (const auto& t : g.tjunctions) {
    const auto& c = g.quads[t.coarse_quad].corners;
    Vec B{{{c[1], 1.0}, {c[0], -1.0}}};
    Vec S{{{t.vertex, 1.0}, {c[0], -0.25}, {c[1], -0.25}, {c[2], -0.25}, {c[3], -0.25}}};
    add_shape_rows(b, B, S, similarity(eval(S, p.rest), eval(B, p.rest)), quad_scale);
  }
  p.support_edges = g.tjunctions.size();

  // Laplacian smoothing (eq. 4.4) over the orthogonal neighbours; a T-junction's fourth
  // neighbour is the centroid of the bigger quad. The row keeps each vertex's rest Laplacian
  // (it measures change), and on a sliding outline only the tangential component is smoothed
  // (the paper's anti-shrink projection after Taubin): the normal one is fixed there anyway.
  double smooth_scale = std::sqrt(w.smooth * kappa);
  for (std::uint32_t v = 0; v < g.vertices.size(); ++v) {
    if (p.column[v][0] < 0 && p.column[v][1] < 0) continue;
    Vec L{{{v, 1.0}}};
    int n = 0;
    for (const auto& nb : g.neighbors[v]) n += nb.kind != grid::Neighbor::Kind::none;
    for (const auto& nb : g.neighbors[v]) {
      if (nb.kind == grid::Neighbor::Kind::vertex) L.terms.push_back({nb.index, -1.0 / n});
      if (nb.kind == grid::Neighbor::Kind::quad_centroid)
        for (auto corner : g.quads[nb.index].corners) L.terms.push_back({corner, -0.25 / n});
    }
    XY delta = eval(L, p.rest);
    for (int axis = 0; axis < 2; ++axis) {
      if (p.column[v][axis] < 0) continue;
      for (auto [pt, coef] : L.terms) b.add(pt, axis, coef);
      b.end_row(smooth_scale, axis == 0 ? delta.x : delta.y);
    }
  }

  p.system.guide_row_begin = b.rows();
  add_guide_rows(b, guide_nodes, &p.embeddings, &g, p.system.guide_scale);  // eq. 4.7
  p.grid = std::move(g);
  finish_prepared(p, unknowns, b, start);
  return p;
}

Prepared prepare_edges(const PlanarNetwork& net, const std::vector<std::uint32_t>& guide_nodes, const Weights& w) {
  auto start = Clock::now();
  Prepared p;
  p.method = Method::edges;
  p.guide_nodes = guide_nodes;
  p.rest = net.nodes;
  p.column.assign(net.nodes.size(), {0, 0});

  // The convex hull's nodes hold the outline.
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Traits = CGAL::Convex_hull_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  std::vector<Kernel::Point_2> pts;
  pts.reserve(net.nodes.size());
  for (const auto& n : net.nodes) pts.emplace_back(n.x, n.y);
  std::vector<std::size_t> indices(pts.size()), hull;
  std::iota(indices.begin(), indices.end(), 0);
  CGAL::convex_hull_2(indices.begin(), indices.end(), std::back_inserter(hull),
                      Traits(CGAL::make_property_map(pts)));
  for (auto i : hull) p.column[i] = {-1, -1};
  for (auto g : guide_nodes) p.column[g] = {0, 0};  // a guide vertex must be free to follow its target
  int unknowns = number_unknowns(p.column);

  SystemBuilder b(p.rest, p.column);
  p.system.road_scale = std::sqrt(w.road);
  p.system.guide_scale = std::sqrt(w.guide);
  add_road_rows(b, net, nullptr, nullptr, p.system.road_scale);  // eq. 4.1 / 4.8
  p.system.road_rows = b.rows();
  p.system.guide_row_begin = b.rows();
  add_guide_rows(b, guide_nodes, nullptr, nullptr, p.system.guide_scale);
  // A faint pull to rest: components without a hull node would otherwise float freely.
  const double anchor = 1e-3;  // sqrt(1e-6)
  for (std::uint32_t i = 0; i < net.nodes.size(); ++i)
    for (int axis = 0; axis < 2; ++axis) {
      if (p.column[i][axis] < 0) continue;
      b.add(i, axis, 1.0);
      b.end_row(anchor, axis == 0 ? net.nodes[i].x : net.nodes[i].y);
    }
  finish_prepared(p, unknowns, b, start);
  return p;
}

Eigen::VectorXd right_hand_side(const Prepared& p, const PlanarNetwork& net, const Targets& targets) {
  const auto& s = p.system;
  Eigen::VectorXd b = s.base_target;
  // Road rows carry the rest edge vector as target; the request scales it (s_i, eq. 4.9).
  if (!targets.edge_scale.empty())
    for (std::size_t i = 0; i < net.edges.size(); ++i) {
      b[static_cast<Eigen::Index>(2 * i)] *= targets.edge_scale[i];
      b[static_cast<Eigen::Index>(2 * i + 1)] *= targets.edge_scale[i];
    }
  // Guide rows: targets in the order of p.guide_nodes.
  for (std::size_t g = 0; g < targets.guides.size() && g < p.guide_nodes.size(); ++g) {
    b[static_cast<Eigen::Index>(s.guide_row_begin + 2 * g)] = s.guide_scale * targets.guides[g].target.x;
    b[static_cast<Eigen::Index>(s.guide_row_begin + 2 * g + 1)] = s.guide_scale * targets.guides[g].target.y;
  }
  return s.A.transpose() * (b - s.fixed_part);
}

std::vector<XY> points_from(const Prepared& p, const Eigen::VectorXd& x) {
  std::vector<XY> pts = p.rest;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (p.column[i][0] >= 0) pts[i].x = x[p.column[i][0]];
    if (p.column[i][1] >= 0) pts[i].y = x[p.column[i][1]];
  }
  return pts;
}

std::vector<XY> road_nodes_from(const Prepared& p, const std::vector<XY>& points) {
  if (p.method == Method::edges) return points;
  std::vector<XY> nodes;
  nodes.reserve(p.embeddings.size());
  for (const auto& e : p.embeddings) nodes.push_back(grid::place(*p.grid, points, e));
  return nodes;
}

}  // namespace tourmap::deform
