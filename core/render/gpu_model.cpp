#include "gpu_model.hpp"

#include "gl_program.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace tourmap::render {
namespace {

// 52 bytes per vertex. Joints as unsigned shorts read as a uvec4 (glVertexArrayAttribIFormat).
struct PackedVertex {
  float position[3];
  float normal[3];
  std::uint8_t color[4];
  std::uint16_t joints[4];
  float weights[4];
};
static_assert(sizeof(PackedVertex) == 52);

[[noreturn]] void fail(const std::string& model, const std::string& what) {
  throw std::invalid_argument("GpuModel '" + model + "': " + what);
}

// Area-weighted vertex normals, for models that come without normals.
std::vector<crowd::Vec3> computed_normals(const crowd::SkinnedModel& m) {
  std::vector<crowd::Vec3> n(m.positions.size(), crowd::Vec3::Zero());
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const auto a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
    if (std::max({a, b, c}) >= m.positions.size()) continue;
    const crowd::Vec3 f = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
    n[a] += f;
    n[b] += f;
    n[c] += f;
  }
  for (auto& v : n) v = v.norm() > 0 ? v.normalized() : crowd::Vec3::UnitY();
  return n;
}

std::vector<PackedVertex> pack_vertices(const crowd::SkinnedModel& m, int joint_count) {
  const std::size_t n = m.positions.size();
  if (!m.normals.empty() && m.normals.size() != n) fail(m.name, "normals and positions differ in count");
  if (!m.colors.empty() && m.colors.size() != n) fail(m.name, "colors and positions differ in count");
  if (m.joints.size() != m.weights.size() || (!m.joints.empty() && m.joints.size() != n))
    fail(m.name, "joints/weights must both be empty or have one entry per vertex");
  const std::vector<crowd::Vec3> normals = m.normals.empty() ? computed_normals(m) : m.normals;
  std::vector<PackedVertex> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    PackedVertex& v = out[i];
    if (!m.positions[i].allFinite()) fail(m.name, "vertex " + std::to_string(i) + " has a non-finite position");
    for (int k = 0; k < 3; ++k) {
      v.position[k] = m.positions[i][k];
      v.normal[k] = std::isfinite(normals[i][k]) ? normals[i][k] : 0.f;
    }
    const std::array<std::uint8_t, 4> grey{180, 180, 180, 255};
    const auto& c = m.colors.empty() ? grey : m.colors[i];
    std::copy(c.begin(), c.end(), v.color);
    if (m.joints.empty()) {  // rigid: everything on joint 0
      v.joints[0] = v.joints[1] = v.joints[2] = v.joints[3] = 0;
      v.weights[0] = 1;
      v.weights[1] = v.weights[2] = v.weights[3] = 0;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const float w = m.weights[i][static_cast<std::size_t>(k)];
      const std::uint16_t j = m.joints[i][static_cast<std::size_t>(k)];
      if (!(w >= 0) || !std::isfinite(w)) fail(m.name, "vertex " + std::to_string(i) + " has a bad skin weight");
      if (w > 0 && j >= joint_count)
        fail(m.name, "vertex " + std::to_string(i) + " uses joint " + std::to_string(j) + " of " +
                         std::to_string(joint_count));
      v.joints[k] = w > 0 ? j : 0;  // unused influences point at a joint that exists
      v.weights[k] = w;
    }
  }
  return out;
}

}  // namespace

