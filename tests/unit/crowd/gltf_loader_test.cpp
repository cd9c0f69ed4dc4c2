#include "crowd/gltf_loader.hpp"

#include "crowd/skinning.hpp"
#include "load/load_error.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

namespace tourmap::crowd {
namespace {

using load::LoadError;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the LoadError `f` throws ("" and a test failure if it throws nothing).
template <class F>
std::string load_error_of(F&& f) {
  try {
    f();
  } catch (const LoadError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no LoadError";
  return "";
}

// ---- a hand-made .glb whose posed vertices are computed by hand ---------------------------

// Knobs for the hostile variants of the test file.
struct Tweaks {
  std::uint8_t joint_of_vertex1 = 1;   // JOINTS_0 of skinned vertex 1 (the skin has 2 joints)
  std::uint16_t third_index = 2;       // index 2 of the skinned triangle (3 vertices)
  std::size_t declared_positions = 3;  // POSITION accessor count (the data holds 3)
  std::array<float, 2> weights_of_vertex2{0.5f, 0.5f};
};

class GlbBuilder {
 public:
  template <class T>
  int add(const std::vector<T>& data, int component_type, const std::string& type, std::size_t count) {
    while (bin_.size() % 4) bin_.push_back('\0');
    const std::size_t offset = bin_.size(), bytes = data.size() * sizeof(T);
    bin_.append(reinterpret_cast<const char*>(data.data()), bytes);
    views_ += (views_.empty() ? "" : ",") + std::string("{\"buffer\":0,\"byteOffset\":") + std::to_string(offset) +
              ",\"byteLength\":" + std::to_string(bytes) + "}";
    accessors_ += (accessors_.empty() ? "" : ",") + std::string("{\"bufferView\":") + std::to_string(count_) +
                  ",\"componentType\":" + std::to_string(component_type) + ",\"count\":" + std::to_string(count) +
                  ",\"type\":\"" + type + "\"}";
    return count_++;
  }

  std::string glb(const std::string& rest_of_json) {
    while (bin_.size() % 4) bin_.push_back('\0');
    std::string json = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" + std::to_string(bin_.size()) +
                       "}],\"bufferViews\":[" + views_ + "],\"accessors\":[" + accessors_ + "]," + rest_of_json + "}";
    while (json.size() % 4) json.push_back(' ');
    std::string out;
    auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    out += "glTF";
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin_.size()));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534A);  // JSON
    out += json;
    u32(static_cast<std::uint32_t>(bin_.size()));
    u32(0x004E4942);  // BIN
    out += bin_;
    return out;
  }

 private:
  std::string bin_, views_, accessors_;
  int count_ = 0;
};

