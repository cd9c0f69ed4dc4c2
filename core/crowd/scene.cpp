#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace tourmap::crowd {
namespace {

std::vector<SceneSpec> make_specs() {
  const SceneCharacter cesium{"CesiumMan", "humans/CesiumMan.glb", "", 2, 1.75f};
  const SceneCharacter robot{"RobotExpressive", "humans/RobotExpressive.glb", "Walking", 2, 1.7f};
  const SceneCharacter mannequin{"Mannequiny", "humans/Mannequiny.glb", "run", 1, 1.8f};
  const SceneCharacter horse{"Horse", "animals/Horse.glb", "Gallop", 2, 1.7f};
  const SceneCharacter donkey{"Donkey", "animals/Donkey.glb", "Gallop", 2, 1.4f};
  const SceneCharacter cow{"Cow", "animals/Cow.glb", "Gallop", 2, 1.5f};
  const SceneCharacter fox{"Fox", "animals/Fox.glb", "Run", 3, 0.6f};

  SceneSpec office;
  office.id = "office";
  office.title = "Office evacuation";
  office.description = "200 people walking the corridors of an office floor; the room walls hide most of them.";
  office.characters = {cesium, robot, mannequin};
  office.default_count = 200;
  office.max_count = 2000;
  office.rows = 3;
  office.cols = 4;
  office.block_m = 8;
  office.corridor_m = 4;
  office.wall_height_m = 3;
  office.hollow_blocks = true;

  SceneSpec exhibition;
  exhibition.id = "exhibition";
  exhibition.title = "Exhibition hall";
  exhibition.description = "1,000 visitors walking between rows of booths in a large hall.";
  exhibition.characters = {cesium, robot, mannequin};
  exhibition.default_count = 1000;
  exhibition.max_count = 5000;
  exhibition.rows = 6;
  exhibition.cols = 8;
  exhibition.block_m = 5;
  exhibition.corridor_m = 5;
  exhibition.wall_height_m = 2.5f;
  exhibition.hollow_blocks = false;

  SceneSpec stampede;
  stampede.id = "stampede";
  stampede.title = "Stampede";
  stampede.description = "5,000 horses, donkeys, cows and foxes running across a plain.";
  stampede.characters = {horse, donkey, cow, fox};
  stampede.default_count = 5000;
  stampede.max_count = 10000;
  stampede.layout = SceneLayout::open_field;
  stampede.speed_mps = 6;
  return {office, exhibition, stampede};
}

float polyline_length(const std::vector<Vec3>& loop) {
  float len = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) len += (loop[(i + 1) % loop.size()] - loop[i]).norm();
  return len;
}

// The walls of a room: four walls with a door gap in the south wall.
void add_room(std::vector<Box3>& out, float x0, float z0, float size, float height) {
  const float t = 0.2f, door = 1.6f;
  const float x1 = x0 + size, z1 = z0 + size;
  out.emplace_back(Vec3(x0, 0, z1 - t), Vec3(x1, height, z1));                      // north
  out.emplace_back(Vec3(x0, 0, z0), Vec3(x0 + t, height, z1));                      // west
  out.emplace_back(Vec3(x1 - t, 0, z0), Vec3(x1, height, z1));                      // east
  const float mid = (x0 + x1) / 2;
  out.emplace_back(Vec3(x0, 0, z0), Vec3(mid - door / 2, height, z0 + t));          // south, left of the door
  out.emplace_back(Vec3(mid + door / 2, 0, z0), Vec3(x1, height, z0 + t));          // south, right of the door
}

