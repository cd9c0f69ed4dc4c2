#include "crowd/gltf_nodes.hpp"

#include "load/load_error.hpp"

#include <algorithm>
#include <cmath>

namespace tourmap::crowd::gltf {
namespace {

[[noreturn]] void fail(const ReadContext& ctx, const std::string& problem) { throw load::LoadError(ctx.file, problem); }

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

NodeTrs read_trs(const ReadContext& ctx, const tinygltf::Node& node, std::size_t index) {
  const std::string where = "node " + std::to_string(index);
  NodeTrs trs;
  if (!all_finite(node.translation) || !all_finite(node.rotation) || !all_finite(node.scale) ||
      !all_finite(node.matrix))
    fail(ctx, where + " has a non-finite transform");
  if (node.matrix.size() == 16) {
    trs.has_matrix = true;
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(c * 4 + r)];  // column-major
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
      fail(ctx, where + " has a matrix that is not affine (last row must be 0 0 0 1)");
    trs.matrix.matrix() = m;
    return trs;
  }
  if (!node.matrix.empty()) fail(ctx, where + " has a matrix that is not 4x4");
  if (node.translation.size() == 3)
    trs.translation = {node.translation[0], node.translation[1], node.translation[2]};
  else if (!node.translation.empty())
    fail(ctx, where + " translation does not have 3 values");
  if (node.rotation.size() == 4) {
    // glTF stores x, y, z, w.
    trs.rotation = Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (trs.rotation.norm() < 1e-6) fail(ctx, where + " rotation is a zero quaternion");
    trs.rotation.normalize();
  } else if (!node.rotation.empty()) {
    fail(ctx, where + " rotation does not have 4 values");
  }
  if (node.scale.size() == 3)
    trs.scale = {node.scale[0], node.scale[1], node.scale[2]};
  else if (!node.scale.empty())
    fail(ctx, where + " scale does not have 3 values");
  return trs;
}

Eigen::Vector4d value4(const FloatAccessor& a, std::size_t element) {
  Eigen::Vector4d v = Eigen::Vector4d::Zero();
  for (int c = 0; c < a.components && c < 4; ++c) v[c] = a.at(element, c);
  return v;
}

Eigen::Quaterniond as_quaternion(const Eigen::Vector4d& xyzw) {
  Eigen::Quaterniond q(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
  const double n = q.norm();
  return n > 1e-12 ? Eigen::Quaterniond(q.coeffs() / n) : Eigen::Quaterniond::Identity();
}

void store(const Channel& ch, const Eigen::Vector4d& v, NodeTrs& trs) {
  switch (ch.path) {
    case ChannelPath::translation:
      trs.translation = v.head<3>();
      break;
    case ChannelPath::scale:
      trs.scale = v.head<3>();
      break;
    case ChannelPath::rotation:
      trs.rotation = as_quaternion(v);
      break;
  }
}

// The channel's value at time t.
Eigen::Vector4d sample(const Channel& ch, float t) {
  const std::size_t n = ch.times.size();
  const bool cubic = ch.interpolation == Interpolation::cubic_spline;
  auto key_value = [&](std::size_t k) { return value4(ch.values, cubic ? 3 * k + 1 : k); };
  if (n == 1 || t <= ch.times.front()) return key_value(0);
  if (t >= ch.times.back()) return key_value(n - 1);
  // First key strictly after t; t lies in [times[k], times[k+1]).
  const std::size_t k1 =
      static_cast<std::size_t>(std::upper_bound(ch.times.begin(), ch.times.end(), t) - ch.times.begin());
  const std::size_t k = k1 - 1;
  const double dt = static_cast<double>(ch.times[k1]) - ch.times[k];
  if (ch.interpolation == Interpolation::step || dt <= 0) return key_value(k);
  const double s = (t - ch.times[k]) / dt;
  if (ch.interpolation == Interpolation::linear) {
    if (ch.path == ChannelPath::rotation) {
      const Eigen::Quaterniond q = as_quaternion(key_value(k)).slerp(s, as_quaternion(key_value(k1)));
      return {q.x(), q.y(), q.z(), q.w()};
    }
    return (1 - s) * key_value(k) + s * key_value(k1);
  }
  // CUBICSPLINE (glTF 2.0 spec, appendix C): Hermite with tangents scaled by the key interval.
  const Eigen::Vector4d v0 = key_value(k), v1 = key_value(k1);
  const Eigen::Vector4d out0 = value4(ch.values, 3 * k + 2), in1 = value4(ch.values, 3 * k1);
  const double s2 = s * s, s3 = s2 * s;
  Eigen::Vector4d v =
      (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * dt * out0 + (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * dt * in1;
  return v;  // rotation is renormalised in store()
}

}  // namespace

Eigen::Affine3d NodeTrs::local() const {
  if (has_matrix) return matrix;
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.translate(translation);
  m.rotate(rotation);
  m.scale(scale);
  return m;
}

NodeGraph build_node_graph(const ReadContext& ctx) {
  const auto& nodes = ctx.model.nodes;
  NodeGraph g;
  g.parent.assign(nodes.size(), -1);
  g.rest.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    g.rest.push_back(read_trs(ctx, nodes[i], i));
    for (int c : nodes[i].children) {
      if (c < 0 || static_cast<std::size_t>(c) >= nodes.size())
        fail(ctx, "node " + std::to_string(i) + " has a child " + std::to_string(c) + " that does not exist");
      if (g.parent[static_cast<std::size_t>(c)] != -1 || static_cast<std::size_t>(c) == i)
        fail(ctx, "node " + std::to_string(c) + " has more than one parent (the node graph must be a tree)");
      g.parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
    }
  }
  // Breadth-first from the roots; a node never reached lies on a cycle.
  g.topological.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (g.parent[i] == -1) g.topological.push_back(static_cast<int>(i));
  for (std::size_t q = 0; q < g.topological.size(); ++q)
    for (int c : nodes[static_cast<std::size_t>(g.topological[q])].children) g.topological.push_back(c);
  if (g.topological.size() != nodes.size()) fail(ctx, "the node graph has a cycle");
  return g;
}

std::vector<Eigen::Affine3d> global_transforms(const NodeGraph& graph, const std::vector<NodeTrs>& locals) {
  std::vector<Eigen::Affine3d> global(locals.size(), Eigen::Affine3d::Identity());
  for (int n : graph.topological) {
    const std::size_t i = static_cast<std::size_t>(n);
    global[i] =
        graph.parent[i] < 0 ? locals[i].local() : global[static_cast<std::size_t>(graph.parent[i])] * locals[i].local();
  }
  return global;
}

std::vector<int> scene_nodes(const ReadContext& ctx, const NodeGraph& graph) {
  const auto& m = ctx.model;
  std::vector<int> roots;
  if (!m.scenes.empty()) {
    int s = m.defaultScene;
    if (s < 0) s = 0;
    if (static_cast<std::size_t>(s) >= m.scenes.size())
      fail(ctx, "default scene " + std::to_string(s) + " does not exist");
    for (int n : m.scenes[static_cast<std::size_t>(s)].nodes) {
      if (n < 0 || static_cast<std::size_t>(n) >= m.nodes.size())
        fail(ctx, "scene node " + std::to_string(n) + " does not exist");
      roots.push_back(n);
    }
  } else {
    for (std::size_t i = 0; i < graph.parent.size(); ++i)
      if (graph.parent[i] == -1) roots.push_back(static_cast<int>(i));
  }
  std::vector<int> out;
  std::vector<char> seen(m.nodes.size(), 0);
  for (int r : roots) {
    std::vector<int> stack{r};  // the graph is a tree, so this terminates
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[static_cast<std::size_t>(n)]) continue;  // a scene may list a node twice
      seen[static_cast<std::size_t>(n)] = 1;
      out.push_back(n);
      const auto& ch = m.nodes[static_cast<std::size_t>(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
  }
  return out;
}

bool is_ancestor_or_self(const NodeGraph& graph, int ancestor, int node) {
  for (int n = node; n >= 0; n = graph.parent[static_cast<std::size_t>(n)])
    if (n == ancestor) return true;
  return false;
}

AnimationClip read_animation(const ReadContext& ctx, int index, const NodeGraph& graph) {
  const tinygltf::Animation& a = ctx.model.animations[static_cast<std::size_t>(index)];
  AnimationClip clip;
  clip.name = a.name.empty() ? "animation " + std::to_string(index) : a.name;
  const std::string where = "animation " + std::to_string(index);
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    const tinygltf::AnimationChannel& src = a.channels[c];
    const std::string what = where + " channel " + std::to_string(c);
    Channel ch;
    if (src.target_path == "translation")
      ch.path = ChannelPath::translation;
    else if (src.target_path == "rotation")
      ch.path = ChannelPath::rotation;
    else if (src.target_path == "scale")
      ch.path = ChannelPath::scale;
    else
      continue;                         // morph-target weights (or an extension's path): the base mesh is used
    if (src.target_node < 0) continue;  // allowed by extensions that target something else
    if (static_cast<std::size_t>(src.target_node) >= graph.parent.size())
      fail(ctx, what + " targets node " + std::to_string(src.target_node) + " that does not exist");
    if (graph.rest[static_cast<std::size_t>(src.target_node)].has_matrix)
      fail(ctx, what + " animates node " + std::to_string(src.target_node) + ", which has a matrix");
    ch.node = src.target_node;
    if (src.sampler < 0 || static_cast<std::size_t>(src.sampler) >= a.samplers.size())
      fail(ctx, what + " uses sampler " + std::to_string(src.sampler) + " that does not exist");
    const tinygltf::AnimationSampler& smp = a.samplers[static_cast<std::size_t>(src.sampler)];
    if (smp.interpolation == "LINEAR" || smp.interpolation.empty())
      ch.interpolation = Interpolation::linear;
    else if (smp.interpolation == "STEP")
      ch.interpolation = Interpolation::step;
    else if (smp.interpolation == "CUBICSPLINE")
      ch.interpolation = Interpolation::cubic_spline;
    else
      fail(ctx, what + " has unknown interpolation '" + smp.interpolation + "'");

    const FloatAccessor times = read_floats(ctx, smp.input, what + " input", {1});
    ch.times = times.values;
    if (ch.times.empty()) fail(ctx, what + " has no key frames");
    for (std::size_t k = 1; k < ch.times.size(); ++k)
      if (ch.times[k] < ch.times[k - 1]) fail(ctx, what + " key times decrease at key " + std::to_string(k));
    const int comps = ch.path == ChannelPath::rotation ? 4 : 3;
    ch.values = read_floats(ctx, smp.output, what + " output", {comps});
    const std::size_t per_key = ch.interpolation == Interpolation::cubic_spline ? 3 : 1;
    if (ch.values.count != per_key * ch.times.size())
      fail(ctx, what + " has " + std::to_string(ch.values.count) + " output values for " +
                    std::to_string(ch.times.size()) + " key times");
    clip.duration_s = std::max(clip.duration_s, ch.times.back());
    clip.channels.push_back(std::move(ch));
  }
  return clip;
}

void apply_clip(const AnimationClip& clip, float t, std::vector<NodeTrs>& locals) {
  for (const Channel& ch : clip.channels) store(ch, sample(ch, t), locals[static_cast<std::size_t>(ch.node)]);
}

}  // namespace tourmap::crowd::gltf