// Scene: "root" (translation 10,0,0) > joint "j0" > joint "j1" (at +1 on x, REST rotation
// 90 degrees about Z) > rigid mesh node "rigid" (+1 on y). The skin binds j0 at (10,0,0) and
// j1 at (11,0,0) UNROTATED (inverse bind = translations), so bind pose != rest pose.
// The skinned mesh node has a translation (100,0,0) that glTF says to ignore.
// Animations (keys at t = 0 and 1): "bend" turns j1 from identity to 90 degrees about Z
// (LINEAR), "step" moves j0 from (0,0,0) to (0,2,0) (STEP), "cubic" moves j0 from (0,0,0) to
// (0,2,0) with out-tangent (0,4,0) at the first key (CUBICSPLINE).
std::string test_glb(const Tweaks& t = {}) {
  GlbBuilder b;
  constexpr int kFloat = 5126, kUbyte = 5121, kUshort = 5123;
  const int pos = b.add(std::vector<float>{10, 0, 0, 12, 0, 0, 11.5f, 0, 1}, kFloat, "VEC3", t.declared_positions);
  const int joints =
      b.add(std::vector<std::uint8_t>{0, 0, 0, 0, t.joint_of_vertex1, 0, 0, 0, 0, 1, 0, 0}, kUbyte, "VEC4", 3);
  const int weights =
      b.add(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, t.weights_of_vertex2[0], t.weights_of_vertex2[1], 0, 0}, kFloat,
            "VEC4", 3);
  const int idx = b.add(std::vector<std::uint16_t>{0, 1, t.third_index}, kUshort, "SCALAR", 3);
  const int rigid_pos = b.add(std::vector<float>{0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f}, kFloat, "VEC3", 3);
  const int ibm = b.add(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -10, 0, 0, 1,  //
                                           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -11, 0, 0, 1},
                        kFloat, "MAT4", 2);
  const int times = b.add(std::vector<float>{0, 1}, kFloat, "SCALAR", 2);
  const float h = std::sqrt(0.5f);
  const int rot = b.add(std::vector<float>{0, 0, 0, 1, 0, 0, h, h}, kFloat, "VEC4", 2);
  const int step = b.add(std::vector<float>{0, 0, 0, 0, 2, 0}, kFloat, "VEC3", 2);
  const int cubic = b.add(std::vector<float>{0, 0, 0, 0, 0, 0, 0, 4, 0,   // key 0: in, value, out
                                             0, 0, 0, 0, 2, 0, 0, 0, 0},  // key 1
                          kFloat, "VEC3", 6);
  auto s = [](int i) { return std::to_string(i); };
  auto anim = [&](const std::string& name, int output, const std::string& interp, int node, const std::string& path) {
    return "{\"name\":\"" + name + "\",\"samplers\":[{\"input\":" + s(times) + ",\"output\":" + s(output) +
           ",\"interpolation\":\"" + interp + "\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":" + s(node) +
           ",\"path\":\"" + path + "\"}}]}";
  };
  return b.glb(
      "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
      "\"nodes\":["
      "{\"name\":\"root\",\"translation\":[10,0,0],\"children\":[3,1]},"
      "{\"name\":\"j0\",\"children\":[2]},"
      "{\"name\":\"j1\",\"translation\":[1,0,0],\"rotation\":[0,0,0.70710678,0.70710678],\"children\":[4]},"
      "{\"name\":\"skinned\",\"mesh\":0,\"skin\":0,\"translation\":[100,0,0]},"
      "{\"name\":\"rigid\",\"mesh\":1,\"translation\":[0,1,0]}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      s(pos) + ",\"JOINTS_0\":" + s(joints) + ",\"WEIGHTS_0\":" + s(weights) + "},\"indices\":" + s(idx) +
      "}]},"
      "{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      s(rigid_pos) +
      "}}]}],"
      "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":" +
      s(ibm) +
      "}],"
      "\"animations\":[" +
      anim("bend", rot, "LINEAR", 2, "rotation") + "," + anim("step", step, "STEP", 1, "translation") + "," +
      anim("cubic", cubic, "CUBICSPLINE", 1, "translation") + "]");
}

void expect_vec(const Vec3& got, const Vec3& want, const std::string& what) {
  EXPECT_NEAR(got.x(), want.x(), 1e-4f) << what;
  EXPECT_NEAR(got.y(), want.y(), 1e-4f) << what;
  EXPECT_NEAR(got.z(), want.z(), 1e-4f) << what;
}

class GltfHandMade : public ::testing::Test {
 protected:
  test::TempDir dir;
  LoadOptions options() const {
    LoadOptions o;
    o.sample_fps = 2;  // poses at t = 0, 0.5, 1
    o.weld = false;    // keep the file's vertex order: 3 skinned, then 3 rigid
    return o;
  }
};

TEST_F(GltfHandMade, SkeletonBindPoseAndSampling) {
  const SkinnedModel m = load_skinned_model(dir.write("t.glb", test_glb()), options());
  EXPECT_EQ(m.skeleton.joint_names, (std::vector<std::string>{"j0", "j1"}));
  EXPECT_EQ(m.skeleton.parent, (std::vector<int>{-1, 0}));
  ASSERT_EQ(m.vertex_count(), 6u);
  ASSERT_EQ(m.triangle_count(), 2u);
  // Skinned vertices: mesh space as is (the node's own translation is ignored).
  expect_vec(m.positions[0], Vec3(10, 0, 0), "skinned 0");
  expect_vec(m.positions[2], Vec3(11.5f, 0, 1), "skinned 2");
  // Rigid vertices: bind = B_j1 * G_j1(rest)^-1 * G_rigid(rest) * p = T(11,0,0) * T(0,1,0) * p.
  expect_vec(m.positions[3], Vec3(11, 1, 0), "rigid 0");
  expect_vec(m.positions[4], Vec3(11.5f, 1, 0), "rigid 1");
  EXPECT_EQ(m.joints[3][0], 1);
  EXPECT_EQ(m.weights[3][0], 1.f);
  ASSERT_EQ(m.animations.size(), 3u);
  for (const Animation& a : m.animations) {
    EXPECT_FLOAT_EQ(a.duration_s, 1.f);
    EXPECT_EQ(a.poses.size(), 3u) << a.name;
    // eq. 3.1: M_j = G_j * B_j^-1 for every stored pose.
    for (const Pose& p : a.poses)
      for (std::size_t j = 0; j < 2; ++j)
        EXPECT_TRUE(p.skinning[j].matrix().isApprox(p.global[j].matrix() * m.skeleton.inverse_bind[j], 1e-5f));
  }
}

