#include "crowd/triangle_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tourmap::crowd {
namespace {

constexpr std::uint32_t leaf_triangles = 4;

using Vec3d = Eigen::Vector3d;

double point_segment_distance_sq(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double t = len_sq > 0 ? std::clamp((p - a).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).squaredNorm();
}

double edges_distance_sq(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return std::min({point_segment_distance_sq(p, a, b), point_segment_distance_sq(p, b, c),
                   point_segment_distance_sq(p, c, a)});
}

float box_distance_sq(const Vec3& q, const Box3& box) {
  return (box.min() - q).cwiseMax(q - box.max()).cwiseMax(0.f).squaredNorm();
}

}  // namespace

// In double: simplified clusters have long slivers, where float barycentrics lose ~1e-5 m.
float point_triangle_distance_sq(const Vec3& pf, const Vec3& af, const Vec3& bf, const Vec3& cf) {
  const Vec3d p = pf.cast<double>(), a = af.cast<double>(), b = bf.cast<double>(), c = cf.cast<double>();
  const Vec3d ab = b - a, ac = c - a;
  const Vec3d normal = ab.cross(ac);
  if (!(normal.squaredNorm() > 0)) return static_cast<float>(edges_distance_sq(p, a, b, c));  // degenerate
  // Voronoi regions of the corners, then the edges, then the face (Ericson 5.1.5).
  const Vec3d ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return static_cast<float>(ap.squaredNorm());
  const Vec3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return static_cast<float>(bp.squaredNorm());
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return static_cast<float>(point_segment_distance_sq(p, a, b));
  const Vec3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return static_cast<float>(cp.squaredNorm());
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return static_cast<float>(point_segment_distance_sq(p, a, c));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return static_cast<float>(point_segment_distance_sq(p, b, c));
  // Inside the face's prism: the distance to the plane (more robust than rebuilding the
  // closest point from barycentrics).
  const double height = normal.dot(ap);
  return static_cast<float>(height * height / normal.squaredNorm());
}

void TriangleBvh::build(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& indices) {
  if (indices.size() % 3 != 0)
    throw std::invalid_argument("TriangleBvh: index count " + std::to_string(indices.size()) + " is not a multiple of 3");
  corners_.clear();
  centroids_.clear();
  nodes_.clear();
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    std::array<Vec3, 3> tri;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = indices[t + k];
      if (v >= positions.size())
        throw std::invalid_argument("TriangleBvh: vertex " + std::to_string(v) + " out of range (" +
                                    std::to_string(positions.size()) + " positions)");
      tri[k] = positions[v];
    }
    corners_.push_back(tri);
    centroids_.push_back((tri[0] + tri[1] + tri[2]) / 3.f);
  }
  if (corners_.empty()) return;
  order_.resize(corners_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<std::uint32_t>(i);
  nodes_.reserve(2 * corners_.size() / leaf_triangles + 2);
  build_node(0, static_cast<std::uint32_t>(corners_.size()));
  // Leaves in order_ order, so a leaf's triangles are contiguous in memory.
  leaf_triangles_.clear();
  for (std::uint32_t i : order_) leaf_triangles_.emplace_back(corners_[i]);
}

TriangleBvh::Prepared::Prepared(const std::array<Vec3, 3>& corners)
    : a(corners[0].cast<double>()),
      ab(corners[1].cast<double>() - a),
      ac(corners[2].cast<double>() - a),
      normal(ab.cross(ac)),
      ab_ab(ab.squaredNorm()),
      ac_ac(ac.squaredNorm()),
      ab_ac(ab.dot(ac)),
      normal_sq(normal.squaredNorm()),
      degenerate(!(normal_sq > 0)) {}