GpuModel::GpuModel(const crowd::SkinnedModel& model, const crowd::ClusterHierarchy& hierarchy) : name_(model.name) {
  if (model.positions.empty()) fail(name_, "no vertices");
  if (model.animations.empty() || model.animations[0].poses.empty())
    fail(name_, "no pose (a static mesh needs one animation with one identity pose)");
  joint_count_ = static_cast<int>(model.animations[0].poses[0].skinning.size());
  if (joint_count_ < 1) fail(name_, "a pose without skinning matrices");
  is_static_ = model.is_static();

  // The hierarchy: a tree reachable from the root, index ranges inside `indices`.
  const std::size_t cluster_count = hierarchy.clusters.size();
  if (hierarchy.root < 0 || static_cast<std::size_t>(hierarchy.root) >= cluster_count)
    fail(name_, "hierarchy root " + std::to_string(hierarchy.root) + " is not a cluster");
  for (std::size_t i = 0; i < cluster_count; ++i) {
    const crowd::Cluster& c = hierarchy.clusters[i];
    if (c.index_count % 3 != 0 || std::size_t{c.first_index} + c.index_count > hierarchy.indices.size())
      fail(name_, "cluster " + std::to_string(i) + " has a bad index range");
    const bool leaf = c.children[0] == -1 && c.children[1] == -1;
    const bool inner = c.children[0] >= 0 && c.children[1] >= 0 && c.children[0] != c.children[1] &&
                       std::max(c.children[0], c.children[1]) < static_cast<int>(cluster_count);
    if (!leaf && !inner) fail(name_, "cluster " + std::to_string(i) + " has bad children");
  }
  for (std::size_t i = 0; i < hierarchy.indices.size(); ++i)
    if (hierarchy.indices[i] >= model.positions.size())
      fail(name_, "hierarchy index " + std::to_string(i) + " points past the vertices");

  // Depth (from the root), height (to the deepest leaf) and subtree bounds, iteratively; a
  // cluster reached twice means the "tree" is not one.
  std::vector<int> order, depth(cluster_count, -1);
  order.reserve(cluster_count);
  order.push_back(hierarchy.root);
  depth[static_cast<std::size_t>(hierarchy.root)] = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const crowd::Cluster& c = hierarchy.clusters[static_cast<std::size_t>(order[k])];
    if (c.is_leaf()) continue;
    for (int child : c.children) {
      if (depth[static_cast<std::size_t>(child)] >= 0) fail(name_, "cluster " + std::to_string(child) + " has two parents");
      depth[static_cast<std::size_t>(child)] = depth[static_cast<std::size_t>(order[k])] + 1;
      order.push_back(child);
    }
  }
  std::vector<int> height(cluster_count, 0);
  subtree_bounds_.resize(cluster_count);
  for (std::size_t i = 0; i < cluster_count; ++i) subtree_bounds_[i] = hierarchy.clusters[i].bounds;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {  // children before parents
    const crowd::Cluster& c = hierarchy.clusters[static_cast<std::size_t>(*it)];
    if (c.is_leaf()) continue;
    for (int child : c.children) {
      const auto ch = static_cast<std::size_t>(child);
      height[static_cast<std::size_t>(*it)] = std::max(height[static_cast<std::size_t>(*it)], height[ch] + 1);
      subtree_bounds_[static_cast<std::size_t>(*it)].extend(subtree_bounds_[ch]);
    }
  }
  fineness_.assign(cluster_count, 1.f);
  for (int id : order) {
    const auto i = static_cast<std::size_t>(id);
    const int total = depth[i] + height[i];
    fineness_[i] = total > 0 ? static_cast<float>(depth[i]) / static_cast<float>(total) : 1.f;
  }
  hierarchy_.clusters = hierarchy.clusters;
  hierarchy_.root = hierarchy.root;
  hierarchy_.stats = hierarchy.stats;
  cut_tree_ = crowd::build_cut_tree(hierarchy_);

  // The index buffer layout: leaves in depth-first order, then inner clusters by (depth, order).
  std::vector<int> dfs;
  dfs.reserve(order.size());
  std::vector<int> stack{hierarchy.root};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    dfs.push_back(id);
    const crowd::Cluster& c = hierarchy.clusters[static_cast<std::size_t>(id)];
    if (!c.is_leaf()) {
      stack.push_back(c.children[1]);
      stack.push_back(c.children[0]);
    }
  }
  for (int id : dfs)
    if (hierarchy.clusters[static_cast<std::size_t>(id)].is_leaf()) index_order_.push_back(id);
  std::vector<int> inner;
  for (int id : dfs)
    if (!hierarchy.clusters[static_cast<std::size_t>(id)].is_leaf()) inner.push_back(id);
  std::stable_sort(inner.begin(), inner.end(), [&](int a, int b) {
    return depth[static_cast<std::size_t>(a)] < depth[static_cast<std::size_t>(b)];
  });
  index_order_.insert(index_order_.end(), inner.begin(), inner.end());
  std::vector<std::uint32_t> indices;
  indices.reserve(hierarchy.indices.size());
  for (int id : index_order_) {
    crowd::Cluster& c = hierarchy_.clusters[static_cast<std::size_t>(id)];
    const auto from = hierarchy.indices.begin() + c.first_index;
    c.first_index = static_cast<std::uint32_t>(indices.size());
    indices.insert(indices.end(), from, from + c.index_count);
  }
  if (indices.empty()) indices = {0, 0, 0};  // a GL buffer needs some storage

  // The palette: per animation, per pose, per joint, the three rows of the 3x4 skinning matrix.
  std::vector<float> palette;
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const auto& anim = model.animations[a];
    if (anim.poses.empty()) fail(name_, "animation " + std::to_string(a) + " has no poses");
    animation_first_matrix_.push_back(static_cast<std::uint32_t>(palette.size() / 12));
    animation_frames_.push_back(static_cast<int>(anim.poses.size()));
    for (std::size_t p = 0; p < anim.poses.size(); ++p) {
      const auto& skinning = anim.poses[p].skinning;
      if (skinning.size() != static_cast<std::size_t>(joint_count_))
        fail(name_, "animation " + std::to_string(a) + " pose " + std::to_string(p) + " has " +
                        std::to_string(skinning.size()) + " skinning matrices, expected " + std::to_string(joint_count_));
      for (const auto& m : skinning) {
        if (!m.matrix().allFinite()) fail(name_, "a non-finite skinning matrix in animation " + std::to_string(a));
        for (int r = 0; r < 3; ++r)
          for (int col = 0; col < 4; ++col) palette.push_back(m.matrix()(r, col));
      }
    }
  }
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (palette.size() / 4 > static_cast<std::size_t>(max_texels))
    throw std::runtime_error("GpuModel '" + name_ + "': the pose palette needs " + std::to_string(palette.size() / 4) +
                             " texels, the GPU allows " + std::to_string(max_texels));

  const std::vector<PackedVertex> vertices = pack_vertices(model, joint_count_);
  glCreateBuffers(1, &vertex_buffer_);
  glNamedBufferStorage(vertex_buffer_, static_cast<GLsizeiptr>(vertices.size() * sizeof(PackedVertex)), vertices.data(), 0);
  glCreateBuffers(1, &index_buffer_);
  glNamedBufferStorage(index_buffer_, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
  glCreateBuffers(1, &palette_buffer_);
  glNamedBufferStorage(palette_buffer_, static_cast<GLsizeiptr>(palette.size() * sizeof(float)), palette.data(), 0);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &palette_texture_);
  glTextureBuffer(palette_texture_, GL_RGBA32F, palette_buffer_);

  glCreateVertexArrays(1, &vao_);
  glVertexArrayVertexBuffer(vao_, 0, vertex_buffer_, 0, sizeof(PackedVertex));
  glVertexArrayElementBuffer(vao_, index_buffer_);
  const auto attribute = [&](GLuint location, GLint size, GLenum type, GLboolean normalized, std::size_t offset) {
    glEnableVertexArrayAttrib(vao_, location);
    glVertexArrayAttribFormat(vao_, location, size, type, normalized, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao_, location, 0);
  };
  attribute(0, 3, GL_FLOAT, GL_FALSE, offsetof(PackedVertex, position));
  attribute(1, 3, GL_FLOAT, GL_FALSE, offsetof(PackedVertex, normal));
  attribute(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(PackedVertex, color));
  glEnableVertexArrayAttrib(vao_, 3);
  glVertexArrayAttribIFormat(vao_, 3, 4, GL_UNSIGNED_SHORT, offsetof(PackedVertex, joints));
  glVertexArrayAttribBinding(vao_, 3, 0);
  attribute(4, 4, GL_FLOAT, GL_FALSE, offsetof(PackedVertex, weights));
  // Per-draw item (instance index, cluster fineness), one per drawn instance (divisor 1); the
  // renderer binds its item buffer to kItemBinding every frame.
  glEnableVertexArrayAttrib(vao_, kItemAttribute);
  glVertexArrayAttribIFormat(vao_, kItemAttribute, 2, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao_, kItemAttribute, kItemBinding);
  glVertexArrayBindingDivisor(vao_, kItemBinding, 1);
  try {
    check_gl("GpuModel upload");
  } catch (...) {
    release();
    throw;
  }
}

GpuModel::~GpuModel() { release(); }

void GpuModel::release() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteTextures(1, &palette_texture_);
  const GLuint buffers[] = {vertex_buffer_, index_buffer_, palette_buffer_};
  glDeleteBuffers(3, buffers);
}

int GpuModel::frame_count(int animation) const {
  if (animation < 0 || animation >= animation_count())
    throw std::invalid_argument("GpuModel '" + name_ + "': no animation " + std::to_string(animation));
  return animation_frames_[static_cast<std::size_t>(animation)];
}

std::uint32_t GpuModel::palette_base(int animation, int frame) const {
  const int frames = frame_count(animation);
  if (frame < 0 || frame >= frames)
    throw std::invalid_argument("GpuModel '" + name_ + "': animation " + std::to_string(animation) + " has no frame " +
                                std::to_string(frame) + " (it has " + std::to_string(frames) + ")");
  return animation_first_matrix_[static_cast<std::size_t>(animation)] +
         static_cast<std::uint32_t>(frame) * static_cast<std::uint32_t>(joint_count_);
}

}  // namespace tourmap::render
