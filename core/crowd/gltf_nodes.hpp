#pragma once
// The glTF node tree (validated: every node has at most one parent and there are no cycles),
// node-local TRS transforms and global transforms G = G_parent * T * R * S, plus animation
// channels sampled at a time t (LINEAR with quaternion slerp, STEP, CUBICSPLINE).
// Computation is in double; the loader rounds the results to float.

#include "crowd/gltf_accessor.hpp"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace tourmap::crowd::gltf {

struct NodeTrs {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  bool has_matrix = false;  // a `matrix` node; glTF forbids animating it
  Eigen::Affine3d matrix = Eigen::Affine3d::Identity();
  Eigen::Affine3d local() const;
};

struct NodeGraph {
  std::vector<int> parent;       // -1 for a root
  std::vector<int> topological;  // every node, each after its parent
  std::vector<NodeTrs> rest;     // the file's node transforms (no animation applied)
};

NodeGraph build_node_graph(const ReadContext& ctx);

// Global transform of every node for the given local transforms (indexed like graph.parent).
std::vector<Eigen::Affine3d> global_transforms(const NodeGraph& graph, const std::vector<NodeTrs>& locals);

// Nodes of the default scene (scene 0 if none is marked; every root if the file has no scene),
// each followed by its subtree (pre-order).
std::vector<int> scene_nodes(const ReadContext& ctx, const NodeGraph& graph);

// True when `ancestor` is `node` or one of its ancestors.
bool is_ancestor_or_self(const NodeGraph& graph, int ancestor, int node);

enum class ChannelPath { translation, rotation, scale };
enum class Interpolation { linear, step, cubic_spline };

struct Channel {
  int node = -1;
  ChannelPath path = ChannelPath::translation;
  Interpolation interpolation = Interpolation::linear;
  std::vector<float> times;  // non-decreasing
  FloatAccessor values;      // one value per time; three (in-tangent, value, out-tangent) for cubic
};

struct AnimationClip {
  std::string name;
  float duration_s = 0;           // the largest key time
  std::vector<Channel> channels;  // T/R/S only; morph-target `weights` channels are skipped
};

AnimationClip read_animation(const ReadContext& ctx, int animation, const NodeGraph& graph);

// Overwrites the animated properties of `locals` with the clip's values at time t
// (before the first key: the first value; after the last: the last value).
void apply_clip(const AnimationClip& clip, float t, std::vector<NodeTrs>& locals);

}  // namespace tourmap::crowd::gltf