// point_triangle_distance_sq with the per-triangle products precomputed: with ap = p - a,
// bp = ap - ab and cp = ap - ac, Ericson's d3..d6 follow from d1 = ab.ap and d2 = ac.ap.
double TriangleBvh::Prepared::distance_sq(const Eigen::Vector3d& p) const {
  const Vec3d ap = p - a;
  if (degenerate) return edges_distance_sq(p, a, a + ab, a + ac);
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const double d3 = d1 - ab_ab, d4 = d2 - ab_ac;
  if (d3 >= 0 && d4 <= d3) return (ap - ab).squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - (d1 / ab_ab) * ab).squaredNorm();
  const double d5 = d1 - ab_ac, d6 = d2 - ac_ac;
  if (d6 >= 0 && d5 <= d6) return (ap - ac).squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - (d2 / ac_ac) * ac).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (ap - ab - t * (ac - ab)).squaredNorm();
  }
  const double height = normal.dot(ap);
  return height * height / normal_sq;
}

// Median split along the longest axis of the centroids' box, on the range [first, first + count)
// of order_; depth stays <= log2(n) + 1.
std::uint32_t TriangleBvh::build_node(std::uint32_t first, std::uint32_t count) {
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Box3 box, centre_box;
  for (std::uint32_t i = first; i < first + count; ++i) {
    for (const Vec3& x : corners_[order_[i]]) box.extend(x);
    centre_box.extend(centroids_[order_[i]]);
  }
  nodes_[id].box = box;
  if (count <= leaf_triangles) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  int axis = 0;
  centre_box.sizes().maxCoeff(&axis);
  const std::uint32_t half = count / 2;
  const auto begin = order_.begin() + first;
  std::nth_element(begin, begin + half, begin + count, [&](std::uint32_t x, std::uint32_t y) {
    return centroids_[x][axis] < centroids_[y][axis];
  });
  build_node(first, half);
  const std::uint32_t right = build_node(first + half, count - half);
  nodes_[id].first = right;
  nodes_[id].count = 0;
  return id;
}

float TriangleBvh::distance(const Vec3& q, float enough, std::uint32_t* hint) const {
  float best = std::numeric_limits<float>::infinity();  // squared
  if (nodes_.empty()) return best;
  const float enough_sq = enough > 0 ? enough * enough : 0.f;
  std::uint32_t best_triangle = 0;
  const Eigen::Vector3d qd = q.cast<double>();
  auto test = [&](std::uint32_t i) {
    const auto d = static_cast<float>(leaf_triangles_[i].distance_sq(qd));
    if (d < best) {
      best = d;
      best_triangle = i;
    }
  };
  auto finish = [&] {
    if (hint) *hint = best_triangle;
    return std::sqrt(best);
  };
  if (hint && *hint < leaf_triangles_.size()) {
    test(*hint);
    if (best <= enough_sq) return finish();
  }
  // Nearest child first; the stack holds at most one entry per level plus one (median splits
  // keep the depth <= 33 for any 32-bit count).
  struct Entry {
    std::uint32_t node;
    float box_sq;
  };
  std::array<Entry, 64> stack;  // left uninitialized: only pushed entries are read
  std::size_t size = 0;
  stack[size++] = {0, box_distance_sq(q, nodes_[0].box)};
  while (size > 0) {
    const auto [n, box_sq] = stack[--size];
    if (box_sq >= best) continue;
    const Node& node = nodes_[n];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        test(i);
        if (best <= enough_sq) return finish();
      }
      continue;
    }
    const std::uint32_t left = n + 1, right = node.first;
    const float left_sq = box_distance_sq(q, nodes_[left].box), right_sq = box_distance_sq(q, nodes_[right].box);
    const bool left_first = left_sq <= right_sq;
    const Entry near{left_first ? left : right, left_first ? left_sq : right_sq};
    const Entry far{left_first ? right : left, left_first ? right_sq : left_sq};
    if (far.box_sq < best) stack[size++] = far;
    if (near.box_sq < best) stack[size++] = near;
  }
  return finish();
}

}  // namespace tourmap::crowd