TEST_F(GltfHandMade, LinearRotationSlerpsAndRigidPartsFollowTheirJoint) {
  const SkinnedModel m = load_skinned_model(dir.write("t.glb", test_glb()), options());
  const Animation& bend = m.animations[0];
  ASSERT_EQ(bend.name, "bend");
  const float h = std::sqrt(0.5f);
  // t = 0: j1 unrotated = the bind pose, so nothing moves.
  for (std::size_t v = 0; v < 6; ++v) expect_vec(skin_position(m, v, bend.poses[0]), m.positions[v], "bend t=0");
  // t = 0.5: slerp halfway, 45 degrees. Rigid vertex 0 sits at (0,1,0) from j1's origin (11,0,0).
  expect_vec(skin_position(m, 3, bend.poses[1]), Vec3(11 - h, h, 0), "rigid at 45 degrees");
  // Skinned vertex 2, weights 0.5/0.5: j0 keeps (11.5,0,1); j1 turns (0.5,0,1) by 45 degrees.
  expect_vec(skin_position(m, 2, bend.poses[1]), Vec3(0.5f * (11.5f + 11 + 0.5f * h), 0.5f * 0.5f * h, 1),
             "blend at 45");
  // t = 1: 90 degrees, which is the rest pose: rigid parts land where the node tree puts them
  // (G_rigid(rest) * p, as the static loader computes).
  const SkinnedModel rest = load_static_model(dir.file("t.glb"), options());
  expect_vec(skin_position(m, 3, bend.poses[2]), Vec3(10, 0, 0), "rigid at 90");
  for (std::size_t v = 3; v < 6; ++v) expect_vec(skin_position(m, v, bend.poses[2]), rest.positions[v], "rigid = rest");
  expect_vec(skin_position(m, 2, bend.poses[2]), Vec3(11.25f, 0.25f, 1), "blend at 90");
  expect_vec(bend.poses[2].global[1].translation(), Vec3(11, 0, 0), "G_j1");
}

TEST_F(GltfHandMade, StepAndCubicSplineTranslation) {
  const SkinnedModel m = load_skinned_model(dir.write("t.glb", test_glb()), options());
  const Animation& step = m.animations[1];
  const Animation& cubic = m.animations[2];
  ASSERT_EQ(step.name, "step");
  // STEP holds the first key until t = 1.
  expect_vec(step.poses[1].global[0].translation(), Vec3(10, 0, 0), "step t=0.5");
  expect_vec(step.poses[2].global[0].translation(), Vec3(10, 2, 0), "step t=1");
  expect_vec(skin_position(m, 0, step.poses[2]), Vec3(10, 2, 0), "vertex on j0");
  // j1 keeps its rest rotation (90 degrees) and rides on j0.
  expect_vec(skin_position(m, 3, step.poses[2]), Vec3(10, 2, 0), "rigid rides along");
  // Hermite at s = 0.5: 0.5 v0 + 0.125 out0 + 0.5 v1 - 0.125 in1 = (0, 1 + 0.5, 0).
  expect_vec(cubic.poses[1].global[0].translation(), Vec3(10, 1.5f, 0), "cubic t=0.5");
  expect_vec(cubic.poses[2].global[0].translation(), Vec3(10, 2, 0), "cubic t=1");
}

TEST_F(GltfHandMade, AnimationFilterAndOptions) {
  const std::string path = dir.write("t.glb", test_glb());
  LoadOptions o = options();
  o.animations = {"cubic"};
  const SkinnedModel m = load_skinned_model(path, o);
  ASSERT_EQ(m.animations.size(), 1u);
  EXPECT_EQ(m.animations[0].name, "cubic");
  o.animations = {"fly"};
  const std::string msg = load_error_of([&] { load_skinned_model(path, o); });
  EXPECT_NE(msg.find("no animation named 'fly'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bend, step, cubic"), std::string::npos) << msg;
  o = options();
  o.sample_fps = 0;
  EXPECT_THROW(load_skinned_model(path, o), std::invalid_argument);
}

