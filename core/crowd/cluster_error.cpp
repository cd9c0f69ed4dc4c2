#include "crowd/cluster_error.hpp"

#include "crowd/skinning.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace tourmap::crowd {
namespace {

void require_in_range(const std::vector<std::uint32_t>& ids, std::size_t n, const char* what) {
  for (std::uint32_t v : ids)
    if (v >= n)
      throw std::invalid_argument(std::string("max_distance_to_simplified: ") + what + " vertex " + std::to_string(v) +
                                  " out of range (" + std::to_string(n) + " vertices)");
}

constexpr std::uint32_t no_node = std::numeric_limits<std::uint32_t>::max();

}  // namespace

std::vector<std::vector<Vec3>> posed_positions(const SkinnedModel& m, const std::vector<const Pose*>& poses) {
  std::vector<std::vector<Vec3>> out(poses.size());
  for (std::size_t p = 0; p < poses.size(); ++p) {
    if (m.weights.empty() || poses[p]->skinning.empty())
      out[p] = m.positions;
    else
      skin_positions(m, *poses[p], out[p]);
  }
  return out;
}

float max_distance_to_simplified(const std::vector<std::vector<Vec3>>& posed,
                                 const std::vector<std::uint32_t>& simplified,
                                 const std::vector<std::uint32_t>& sample_vertices,
                                 const std::vector<std::uint32_t>& sample_triangles, float known, TriangleBvh& bvh) {
  if (sample_triangles.size() % 3 != 0)
    throw std::invalid_argument("max_distance_to_simplified: sample triangle index count not a multiple of 3");
  if ((sample_vertices.empty() && sample_triangles.empty()) || posed.empty()) return 0;
  if (simplified.empty()) throw std::invalid_argument("max_distance_to_simplified: samples but no triangles");
  const std::size_t n = posed[0].size();
  for (const auto& pose : posed)
    if (pose.size() != n) throw std::invalid_argument("max_distance_to_simplified: poses with different vertex counts");
  require_in_range(sample_vertices, n, "sample");
  require_in_range(sample_triangles, n, "sample triangle");
  float result = 0;
  for (const auto& x : posed) {
    bvh.build(x, simplified);  // checks the simplified triangles' ids
    std::uint32_t hint = 0;    // consecutive samples are neighbours (listed leaf by leaf)
    for (std::uint32_t v : sample_vertices) result = std::max(result, bvh.distance(x[v], std::max(known, result), &hint));
    for (std::size_t t = 0; t < sample_triangles.size(); t += 3) {
      const Vec3 centroid = (x[sample_triangles[t]] + x[sample_triangles[t + 1]] + x[sample_triangles[t + 2]]) / 3.f;
      result = std::max(result, bvh.distance(centroid, std::max(known, result), &hint));
    }
  }
  return result;
}

HausdorffMeter::HausdorffMeter(const SkinnedModel& m, const std::vector<std::uint32_t>& canonical,
                               const std::vector<const Pose*>& poses, std::size_t node_count, float resolution)
    : canonical_(canonical),
      posed_(posed_positions(m, poses)),
      resolution_(resolution),
      vertices_(node_count),
      triangles_(node_count),
      listed_by_(m.vertex_count(), no_node),
      kept_by_(m.vertex_count(), no_node) {
  if (canonical.size() != m.vertex_count())
    throw std::invalid_argument("HausdorffMeter: canonical map does not match the vertex count");
}

void HausdorffMeter::add_leaf(std::size_t node, const std::vector<std::uint32_t>& triangles) {
  triangles_.at(node) = triangles;
  for (std::uint32_t v : triangles) {
    const std::uint32_t c = canonical_.at(v);
    if (listed_by_[c] == node) continue;
    listed_by_[c] = static_cast<std::uint32_t>(node);
    vertices_[node].push_back(c);
  }
}

float HausdorffMeter::measure_parent(std::size_t node, const std::array<int, 2>& children,
                                     const std::vector<std::uint32_t>& simplified, float known) {
  auto& vertices = vertices_.at(node);
  auto& triangles = triangles_.at(node);
  for (int child : children) {
    auto& child_vertices = vertices_.at(static_cast<std::size_t>(child));
    auto& child_triangles = triangles_.at(static_cast<std::size_t>(child));
    for (std::uint32_t c : child_vertices) {  // a vertex both children use is listed once
      if (listed_by_[c] == node) continue;
      listed_by_[c] = static_cast<std::uint32_t>(node);
      vertices.push_back(c);
    }
    triangles.insert(triangles.end(), child_triangles.begin(), child_triangles.end());
    std::vector<std::uint32_t>().swap(child_vertices);
    std::vector<std::uint32_t>().swap(child_triangles);
  }
  // Vertices the simplified triangles kept are at distance 0 in every pose.
  for (std::uint32_t v : simplified) kept_by_[canonical_.at(v)] = static_cast<std::uint32_t>(node);
  removed_.clear();
  for (std::uint32_t c : vertices)
    if (kept_by_[c] != node) removed_.push_back(c);
  return max_distance_to_simplified(posed_, simplified, removed_, triangles, std::max(known, resolution_), bvh_);
}

}  // namespace tourmap::crowd
