#include "crowd/gltf_loader.hpp"

#include "crowd/gltf_accessor.hpp"
#include "crowd/gltf_nodes.hpp"
#include "crowd/gltf_primitive.hpp"
#include "crowd/gltf_skeleton.hpp"
#include "crowd/mesh_normals.hpp"
#include "crowd/skeleton_root.hpp"
#include "crowd/skinning.hpp"
#include "crowd/weld.hpp"
#include "load/load_error.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace tourmap::crowd {
namespace {

using gltf::Binding;
using gltf::MergedMesh;
using gltf::ReadContext;
using gltf::SkeletonBuild;
using Mat4d = Eigen::Matrix4d;

constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 30;
constexpr std::size_t kMaxPosesPerClip = 20000;
constexpr std::size_t kMaxPoseMatrices = std::size_t{1} << 24;  // poses x joints over all clips

[[noreturn]] void fail(const std::string& file, const std::string& problem) { throw load::LoadError(file, problem); }

tinygltf::Model read_gltf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot read the file size: " + ec.message());
  if (size > kMaxFileBytes) fail(path, "file is larger than " + std::to_string(kMaxFileBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 12) fail(path, "too short to be a glTF file (" + std::to_string(bytes.size()) + " bytes)");

  tinygltf::TinyGLTF parser;
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  bool ok = false;
  if (std::equal(bytes.begin(), bytes.begin() + 4, "glTF")) {
    ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                     base_dir);
  } else {
    const auto first = std::find_if(bytes.begin(), bytes.end(), [](unsigned char c) { return !std::isspace(c); });
    if (first == bytes.end() || *first != '{') fail(path, "not a glTF file (neither a binary glTF header nor JSON)");
    ok = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                    static_cast<unsigned int>(bytes.size()), base_dir);
  }
  if (!ok) fail(path, "malformed glTF: " + (err.empty() ? std::string("parser failed") : err));
  for (const std::string& ext : model.extensionsRequired) fail(path, "requires the unsupported glTF extension " + ext);
  return model;
}

void finish_mesh(const std::string& file, MergedMesh&& mesh, const LoadOptions& options, SkinnedModel& model) {
  if (mesh.indices.empty()) fail(file, "has no triangle mesh in its scene");
  model.positions = std::move(mesh.positions);
  model.normals = std::move(mesh.normals);
  model.colors = std::move(mesh.colors);
  model.joints = std::move(mesh.joints);
  model.weights = std::move(mesh.weights);
  model.indices = std::move(mesh.indices);
  if (options.weld) {
    weld_vertices(model);
    // Welding drops triangles whose corners merged: a mesh of only such triangles has none left.
    if (model.indices.empty()) fail(file, "has no triangle mesh in its scene (every triangle is degenerate)");
    model.normals = smooth_normals(model.positions, model.indices);
  } else if (std::find(mesh.has_normal.begin(), mesh.has_normal.end(), 0) != mesh.has_normal.end()) {
    const std::vector<Vec3> computed = smooth_normals(model.positions, model.indices);
    for (std::size_t v = 0; v < model.normals.size(); ++v)
      if (!mesh.has_normal[v]) model.normals[v] = computed[v];
  }
}

void check_options(const LoadOptions& o) {
  if (!std::isfinite(o.sample_fps) || o.sample_fps <= 0 || o.sample_fps > 1000)
    throw std::invalid_argument("LoadOptions::sample_fps must be in (0, 1000], got " + std::to_string(o.sample_fps));
}