TEST_F(GltfHandMade, HostileVariantsAreRejectedNotReadOutOfBounds) {
  Tweaks bad_joint;
  bad_joint.joint_of_vertex1 = 5;
  std::string msg = load_error_of([&] { load_skinned_model(dir.write("a.glb", test_glb(bad_joint)), options()); });
  EXPECT_NE(msg.find("uses joint 5"), std::string::npos) << msg;

  Tweaks bad_index;
  bad_index.third_index = 9;
  msg = load_error_of([&] { load_skinned_model(dir.write("b.glb", test_glb(bad_index)), options()); });
  EXPECT_NE(msg.find("index 2 is 9"), std::string::npos) << msg;

  Tweaks long_accessor;  // claims 1000 positions in a 36-byte buffer view
  long_accessor.declared_positions = 1000;
  msg = load_error_of([&] { load_skinned_model(dir.write("c.glb", test_glb(long_accessor)), options()); });
  EXPECT_NE(msg.find("c.glb"), std::string::npos) << msg;
  EXPECT_NE(msg.find("POSITION"), std::string::npos) << msg;
}

TEST_F(GltfHandMade, WeightsAreRenormalised) {
  Tweaks heavy;
  heavy.weights_of_vertex2 = {3, 1};
  const SkinnedModel m = load_skinned_model(dir.write("w.glb", test_glb(heavy)), options());
  EXPECT_FLOAT_EQ(m.weights[2][0], 0.75f);
  EXPECT_FLOAT_EQ(m.weights[2][1], 0.25f);
}

// ---- the real models ---------------------------------------------------------------------

struct ModelFacts {
  const char* file;
  std::size_t triangles, vertices;  // before welding (PROVENANCE.md)
  std::size_t joints, animations;   // 0 joints: a static model
  bool stands_on_y0;                // a character or a room (zdm2 is a multi-level map)
};

void PrintTo(const ModelFacts& f, std::ostream* os) { *os << f.file; }

const ModelFacts kModels[] = {
    {"models/humans/CesiumMan.glb", 4672, 3273, 19, 1, true},
    {"models/humans/Mannequiny.glb", 13832, 12597, 45, 10, true},
    {"models/humans/RobotExpressive.glb", 3237, 7214, 43, 14, true},
    {"models/animals/Fox.glb", 576, 1728, 24, 3, true},
    {"models/animals/Horse.glb", 2182, 4400, 50, 13, true},
    {"models/animals/Donkey.glb", 2000, 4044, 50, 13, true},
    {"models/animals/Cow.glb", 2450, 4970, 42, 13, true},
    {"models/environment/OcclusionRoom.glb", 63720, 34716, 0, 0, true},
    {"models/environment/zdm2.glb", 58772, 87822, 0, 0, false},
};

void expect_valid(const SkinnedModel& m) {
  const std::size_t n = m.vertex_count();
  ASSERT_EQ(m.normals.size(), n);
  ASSERT_EQ(m.colors.size(), n);
  ASSERT_EQ(m.joints.size(), n);
  ASSERT_EQ(m.weights.size(), n);
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (std::uint32_t i : m.indices) ASSERT_LT(i, n);
  const std::size_t joints = m.skeleton.parent.size();
  ASSERT_EQ(m.skeleton.inverse_bind.size(), joints);
  for (std::size_t v = 0; v < n; ++v) {
    float sum = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      ASSERT_GE(m.weights[v][k], 0.f);
      ASSERT_LT(m.joints[v][k], joints);
      sum += m.weights[v][k];
    }
    ASSERT_NEAR(sum, 1.f, 1e-5f) << "vertex " << v;
    ASSERT_NEAR(m.normals[v].norm(), 1.f, 1e-4f) << "vertex " << v;
  }
  for (const Animation& a : m.animations)
    for (const Pose& p : a.poses) {
      ASSERT_EQ(p.skinning.size(), joints);
      ASSERT_EQ(p.global.size(), joints);
    }
}

class GltfRealModel : public ::testing::TestWithParam<ModelFacts> {};

