#include "crowd/pose_selection.hpp"

#include "crowd/mds.hpp"
#include "crowd/skeleton_root.hpp"
#include "crowd/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tourmap::crowd {
namespace {

constexpr Eigen::Index kMaxGroupPoints = 20000;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
};

double bbox_diagonal(const Eigen::MatrixXd& points, const std::vector<int>& group, Eigen::Index* longest_axis) {
  Eigen::RowVectorXd lo = points.row(group[0]), hi = lo;
  for (int i : group) {
    lo = lo.cwiseMin(points.row(i));
    hi = hi.cwiseMax(points.row(i));
  }
  const Eigen::RowVectorXd extent = hi - lo;
  if (longest_axis) extent.maxCoeff(longest_axis);
  return extent.norm();
}

}  // namespace

std::vector<std::vector<int>> group_poses(const Eigen::MatrixXd& points, double d) {
  const Eigen::Index n = points.rows();
  if (!std::isfinite(d) || d < 0) throw std::invalid_argument("group_poses: d must be finite and >= 0");
  if (!points.allFinite()) throw std::invalid_argument("group_poses: non-finite point");
  if (n > kMaxGroupPoints)
    throw std::invalid_argument("group_poses: " + std::to_string(n) + " points, more than " +
                                std::to_string(kMaxGroupPoints));
  if (n == 0) return {};
  if (points.cols() == 0) throw std::invalid_argument("group_poses: points have no coordinates");

  // Clustering stage: groups with any two points within d merge (transitively).
  UnionFind uf(static_cast<std::size_t>(n));
  const double d2 = d * d;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j)
      if ((points.row(i) - points.row(j)).squaredNorm() <= d2) uf.unite(static_cast<int>(i), static_cast<int>(j));
  std::vector<std::vector<int>> clusters(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    clusters[static_cast<std::size_t>(uf.find(static_cast<int>(i)))].push_back(static_cast<int>(i));

  // Partitioning stage: split groups whose bbox diagonal exceeds 1.5 d at the median of the
  // longest axis. Each split halves the group, so this ends after O(n log n) work.
  std::vector<std::vector<int>> work, out;
  for (auto& c : clusters)
    if (!c.empty()) work.push_back(std::move(c));
  while (!work.empty()) {
    std::vector<int> g = std::move(work.back());
    work.pop_back();
    Eigen::Index axis = 0;
    if (g.size() < 2 || bbox_diagonal(points, g, &axis) <= 1.5 * d) {
      out.push_back(std::move(g));
      continue;
    }
    std::sort(g.begin(), g.end(), [&](int a, int b) {
      return points(a, axis) != points(b, axis) ? points(a, axis) < points(b, axis) : a < b;
    });
    const auto mid = g.begin() + static_cast<std::ptrdiff_t>(g.size() / 2);
    std::vector<int> low(g.begin(), mid), high(mid, g.end());
    std::sort(low.begin(), low.end());
    std::sort(high.begin(), high.end());
    work.push_back(std::move(low));
    work.push_back(std::move(high));
  }
  std::vector<std::pair<int, std::size_t>> order;
  for (std::size_t i = 0; i < out.size(); ++i) order.emplace_back(representative(points, out[i]), i);
  std::sort(order.begin(), order.end());
  std::vector<std::vector<int>> sorted;
  for (const auto& [rep, i] : order) sorted.push_back(std::move(out[i]));
  return sorted;
}

int representative(const Eigen::MatrixXd& points, const std::vector<int>& group) {
  if (group.empty()) throw std::invalid_argument("representative: empty group");
  for (int i : group)
    if (i < 0 || i >= points.rows())
      throw std::out_of_range("representative: point " + std::to_string(i) + " out of range");
  Eigen::RowVectorXd lo = points.row(group[0]), hi = lo;
  for (int i : group) {
    lo = lo.cwiseMin(points.row(i));
    hi = hi.cwiseMax(points.row(i));
  }
  const Eigen::RowVectorXd centre = 0.5 * (lo + hi);
  int best = group[0];
  double best_d2 = (points.row(best) - centre).squaredNorm();
  for (int i : group) {
    const double d2 = (points.row(i) - centre).squaredNorm();
    if (d2 < best_d2 || (d2 == best_d2 && i < best)) {
      best = i;
      best_d2 = d2;
    }
  }
  return best;
}

Eigen::MatrixXd pose_distances(const SkinnedModel& model, int animation, std::size_t max_samples) {
  if (animation < 0 || static_cast<std::size_t>(animation) >= model.animations.size())
    throw std::out_of_range("pose_distances: animation " + std::to_string(animation) + " of " +
                            std::to_string(model.animations.size()));
  if (max_samples == 0) throw std::invalid_argument("pose_distances: max_samples must be > 0");
  const auto& poses = model.animations[static_cast<std::size_t>(animation)].poses;
  const std::size_t p = poses.size(), n = model.positions.size();
  const std::size_t s = std::min(n, max_samples);
  if (p == 0) return Eigen::MatrixXd(0, 0);
  if (s == 0) return Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));

  const int root = main_root_joint(model.skeleton.parent);
  const bool has_root_frames = root >= 0 && std::all_of(poses.begin(), poses.end(), [&](const Pose& q) {
                                 return q.global.size() == model.skeleton.parent.size();
                               });
  std::vector<Vec3> posed;
  // Pose k's sample with root motion and centroid removed, one column per sampled vertex.
  std::vector<Eigen::Matrix3Xd> samples(p, Eigen::Matrix3Xd(3, static_cast<Eigen::Index>(s)));
  for (std::size_t k = 0; k < p; ++k) {
    skin_positions(model, poses[k], posed);
    Eigen::Affine3d to_frame0 = Eigen::Affine3d::Identity();
    if (has_root_frames)
      to_frame0 = poses[0].global[static_cast<std::size_t>(root)].cast<double>() *
                  poses[k].global[static_cast<std::size_t>(root)].cast<double>().inverse();
    Eigen::Matrix3Xd& q = samples[k];
    for (std::size_t i = 0; i < s; ++i)
      q.col(static_cast<Eigen::Index>(i)) = to_frame0 * posed[i * n / s].cast<double>();
    q.colwise() -= q.rowwise().mean();
  }
  Eigen::MatrixXd dist = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = a + 1; b < p; ++b) {
      const double d = std::sqrt((samples[a] - samples[b]).colwise().squaredNorm().maxCoeff());
      dist(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = d;
      dist(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(a)) = d;
    }
  return dist;
}

PoseSelection select_poses(const SkinnedModel& model, int animation, float d_fraction, int dims) {
  if (!std::isfinite(d_fraction) || d_fraction < 0)
    throw std::invalid_argument("select_poses: d_fraction must be finite and >= 0");
  if (dims < 1) throw std::invalid_argument("select_poses: dims must be >= 1");
  PoseSelection sel;
  const Eigen::MatrixXd dist = pose_distances(model, animation);
  sel.pose_count = static_cast<std::size_t>(dist.rows());
  sel.sample_vertices = std::min(model.positions.size(), kPoseDistanceSamples);
  Box3 bind;
  for (const Vec3& v : model.positions) bind.extend(v);
  sel.d = model.positions.empty() ? 0.0 : d_fraction * static_cast<double>(bind.diagonal().norm());
  sel.points = classical_mds(dist, dims);  // pose space reduction (sec. 3.4)
  sel.groups = group_poses(sel.points, sel.d);
  for (const auto& g : sel.groups) sel.representatives.push_back(representative(sel.points, g));
  return sel;
}

}  // namespace tourmap::crowd