std::string model_name(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::vector<gltf::AnimationClip> selected_clips(const ReadContext& ctx, const gltf::NodeGraph& graph,
                                                const LoadOptions& options) {
  std::vector<gltf::AnimationClip> all;
  for (std::size_t a = 0; a < ctx.model.animations.size(); ++a)
    all.push_back(gltf::read_animation(ctx, static_cast<int>(a), graph));
  if (options.animations.empty()) return all;
  std::vector<gltf::AnimationClip> out;
  for (const std::string& name : options.animations) {
    const auto it = std::find_if(all.begin(), all.end(), [&](const auto& c) { return c.name == name; });
    if (it == all.end()) {
      std::string names;
      for (const auto& c : all) names += (names.empty() ? "" : ", ") + c.name;
      fail(ctx.file, "has no animation named '" + name + "' (it has: " + (names.empty() ? "none" : names) + ")");
    }
    out.push_back(*it);
  }
  return out;
}

Pose pose_from_globals(const std::vector<Eigen::Affine3d>& global, const SkeletonBuild& sk,
                       const std::vector<Mat4d>& stored_inverse_bind) {
  Pose pose;
  pose.skinning.reserve(sk.joint_node.size());
  pose.global.reserve(sk.joint_node.size());
  for (std::size_t j = 0; j < sk.joint_node.size(); ++j) {
    const Eigen::Affine3d& g = global[static_cast<std::size_t>(sk.joint_node[j])];
    pose.global.emplace_back(g.cast<float>());
    pose.skinning.emplace_back(Eigen::Affine3d(g.matrix() * stored_inverse_bind[j]).cast<float>());  // eq. 3.1
  }
  return pose;
}

// Every clip sampled at t = k / fps, k = 0 .. floor(duration * fps), at least 2 poses.
std::vector<Animation> sample_animations(const std::string& file, const gltf::NodeGraph& graph,
                                         const std::vector<gltf::AnimationClip>& clips, const SkeletonBuild& sk,
                                         const std::vector<Mat4d>& stored_inverse_bind, float fps) {
  std::vector<Animation> out;
  std::size_t matrices = 0;
  for (const gltf::AnimationClip& clip : clips) {
    const double steps = std::floor(static_cast<double>(clip.duration_s) * fps + 1e-3);
    if (steps + 1 > static_cast<double>(kMaxPosesPerClip))
      fail(file, "animation '" + clip.name + "' lasts " + std::to_string(clip.duration_s) + " s: more than " +
                     std::to_string(kMaxPosesPerClip) + " poses at " + std::to_string(fps) + " fps");
    const std::size_t n = std::max<std::size_t>(2, static_cast<std::size_t>(steps) + 1);
    matrices += n * sk.joint_node.size();
    if (matrices > kMaxPoseMatrices)
      fail(file, "animations need more than " + std::to_string(kMaxPoseMatrices) + " pose matrices");
    Animation anim;
    anim.name = clip.name;
    anim.duration_s = clip.duration_s;
    anim.fps = fps;
    anim.poses.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
      std::vector<gltf::NodeTrs> locals = graph.rest;
      gltf::apply_clip(clip, static_cast<float>(static_cast<double>(k) / fps), locals);
      anim.poses.push_back(pose_from_globals(gltf::global_transforms(graph, locals), sk, stored_inverse_bind));
    }
    out.push_back(std::move(anim));
  }
  return out;
}

}  // namespace

SkinnedModel load_skinned_model(const std::string& path, const LoadOptions& options) {
  check_options(options);
  const tinygltf::Model gm = read_gltf(path);
  const ReadContext ctx{gm, path};
  if (gm.skins.empty()) fail(path, "has no skin (it is a static mesh: load it with load_static_model)");
  const gltf::NodeGraph graph = gltf::build_node_graph(ctx);
  const std::vector<int> scene = gltf::scene_nodes(ctx, graph);
  const SkeletonBuild sk = gltf::build_skeleton(ctx, scene);
  const std::vector<Eigen::Affine3d> rest = gltf::global_transforms(graph, graph.rest);

  SkinnedModel model;
  model.name = model_name(path);
  model.skeleton.parent = gltf::joint_parents(graph, sk);
  const int root = main_root_joint(model.skeleton.parent);
  const Mat4d to_world =
      gltf::mesh_to_world(rest[static_cast<std::size_t>(sk.joint_node[static_cast<std::size_t>(root)])],
                          sk.inverse_bind[static_cast<std::size_t>(root)]);
  const Mat4d from_world = to_world.inverse();
  std::vector<Mat4d> stored_inverse_bind;
  for (std::size_t j = 0; j < sk.joint_node.size(); ++j) {
    const tinygltf::Node& node = gm.nodes[static_cast<std::size_t>(sk.joint_node[j])];
    model.skeleton.joint_names.push_back(node.name.empty() ? "joint " + std::to_string(j) : node.name);
    stored_inverse_bind.push_back(sk.inverse_bind[j] * from_world);
    model.skeleton.inverse_bind.push_back(stored_inverse_bind.back().cast<float>());
  }

  MergedMesh mesh;
  for (int n : scene) {
    const tinygltf::Node& node = gm.nodes[static_cast<std::size_t>(n)];
    if (node.mesh < 0) continue;
    if (static_cast<std::size_t>(node.mesh) >= gm.meshes.size())
      fail(path, "node " + std::to_string(n) + " uses mesh " + std::to_string(node.mesh) + " that does not exist");
    // Rigid binding (a mesh without a skin, e.g. RobotExpressive's head on joint "Head"): weight 1
    // on the nearest joint J at or above the node, else the root joint (a mesh outside the
    // skeleton then follows the root; with J = root, p_bind reduces to its world rest position
    // G_node(rest) p). R = to_world, B_J = the bind matrix (inverse of B_J^-1). The vertices are
    // placed at p_bind = R B_J G_J(rest)^-1 G_node(rest) p, so skinning gives
    // M_J(t) p_bind = G_J(t) B_J^-1 R^-1 R B_J G_J(rest)^-1 G_node(rest) p
    //              = G_J(t) (G_J(rest)^-1 G_node(rest)) p:
    // the mesh follows J with its rest offset, as the node hierarchy moves it (non-joint nodes
    // between J and the mesh are taken at rest; none of our files animates them).
    int rigid_joint = root;
    for (int a = n; a >= 0; a = graph.parent[static_cast<std::size_t>(a)])
      if (sk.joint_of_node[static_cast<std::size_t>(a)] >= 0) {
        rigid_joint = sk.joint_of_node[static_cast<std::size_t>(a)];
        break;
      }
    const std::size_t rj_node = static_cast<std::size_t>(sk.joint_node[static_cast<std::size_t>(rigid_joint)]);
    if (std::abs(rest[rj_node].linear().determinant()) < 1e-18)
      fail(path, "joint node " + std::to_string(rj_node) + " has a singular rest transform");
    Binding rigid;
    rigid.rigid_joint = rigid_joint;
    rigid.to_bind = to_world * sk.inverse_bind[static_cast<std::size_t>(rigid_joint)].inverse() *
                    rest[rj_node].matrix().inverse() * rest[static_cast<std::size_t>(n)].matrix();
    const tinygltf::Mesh& gmesh = gm.meshes[static_cast<std::size_t>(node.mesh)];
    for (std::size_t p = 0; p < gmesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = gmesh.primitives[p];
      const std::string what = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p);
      if (node.skin >= 0 && gltf::has_skin_attributes(prim)) {
        // glTF ignores a skinned mesh node's own transform: joints alone place the vertices.
        Binding skinned;
        skinned.to_bind = to_world * sk.skin_correction[static_cast<std::size_t>(node.skin)];
        skinned.skin_joints = &sk.skin_joints[static_cast<std::size_t>(node.skin)];
        gltf::append_primitive(ctx, prim, what, skinned, mesh);
      } else {
        gltf::append_primitive(ctx, prim, what, rigid, mesh);
      }
    }
  }
  finish_mesh(path, std::move(mesh), options, model);

  const std::vector<gltf::AnimationClip> clips = selected_clips(ctx, graph, options);
  if (clips.empty()) {
    // A rigged model without clips: one animation holding the rest pose.
    Animation anim;
    anim.name = "rest";
    anim.fps = options.sample_fps;
    anim.poses.push_back(pose_from_globals(rest, sk, stored_inverse_bind));
    model.animations.push_back(std::move(anim));
  } else {
    model.animations = sample_animations(path, graph, clips, sk, stored_inverse_bind, options.sample_fps);
  }
  return model;
}