TEST_P(GltfRealModel, CountsMatchProvenanceAndDataIsValid) {
  const ModelFacts& f = GetParam();
  const std::string path = test::data_file(f.file);
  const bool is_static = f.joints == 0;
  LoadOptions raw_options;
  raw_options.weld = false;
  const auto t0 = std::chrono::steady_clock::now();
  const SkinnedModel raw = is_static ? load_static_model(path, raw_options) : load_skinned_model(path, raw_options);
  const auto t1 = std::chrono::steady_clock::now();
  const SkinnedModel welded = is_static ? load_static_model(path) : load_skinned_model(path);
  const auto t2 = std::chrono::steady_clock::now();

  EXPECT_EQ(raw.triangle_count(), f.triangles);
  EXPECT_EQ(raw.vertex_count(), f.vertices);
  if (is_static) {
    EXPECT_TRUE(welded.is_static());
  } else {
    EXPECT_FALSE(welded.is_static());
    EXPECT_EQ(welded.skeleton.parent.size(), f.joints);
    EXPECT_EQ(welded.animations.size(), f.animations);
    for (const Animation& a : welded.animations) {
      // t = k / 30 for k = 0 .. floor(30 * duration): the last sample is the clip's end.
      const std::size_t expected = static_cast<std::size_t>(std::floor(a.duration_s * 30 + 1e-3)) + 1;
      EXPECT_EQ(a.poses.size(), std::max<std::size_t>(2, expected)) << a.name;
    }
  }
  // Welding connects seams: fewer vertices, and at most a handful of triangles collapse.
  EXPECT_LT(welded.vertex_count(), raw.vertex_count());
  EXPECT_LE(welded.triangle_count(), raw.triangle_count());
  EXPECT_GE(welded.triangle_count() + 5, raw.triangle_count());
  expect_valid(raw);
  expect_valid(welded);

  // +Y up: characters stand and rooms lie on y ~ 0 in the bind pose.
  Box3 bind;
  for (const Vec3& p : welded.positions) bind.extend(p);
  if (f.stands_on_y0) {
    EXPECT_LT(std::abs(bind.min().y()), 0.03f * bind.sizes().y()) << "bind bbox min y " << bind.min().y();
  }
  const Box3 posed = posed_bounds(welded);
  EXPECT_TRUE(posed.sizes().allFinite());
  std::printf(
      "[ info ] %s: %zu -> %zu vertices after weld, %zu triangles, %zu joints, %zu animations; "
      "load %.0f ms (no weld) / %.0f ms (weld)\n",
      welded.name.c_str(), raw.vertex_count(), welded.vertex_count(), welded.triangle_count(),
      welded.skeleton.parent.size(), welded.animations.size(),
      std::chrono::duration<double, std::milli>(t1 - t0).count(),
      std::chrono::duration<double, std::milli>(t2 - t1).count());
}

INSTANTIATE_TEST_SUITE_P(Models, GltfRealModel, ::testing::ValuesIn(kModels),
                         [](const auto& info) { return std::filesystem::path(info.param.file).stem().string(); });

TEST(GltfRealModels, CesiumManIsAHumanWalkingUpright) {
  const SkinnedModel m = load_skinned_model(test::data_file("models/humans/CesiumMan.glb"));
  ASSERT_EQ(m.animations.size(), 1u);
  EXPECT_FLOAT_EQ(m.animations[0].duration_s, 2.f);
  EXPECT_EQ(m.animations[0].poses.size(), 61u);
  const Box3 b = posed_bounds(m);
  const Vec3 size = b.sizes();
  EXPECT_GT(size.y(), 1.4f);  // metres
  EXPECT_LT(size.y(), 2.0f);
  EXPECT_GT(size.y(), size.x());
  EXPECT_GT(size.y(), size.z());
  EXPECT_LT(std::abs(b.min().y()), 0.1f);  // feet on the ground
  // Textured: many distinct colours.
  std::set<std::array<std::uint8_t, 4>> colors(m.colors.begin(), m.colors.end());
  EXPECT_GT(colors.size(), 20u);
}

TEST(GltfRealModels, MaterialFactorIsStoredAsSrgb) {
  // Horse primitive 0 uses material "Main", baseColorFactor (0.19598514, 0.08910479, 0.03202813).
  const SkinnedModel m = load_skinned_model(test::data_file("models/animals/Horse.glb"));
  auto srgb8 = [](double c) {
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    return static_cast<int>(std::lround(255 * s));
  };
  EXPECT_EQ(m.colors[0][0], srgb8(0.19598513841629028));
  EXPECT_EQ(m.colors[0][1], srgb8(0.0891047865152359));
  EXPECT_EQ(m.colors[0][2], srgb8(0.032028134912252426));
  EXPECT_EQ(m.colors[0][3], 255);
}