void build_blocks(const SceneSpec& spec, SceneState& s, std::mt19937& rng) {
  const float pitch = spec.block_m + spec.corridor_m;
  const float width = spec.cols * pitch + spec.corridor_m;
  const float depth = spec.rows * pitch + spec.corridor_m;
  for (int r = 0; r < spec.rows; ++r)
    for (int c = 0; c < spec.cols; ++c) {
      const float x0 = spec.corridor_m + c * pitch, z0 = spec.corridor_m + r * pitch;
      if (spec.hollow_blocks) {
        add_room(s.occluders, x0, z0, spec.block_m, spec.wall_height_m);
      } else {
        s.occluders.emplace_back(Vec3(x0, 0, z0), Vec3(x0 + spec.block_m, spec.wall_height_m, z0 + spec.block_m));
      }
    }
  // Each agent walks a loop around a rectangle of blocks (one block or a span of blocks), in a
  // lane of the corridor, so nobody walks through a wall.
  std::uniform_int_distribution<int> row(0, spec.rows - 1), col(0, spec.cols - 1);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::uniform_int_distribution<int> character(0, static_cast<int>(spec.characters.size()) - 1);
  for (int i = 0; i < s.count; ++i) {
    int r0 = row(rng), r1 = row(rng), c0 = col(rng), c1 = col(rng);
    if (r0 > r1) std::swap(r0, r1);
    if (c0 > c1) std::swap(c0, c1);
    const float lane = 0.6f + unit(rng) * (spec.corridor_m * 0.5f - 0.9f);  // from the block face
    const float xa = spec.corridor_m + c0 * pitch - lane, xb = spec.corridor_m + c1 * pitch + spec.block_m + lane;
    const float za = spec.corridor_m + r0 * pitch - lane, zb = spec.corridor_m + r1 * pitch + spec.block_m + lane;
    Agent a;
    a.character = character(rng);
    a.loop = {Vec3(xa, 0, za), Vec3(xb, 0, za), Vec3(xb, 0, zb), Vec3(xa, 0, zb)};
    if (unit(rng) < 0.5f) std::reverse(a.loop.begin(), a.loop.end());  // both directions
    a.length_m = polyline_length(a.loop);
    a.speed_mps = spec.speed_mps * (0.8f + 0.4f * unit(rng));
    a.offset_m = unit(rng) * a.length_m;
    a.phase_s = unit(rng) * 4;
    s.agents.push_back(std::move(a));
  }
  s.ground = Box3(Vec3(0, -0.1f, 0), Vec3(width, 0.02f, depth));  // 2 cm above the ground plane: no z-fighting
  const Vec3 centre(width / 2, 0, depth / 2);
  s.default_camera = {centre + Vec3(0, std::max(width, depth) * 0.45f, -depth * 0.85f), centre, 60};
}

void build_open_field(const SceneSpec& spec, SceneState& s, std::mt19937& rng) {
  // A herd in a band: density about one animal per 6 m^2, running along +X and wrapping.
  const float area = std::max(400.f, static_cast<float>(s.count) * 6.f);
  const float depth = std::sqrt(area / 3.f), width = 3.f * depth;
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::uniform_int_distribution<int> character(0, static_cast<int>(spec.characters.size()) - 1);
  for (int i = 0; i < s.count; ++i) {
    Agent a;
    a.character = character(rng);
    a.loop = {Vec3(0, 0, unit(rng) * depth), Vec3(1, 0, 0)};
    a.length_m = width;
    a.speed_mps = spec.speed_mps * (0.85f + 0.3f * unit(rng));
    a.offset_m = unit(rng) * width;
    a.phase_s = unit(rng) * 2;
    s.agents.push_back(std::move(a));
  }
  for (int k = 0; k < 12; ++k) {  // rocks
    const Vec3 c(unit(rng) * width, 0, unit(rng) * depth);
    const float r = 1.f + 2.f * unit(rng);
    s.occluders.emplace_back(c - Vec3(r, 0, r), c + Vec3(r, 1.5f * r, r));
  }
  s.ground = Box3(Vec3(0, -0.1f, 0), Vec3(width, 0.02f, depth));  // 2 cm above the ground plane: no z-fighting
  const Vec3 centre(width / 2, 0, depth / 2);
  s.default_camera = {centre + Vec3(-width * 0.1f, depth * 0.35f, -depth * 0.9f), centre, 60};
}

}  // namespace

const std::vector<SceneSpec>& scene_specs() {
  static const std::vector<SceneSpec> specs = make_specs();
  return specs;
}