SkinnedModel load_static_model(const std::string& path, const LoadOptions& options) {
  check_options(options);
  const tinygltf::Model gm = read_gltf(path);
  const ReadContext ctx{gm, path};
  const gltf::NodeGraph graph = gltf::build_node_graph(ctx);
  const std::vector<int> scene = gltf::scene_nodes(ctx, graph);
  const std::vector<Eigen::Affine3d> rest = gltf::global_transforms(graph, graph.rest);

  MergedMesh mesh;
  for (int n : scene) {
    const tinygltf::Node& node = gm.nodes[static_cast<std::size_t>(n)];
    if (node.mesh < 0) continue;
    if (static_cast<std::size_t>(node.mesh) >= gm.meshes.size())
      fail(path, "node " + std::to_string(n) + " uses mesh " + std::to_string(node.mesh) + " that does not exist");
    // Every mesh (skinned ones too, without their skin) placed by its node's rest transform.
    Binding rigid;
    rigid.to_bind = rest[static_cast<std::size_t>(n)].matrix();
    if (std::abs(rigid.to_bind.topLeftCorner<3, 3>().determinant()) < 1e-18)
      fail(path, "node " + std::to_string(n) + " has a singular transform");
    const tinygltf::Mesh& gmesh = gm.meshes[static_cast<std::size_t>(node.mesh)];
    for (std::size_t p = 0; p < gmesh.primitives.size(); ++p)
      gltf::append_primitive(ctx, gmesh.primitives[p],
                             "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p), rigid, mesh);
  }
  SkinnedModel model;
  model.name = model_name(path);
  finish_mesh(path, std::move(mesh), options, model);
  model.skeleton.joint_names = {"root"};
  model.skeleton.parent = {-1};
  model.skeleton.inverse_bind = {Eigen::Matrix4f::Identity()};
  Animation anim;
  anim.name = "static";
  anim.fps = options.sample_fps;
  anim.poses.push_back(Pose{{Affine::Identity()}, {Affine::Identity()}});
  model.animations.push_back(std::move(anim));
  return model;
}

Box3 posed_bounds(const SkinnedModel& model) {
  Box3 box;
  std::vector<Vec3> posed;
  for (const Animation& anim : model.animations)
    for (const Pose& pose : anim.poses) {
      skin_positions(model, pose, posed);
      for (const Vec3& p : posed) box.extend(p);
    }
  return box;
}

}  // namespace tourmap::crowd