TEST(GltfRealModels, FoxWithoutFileNormalsGetsComputedOnes) {
  LoadOptions o;
  o.weld = false;
  o.animations = {"Walk"};
  const SkinnedModel m = load_skinned_model(test::data_file("models/animals/Fox.glb"), o);
  ASSERT_EQ(m.animations.size(), 1u);
  EXPECT_EQ(m.animations[0].poses.size(), 22u);  // 0.708 s at 30 fps
  std::size_t plus_y = 0;
  for (const Vec3& n : m.normals) {
    ASSERT_NEAR(n.norm(), 1.f, 1e-4f);
    plus_y += n == Vec3::UnitY();
  }
  EXPECT_LT(plus_y, m.normals.size() / 10);
}

// ---- bad files ---------------------------------------------------------------------------

TEST(GltfLoaderErrors, MissingFile) {
  const std::string msg = load_error_of([] { load_skinned_model("/nonexistent/dir/model.glb"); });
  EXPECT_NE(msg.find("/nonexistent/dir/model.glb"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
  try {
    load_static_model("/nonexistent/dir/model.glb");
  } catch (const LoadError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/dir/model.glb");
  }
}

TEST(GltfLoaderErrors, TruncatedGlbAtManyLengths) {
  const std::string bytes = read_bytes(test::data_file("models/humans/CesiumMan.glb"));
  ASSERT_GT(bytes.size(), 100000u);
  test::TempDir dir;
  for (std::size_t n : {std::size_t{0}, std::size_t{11}, std::size_t{12}, std::size_t{20}, std::size_t{100},
                        std::size_t{3000}, bytes.size() / 2, bytes.size() - 1}) {
    const std::string path = dir.write("cut" + std::to_string(n) + ".glb", bytes.substr(0, n));
    const std::string msg = load_error_of([&] { load_skinned_model(path); });
    EXPECT_NE(msg.find(path), std::string::npos) << n << ": " << msg;
  }
}

TEST(GltfLoaderErrors, GarbageBytes) {
  test::TempDir dir;
  std::mt19937 rng(7);
  std::string noise(4096, '\0');
  for (char& c : noise) c = static_cast<char>(rng() & 0xFF);
  std::string msg = load_error_of([&] { load_skinned_model(dir.write("noise.glb", noise)); });
  EXPECT_NE(msg.find("not a glTF file"), std::string::npos) << msg;
  // The right magic, then noise.
  msg = load_error_of([&] { load_static_model(dir.write("magic.glb", "glTF" + noise)); });
  EXPECT_NE(msg.find("malformed glTF"), std::string::npos) << msg;
  msg = load_error_of([&] { load_static_model(dir.write("bad.gltf", "{ \"asset\": { \"version\": ")); });
  EXPECT_NE(msg.find("malformed glTF"), std::string::npos) << msg;
}

TEST(GltfLoaderErrors, StaticFileHasNoSkin) {
  const std::string path = test::data_file("models/environment/OcclusionRoom.glb");
  const std::string msg = load_error_of([&] { load_skinned_model(path); });
  EXPECT_NE(msg.find(path + ": has no skin"), std::string::npos) << msg;
}

// Found by fuzz_gltf_json (tests/fuzz/corpus/gltf_json/regression-degenerate): one mutated
// byte turned the POSITION accessor's "bufferView" key into "bunferView", so every vertex read
// as (0, 0, 0) (an accessor without a buffer view holds zeros). Welding merged them and dropped
// every triangle, and the loader returned a model without triangles or vertices instead of
// its "no triangle mesh" error. This is that file cut down to the accessor.
TEST(GltfLoaderErrors, MeshWhoseTrianglesAllCollapse) {
  test::TempDir dir;
  const std::string path = dir.write("zeros.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
    "nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"componentType":5126,"count":6,"type":"VEC3"}]})");
  const std::string msg = load_error_of([&] { load_static_model(path); });
  EXPECT_NE(msg.find("has no triangle mesh"), std::string::npos) << msg;
  LoadOptions unwelded;
  unwelded.weld = false;  // without welding the file's two (degenerate) triangles stay
  EXPECT_EQ(load_static_model(path, unwelded).triangle_count(), 2u);
}

TEST(GltfLoaderErrors, FileWithoutMesh) {
  test::TempDir dir;
  const std::string path = dir.write("empty.gltf", R"({"asset":{"version":"2.0"},"nodes":[{"name":"a"}]})");
  const std::string msg = load_error_of([&] { load_static_model(path); });
  EXPECT_NE(msg.find("has no triangle mesh"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tourmap::crowd
