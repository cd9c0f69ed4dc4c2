#pragma once
// One model with its cluster hierarchy on the GPU (sec. 3.5): a vertex buffer with the skinning
// data, one index buffer holding every cluster's triangles (a cluster is an index range; the
// ranges are laid out anew, see clusters_in_index_order), and the
// skinning matrices of every sampled pose of every animation in one texture buffer, as the paper
// keeps "all the transformation matrices of bones ... with all the poses in a 1D texture buffer"
// (sec. 3.6). Needs the owning EglContext current for its whole life.

#include "crowd/cluster_hierarchy.hpp"
#include "crowd/cut_tree.hpp"
#include "crowd/skinned_model.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace tourmap::render {

// Vertex attribute locations and the binding of the per-draw item stream (see CrowdRenderer).
inline constexpr unsigned kItemBinding = 1;
inline constexpr unsigned kItemAttribute = 5;

class GpuModel {
 public:
  // Throws std::invalid_argument naming what is inconsistent (array sizes, index or joint out of
  // range, malformed hierarchy, no pose) and std::runtime_error when the GPU limits are exceeded.
  GpuModel(const crowd::SkinnedModel& model, const crowd::ClusterHierarchy& hierarchy);
  ~GpuModel();
  GpuModel(const GpuModel&) = delete;
  GpuModel& operator=(const GpuModel&) = delete;

  // The hierarchy without its index array (which lives on the GPU), for the CPU-side LOD cut.
  const crowd::ClusterHierarchy& hierarchy() const { return hierarchy_; }
  // The hierarchy flattened for the per-frame LOD cut (crowd::cut_instances).
  const crowd::CutTree& cut_tree() const { return cut_tree_; }
  // Bounds of each cluster's whole subtree (its own bounds joined with its descendants'): the
  // conservative box for occlusion queries, as a simplified cluster may not cover its children.
  const std::vector<crowd::Box3>& subtree_bounds() const { return subtree_bounds_; }
  // Cluster ids in the order of their triangles in the index buffer: leaves in depth-first order,
  // then inner clusters by depth, left to right. Siblings and cousins are neighbours, so the
  // renderer can merge the draws of adjacent clusters drawn for the same instances.
  const std::vector<int>& clusters_in_index_order() const { return index_order_; }
  // Per cluster: 1 at a leaf, 0 at the root, depth / (depth + height) between (Fig. 3.11 heatmap).
  const std::vector<float>& fineness() const { return fineness_; }

  int joint_count() const { return joint_count_; }
  int animation_count() const { return static_cast<int>(animation_first_matrix_.size()); }
  int frame_count(int animation) const;
  // Index of the first skinning matrix of (animation, frame) in the palette; throws
  // std::invalid_argument when either is out of range.
  std::uint32_t palette_base(int animation, int frame) const;
  bool is_static() const { return is_static_; }
  const std::string& name() const { return name_; }

  unsigned vertex_array() const { return vao_; }
  unsigned palette_texture() const { return palette_texture_; }

 private:
  void release();

  std::string name_;
  crowd::ClusterHierarchy hierarchy_;
  crowd::CutTree cut_tree_;
  std::vector<crowd::Box3> subtree_bounds_;
  std::vector<float> fineness_;
  std::vector<int> index_order_;
  std::vector<std::uint32_t> animation_first_matrix_;
  std::vector<int> animation_frames_;
  int joint_count_ = 0;
  bool is_static_ = false;
  unsigned vao_ = 0, vertex_buffer_ = 0, index_buffer_ = 0, palette_buffer_ = 0, palette_texture_ = 0;
};

}  // namespace tourmap::render