const SceneSpec* find_scene_spec(std::string_view id) {
  for (const auto& s : scene_specs())
    if (s.id == id) return &s;
  return nullptr;
}

SceneState build_scene(const SceneSpec& spec, int count) {
  SceneState s;
  s.spec = &spec;
  s.count = std::clamp(count, spec.min_count, spec.max_count);
  std::mt19937 rng(0x70c0 + static_cast<unsigned>(s.count));  // deterministic per count
  if (spec.layout == SceneLayout::blocks) build_blocks(spec, s, rng);
  else build_open_field(spec, s, rng);
  s.bounds = s.ground;
  for (const auto& b : s.occluders) s.bounds.extend(b);
  s.bounds.extend(Vec3(s.bounds.min().x(), 2.5f, s.bounds.min().z()));  // characters stand up to ~2 m
  return s;
}

void place_agents(const SceneState& scene, double t, std::vector<Placement>& out) {
  out.clear();
  out.reserve(scene.agents.size());
  for (const auto& a : scene.agents) {
    Placement p;
    p.character = a.character;
    p.anim_time_s = static_cast<float>(t) + a.phase_s;
    const double travelled = std::fmod(a.offset_m + a.speed_mps * t, static_cast<double>(a.length_m));
    if (scene.spec && scene.spec->layout == SceneLayout::open_field) {
      p.position = a.loop[0] + a.loop[1] * static_cast<float>(travelled);
      p.heading = std::atan2(a.loop[1].x(), a.loop[1].z());
    } else {
      double left = travelled;
      for (std::size_t i = 0; i < a.loop.size(); ++i) {
        const Vec3 from = a.loop[i], to = a.loop[(i + 1) % a.loop.size()];
        const double seg = (to - from).norm();
        if (left <= seg || i + 1 == a.loop.size()) {
          const Vec3 dir = (to - from) / static_cast<float>(std::max(seg, 1e-6));
          p.position = from + dir * static_cast<float>(std::min(left, seg));
          p.heading = std::atan2(dir.x(), dir.z());
          break;
        }
        left -= seg;
      }
    }
    out.push_back(p);
  }
}

Affine placement_transform(const Placement& p) {
  Affine a = Affine::Identity();
  a.translate(p.position);
  a.rotate(Eigen::AngleAxisf(p.heading, Vec3::UnitY()));
  return a;
}

SkinnedModel boxes_model(const SceneState& scene) {
  SkinnedModel m;
  m.name = "scene";
  auto add_box = [&m](const Box3& b, std::array<std::uint8_t, 4> colour) {
    // 6 faces x 4 vertices (flat normals), 2 triangles per face.
    const Vec3 lo = b.min(), hi = b.max();
    const Vec3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const Vec3& normal : n) {
      const int axis = normal.x() != 0 ? 0 : normal.y() != 0 ? 1 : 2;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const float fixed = normal[axis] > 0 ? hi[axis] : lo[axis];
      const auto base = static_cast<std::uint32_t>(m.positions.size());
      for (int k = 0; k < 4; ++k) {
        Vec3 p;
        p[axis] = fixed;
        p[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        p[v] = (k >= 2) ? hi[v] : lo[v];
        m.positions.push_back(p);
        m.normals.push_back(normal);
        m.colors.push_back(colour);
        m.joints.push_back({0, 0, 0, 0});
        m.weights.push_back({1, 0, 0, 0});
      }
      // Counter-clockwise seen from outside: (u, v) is right-handed with the normal for +axis.
      if (normal[axis] > 0) m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  };
  add_box(scene.ground, {150, 160, 140, 255});
  for (const auto& b : scene.occluders) add_box(b, {205, 200, 190, 255});
  m.skeleton.joint_names = {"root"};
  m.skeleton.parent = {-1};
  m.skeleton.inverse_bind = {Eigen::Matrix4f::Identity()};
  Animation still;
  still.name = "static";
  still.poses.push_back(Pose{{Affine::Identity()}, {Affine::Identity()}});
  m.animations.push_back(std::move(still));
  return m;
}

}  // namespace tourmap::crowd
